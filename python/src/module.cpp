// The pybind11 extension behind the stickslip Python package: a thin layer
// over the library. replay() for stickslip.simulate(), run_sweep() for
// stickslip.sweep() through the run layer (journal, resume, stop token), with
// the GIL released while simulating; Ctrl-C requests a stop. The pure-Python
// package (python/stickslip) turns the results into pandas and xarray.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstring>
#include <mutex>
#include <optional>
#include <thread>
#include <type_traits>

#include "stickslip/run/result_memory.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "stickslip/error.hpp"
#include "stickslip/estimates.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/uncertain_replay.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/output_lock.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/precision/peak_sweep.hpp"
#include "stickslip/record_schema.hpp"
#include "stickslip/replay.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/trajectory.hpp"
#include "stickslip/version.hpp"

namespace py = pybind11;
using namespace stickslip;

namespace stickslip {
void register_sobol(py::module_& m);  // sobol_bindings.cpp
}

namespace {

// Numbers as the CLI reads them: fmt "{}" is the shortest text that reads
// back to the same double, so the CLI's parsers (and their messages) apply.
std::string list_text(const std::vector<double>& values) {
  return fmt::format("{}", fmt::join(values, ","));
}

// The model from stickslip's keyword arguments, applied as the CLI applies
// its flags (apps/stickslip/model_flags.cpp): the belt (levels, rates,
// generator) first, then the scalars in the order given with mu first, so
// that mu sets mu_s and mu_k both and a later mu_s / mu_k / vI / rI refines.
//   model: {symbol: value} in the order given, plus "belt_levels",
//   "belt_rates": [values] and "belt_generator": [[row]].
// A value that is text is a law (parse_law, with the CLI's messages), put in
// `laws` in io::sort_laws' order; without `laws`, one is refused (`refusal`).
model_parameters parameters_from(const py::dict& model, model_parameters p = {},
                                 std::vector<uncertain_parameter>* laws = nullptr,
                                 const char* refusal = "") {
  if (model.contains("belt_levels") && !model["belt_levels"].is_none())
    p.belt_levels =
        io::parse_belt_levels(list_text(py::cast<std::vector<double>>(model["belt_levels"])));
  if (model.contains("belt_rates") && !model["belt_rates"].is_none())
    p.belt_rates = io::parse_value_list("--belt-rates",
                                        list_text(py::cast<std::vector<double>>(model["belt_rates"])));
  if (model.contains("belt_generator") && !model["belt_generator"].is_none()) {
    const auto rows = py::cast<std::vector<std::vector<double>>>(model["belt_generator"]);
    if (rows.empty())
      throw invalid_value("--belt-generator", "", "a square matrix: 0 rows need 0 rates each");
    std::string text;
    for (std::size_t i = 0; i < rows.size(); ++i) text += (i ? ";" : "") + list_text(rows[i]);
    p.belt_generator = io::parse_belt_generator(text);
  }
  std::vector<parameter_assignment> scalars;
  for (const auto& [key, value] : model) {
    auto sym = py::cast<std::string>(key);
    if (sym == "belt_levels" || sym == "belt_rates" || sym == "belt_generator") continue;
    if (py::isinstance<py::str>(value)) {
      const auto text = py::cast<std::string>(value);
      if (!laws) throw invalid_value(flag_of(sym), text, refusal);
      laws->push_back({sym, parse_law(text, flag_of(sym))});
      continue;
    }
    scalars.push_back({std::move(sym), py::cast<double>(value)});
  }
  if (laws) io::sort_laws(*laws);
  return assign(std::move(p), std::move(scalars));
}

// The model as the CLI records it (simulate --format json "parameters",
// io/output/json_emitter.cpp): every recorded scalar resolved, the belt
// levels, the generator (rows), and for two levels the rates r1, r2.
py::dict model_dict(const model_parameters& p) {
  py::dict d;
  for (const char* sym : recorded_parameter_names) d[sym] = parameter_value(p, sym);
  const auto levels = p.levels();
  const auto q = p.generator();
  const std::size_t n = levels.size();
  d["belt_levels"] = levels;
  py::list rows;
  for (std::size_t i = 0; i < n; ++i)
    rows.append(std::vector<double>(q.begin() + static_cast<std::ptrdiff_t>(i * n),
                                    q.begin() + static_cast<std::ptrdiff_t>((i + 1) * n)));
  d["belt_generator"] = rows;
  if (n == 2) d["belt_rates"] = std::vector<double>{q[1], q[2]};
  return d;
}

// "+1", "-1", "stationary" or a level number, read as --belt-start is.
int belt_start_from(const std::string& text, const model_parameters& p) {
  return io::parse_belt_start("--belt-start", text, p.levels().size());
}

// The closed-form pieces of one realization, kept whole as the library's
// `segment` structs: Python holds them opaquely and hands them back to the
// sampler, so no field (decay_rate was once dropped by a copy into tuples)
// can be lost on the way.
struct trace_segments {
  std::vector<segment> items;
};

// The replay of stickslip.simulate() (and of each of simulate_many()'s
// realizations) from its keyword arguments, read as `simulate` reads its flags.
// With laws (text values), `laws` holds them and the request is realization
// R of the point with those laws (io::replay_uncertain), R required; its
// inputs are then drawn, not fixed, and belt_start is the sweep's.
replay_request request_from(const py::dict& model, std::uint64_t seed, std::optional<std::uint64_t> realization,
                   std::optional<double> x0, std::optional<double> xdot0,
                   std::optional<std::string> belt_start, std::optional<std::vector<double>> switch_times,
                   std::optional<std::vector<std::int64_t>> switch_levels, std::int64_t max_events,
                   bool common_random_numbers, std::vector<uncertain_parameter>& laws) {
  replay_request r;
  r.common_random_numbers = common_random_numbers;
  r.parameters = parameters_from(model, {}, &laws);
  r.seed = seed;
  r.realization = realization.value_or(0);
  r.max_events = max_events;
  if (!laws.empty()) {
    if (!realization) throw io::realization_required(laws);
    if (x0) throw io::fixed_input_with_laws("--x0", fmt::format("{}", *x0), laws);
    if (xdot0) throw io::fixed_input_with_laws("--xdot0", fmt::format("{}", *xdot0), laws);
    if (switch_times) throw io::fixed_input_with_laws("--switch-times", list_text(*switch_times), laws);
    if (switch_levels)
      throw io::fixed_input_with_laws("switch_levels", fmt::format("{}", fmt::join(*switch_levels, ",")), laws);
    if (belt_start) r.initial.belt_start = belt_start_from(*belt_start, r.parameters);
    return r;
  }
  r.x0 = x0;
  r.xdot0 = xdot0;
  if (belt_start)
    if (const int b = belt_start_from(*belt_start, r.parameters); b != 0) r.belt_start = b;
  if (switch_levels && !switch_times)
    throw invalid_value("switch_levels", fmt::format("{} levels", switch_levels->size()),
                        "only together with switch_times");
  if (switch_times && !switch_levels) {
    r.switch_times = io::parse_switch_time_list("--switch-times", list_text(*switch_times));
  } else if (switch_times) {
    // One `t level` line per switch, read as --switch-times-file reads them.
    if (switch_levels->size() != switch_times->size())
      throw invalid_value("switch_levels", fmt::format("{} levels", switch_levels->size()),
                          fmt::format("one level (1..n) per switch time: {}", switch_times->size()));
    std::string text;
    for (std::size_t i = 0; i < switch_times->size(); ++i)
      text += fmt::format("{} {}\n", (*switch_times)[i], (*switch_levels)[i]);
    auto schedule = io::parse_switch_schedule(text, "switch_times", r.parameters.levels().size());
    r.switch_times = std::move(schedule.times);
    if (!schedule.levels.empty()) r.switch_levels = std::move(schedule.levels);
  }
  return r;
}

py::tuple episode_row(const episode& e) {
  return py::make_tuple(to_string(e.kind), e.start, e.end, e.position_at_start, e.belt_velocity,
                        e.censored);
}

// One realization: replay(), or with laws io::replay_uncertain (the CLI's
// simulate --realization R), whose drawn values are returned too.
io::realization_report report_of(const replay_request& r,
                                 const std::vector<uncertain_parameter>& laws) {
  if (!laws.empty()) return io::replay_uncertain(r, laws);
  return {r, replay(r), {}, {}};
}

py::dict replay_py(const py::dict& model, std::uint64_t seed, std::optional<std::uint64_t> realization,
                   std::optional<double> x0, std::optional<double> xdot0,
                   std::optional<std::string> belt_start, std::optional<std::vector<double>> switch_times,
                   std::optional<std::vector<std::int64_t>> switch_levels, std::int64_t max_events,
                   bool common_random_numbers, double burn_in) {
  std::vector<uncertain_parameter> laws;
  replay_request asked = request_from(model, seed, realization, x0, xdot0, belt_start,
                                      switch_times, switch_levels, max_events,
                                      common_random_numbers, laws);
  asked.burn_in = burn_in;  // 0 <= T < t_a: replay() and replay_uncertain() check it
  io::realization_report report;
  {
    py::gil_scoped_release release;
    report = report_of(asked, laws);
  }
  const replay_request& r = report.request;
  realization_trace& t = report.trace;
  py::list episodes, events;
  for (const auto& e : t.episodes) episodes.append(episode_row(e));
  for (const auto& e : t.events)
    events.append(py::make_tuple(to_string(e.kind), e.time, e.position, e.velocity, e.belt_velocity));
  py::dict out;
  out["episodes"] = episodes;
  out["events"] = events;
  out["segments"] = trace_segments{std::move(t.segments)};
  out["x0"] = t.initial.position;
  out["xdot0"] = t.initial.velocity;
  out["belt_start"] = t.initial.belt_direction;
  out["parameters"] = model_dict(r.parameters);
  py::dict law_texts, drawn;
  for (std::size_t i = 0; i < report.uncertain.size(); ++i) {
    law_texts[py::str(report.uncertain[i].symbol)] = to_string(report.uncertain[i].law);
    drawn[py::str(report.uncertain[i].symbol)] = report.drawn[i];
  }
  out["laws"] = law_texts;
  out["drawn"] = drawn;
  // The record's outcome fields (record_schema.hpp), -1 marking no first stick.
  py::dict record;
  for_each_record_field(record_role::outcome, [&](const record_field& field) {
    visit_field(field, t.record, [&](const auto& v) { record[field.name] = v; });
  });
  out["record"] = record;
  return out;
}

// x, x', v every dt and at both ends of every closed-form piece: the one
// trajectory sampler (trajectory.hpp), as `simulate --trajectory` uses it.
py::list sample_trajectory_py(const trace_segments& segments, double dt) {
  py::list out;
  for (const auto& p : sample_trajectory(segments.items, dt))
    out.append(py::make_tuple(p.time, p.position, p.velocity, p.belt_velocity));
  return out;
}

// Runs `work` on a thread of its own while this thread, holding the GIL only
// briefly, checks for Ctrl-C (then requests a stop and waits for the units in
// flight) and reports progress. Returns whether it was interrupted; the
// KeyboardInterrupt stays pending for the caller to raise.
template <class Work>
bool run_interruptibly(Work&& work, run::stop_token& stop, const py::object& progress,
                       const std::atomic<std::uint64_t>& done, const std::atomic<std::uint64_t>& total) {
  std::mutex mu;
  std::condition_variable cv;
  bool finished = false;
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard lock(mu);
    finished = true;
    cv.notify_all();
  });
  bool interrupted = false;
  PyObject *type = nullptr, *value = nullptr, *trace = nullptr;
  while (true) {
    {
      py::gil_scoped_release release;
      std::unique_lock lock(mu);
      cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return finished; });
      if (finished) break;
    }
    if (interrupted) continue;
    // A pending Python exception -- Ctrl-C, or one the progress callback
    // raised (KeyboardInterrupt may land inside tqdm) -- stops the sweep: it
    // is kept, no unit starts any more, and it is raised once the worker has
    // finished the units in flight (never while the worker runs: a joinable
    // std::thread must not be destroyed).
    bool pending = PyErr_CheckSignals() != 0;
    if (!pending && !progress.is_none()) {
      try {
        progress(done.load(), total.load());
      } catch (py::error_already_set& e) {
        e.restore();
        pending = true;
      }
    }
    if (pending) {
      PyErr_Fetch(&type, &value, &trace);
      interrupted = true;
      stop.request(SIGINT);
    }
  }
  worker.join();
  if (interrupted) {
    PyErr_Restore(type, value, trace);
    return true;
  }
  if (failure) std::rethrow_exception(failure);
  if (!progress.is_none()) progress(done.load(), total.load());
  return false;
}

// stickslip.simulate_many(): replay() of each of `realizations` with the same
// arguments, on `threads` worker threads (0 = all cores) without the GIL.
// Each realization is computed alone, exactly as simulate() computes it, so
// the rows (in the order of `realizations`, each episode row led by its
// realization index) do not depend on the thread count. Ctrl-C starts no
// further realization and raises KeyboardInterrupt.
py::list replay_many_py(const py::dict& model, std::uint64_t seed,
                        const std::vector<std::uint64_t>& realizations, std::optional<double> x0,
                        std::optional<double> xdot0, std::optional<std::string> belt_start,
                        std::optional<std::vector<double>> switch_times,
                        std::optional<std::vector<std::int64_t>> switch_levels,
                        std::int64_t max_events, bool common_random_numbers, unsigned threads) {
  std::vector<uncertain_parameter> laws;
  // With laws every index is given: realization r of the point, as simulate() draws it.
  replay_request base = request_from(model, seed, std::uint64_t{0}, x0, xdot0, belt_start,
                                     switch_times, switch_levels, max_events, common_random_numbers,
                                     laws);
  base.keep_events = false;
  base.keep_segments = false;
  const std::size_t n = realizations.size();
  std::vector<std::vector<episode>> episodes(n);
  run::stop_token stop;
  std::atomic<std::uint64_t> done{0}, total{n};
  const bool interrupted = run_interruptibly(
      [&] {
        std::atomic<std::size_t> next{0};
        std::mutex failure_mutex;
        std::exception_ptr failure;
        auto work = [&] {
          while (true) {
            const std::size_t i = next.fetch_add(1);
            if (i >= n || stop.requested()) return;
            try {
              replay_request r = base;
              r.realization = realizations[i];
              episodes[i] = report_of(r, laws).trace.episodes;
              done.fetch_add(1);
            } catch (...) {
              std::lock_guard lock(failure_mutex);
              if (!failure) failure = std::current_exception();
              stop.request(SIGINT);  // no further realization starts
              return;
            }
          }
        };
        const auto count =
            static_cast<std::size_t>(std::min<std::uint64_t>(run::resolve_threads(threads), n));
        std::vector<std::thread> pool;
        for (std::size_t t = 1; t < count; ++t) pool.emplace_back(work);
        work();
        for (auto& t : pool) t.join();
        if (failure) std::rethrow_exception(failure);
      },
      stop, py::none(), done, total);
  if (interrupted) throw py::error_already_set();
  py::list rows;
  for (std::size_t i = 0; i < n; ++i)
    for (const auto& e : episodes[i])
      rows.append(py::make_tuple(realizations[i], to_string(e.kind), e.start, e.end,
                                 e.position_at_start, e.belt_velocity, e.censored));
  return rows;
}

sweep_spec spec_from(const py::dict& base, const std::vector<std::pair<std::string, std::vector<double>>>& axes,
                     std::uint64_t realizations, std::uint64_t seed, std::uint64_t block_size,
                     std::size_t bins, bool records, const std::string& engine,
                     std::int64_t max_events, const std::optional<std::string>& belt_start) {
  sweep_spec s;
  std::vector<uncertain_parameter> laws;
  s.base = parameters_from(base, {}, &laws);
  // An axis of a scalar that has a CLI flag is read as that flag's grid
  // ("--c 0.5,2"), with its checks and messages; a belt level vI or rate rI
  // (a TOML [grid] key only) is checked by validate().
  for (const auto& [name, values] : axes) {
    const std::string sym = canonical_symbol(name);
    const bool flag = std::find(std::begin(recorded_parameter_names), std::end(recorded_parameter_names),
                                sym) != std::end(recorded_parameter_names);
    s.axes.push_back(axis{sym, flag ? io::parse_grid(flag_of(sym), list_text(values), io::grid_domain_of(sym)) : values});
  }
  io::order_added_axes(s.axes);  // the command line's axis order
  for (auto& u : laws) io::set_law(s, u.symbol, std::move(u.law));
  s.realizations = realizations;
  s.seed = seed;
  s.block_size = block_size;
  s.histograms.bins = bins;
  s.keep_records = records;
  s.engine = io::parse_engine("engine", engine);
  s.max_events = max_events;
  if (belt_start) s.initial.belt_start = belt_start_from(*belt_start, s.base);
  validate(s);
  return s;
}

// observe_times=: None (none), a grid's text ("lin:0:50:501") or a list of
// times (the Python layer checked them as numbers), read by the CLI's parser
// of --observe-times: its forms, its checks and its messages.
std::vector<double> observe_times_from(const py::object& times) {
  if (times.is_none()) return {};
  const std::string text = py::isinstance<py::str>(times)
                               ? times.cast<std::string>()
                               : list_text(times.cast<std::vector<double>>());
  return io::parse_grid("observe_times", text, io::grid_domain::non_negative);
}

// Runs the sweep and writes results.nc to `netcdf_path` (and, with an output
// directory, every output file there through the run layer: journal,
// resume). Raises KeyboardInterrupt when interrupted (the journal of an
// output directory then holds every finished unit).
std::string run_sweep_py(const py::dict& base, const std::vector<std::pair<std::string, std::vector<double>>>& axes,
                  std::uint64_t realizations, std::uint64_t seed, std::uint64_t block_size,
                  std::size_t bins, bool records, const std::string& engine, std::int64_t max_events,
                  unsigned threads, const std::string& output, bool resume, bool keep_journal,
                  double checkpoint_interval, const std::string& netcdf_path, const std::string& command_line,
                  const py::object& progress, const std::optional<std::string>& belt_start,
                  bool common_random_numbers, const std::string& target_ci,
                  std::uint64_t min_realizations, bool overwrite,
                  const py::object& design, const std::vector<std::string>& statistics,
                  std::size_t survival_bins, double burn_in, const py::object& observe_times) {
  sweep_spec spec =
      spec_from(base, axes, realizations, seed, block_size, bins, records, engine, max_events,
                belt_start);
  // stickslip.sensitivity(): the CLI's `sensitivity`, a one-point sweep of
  // design rows (uncertainty/sensitivity_design.hpp) with the CLI's rules
  // (set_sensitivity_design); returns its JSON.
  if (!design.is_none()) {
    const auto d = design.cast<py::dict>();
    sensitivity_choice c;
    c.statistic = d["statistic"].cast<std::string>();
    auto rows = [&](const char* key) -> std::optional<std::uint64_t> {
      return d[key].is_none() ? std::nullopt : std::optional(d[key].cast<std::uint64_t>());
    };
    c.samples = rows("samples");
    c.max_samples = rows("max_samples");
    c.min_samples = rows("min_samples");
    c.block_size = rows("block_size");
    if (!d["target_halfwidth"].is_none()) c.target_halfwidth = d["target_halfwidth"].cast<double>();
    set_sensitivity_design(spec, c);
  }
  // Precision: common random numbers, adaptive sampling (realizations is then the cap).
  spec.common_random_numbers = common_random_numbers;
  if (!target_ci.empty()) {
    io::parse_target_ci("target_ci", target_ci, spec);
    spec.min_realizations = min_realizations;
  }
  // The CLI's --statistics and --survival-bins (their checks and messages).
  spec.statistics = parse_statistics_selection("statistics", statistics);
  apply_statistics_selection(spec);
  spec.survival.bins = survival_bins;
  spec.burn_in = burn_in;  // the CLI's --burn-in (validate() checks 0 <= T < t_a)
  spec.observe_times = observe_times_from(observe_times);  // the CLI's --observe-times
  resolve_survival_grid(spec);
  validate(spec);
  // Refused before anything is allocated, with or without an output folder
  // (run_journaled checks it too; the in-memory path below does not go there).
  run::check_result_memory(spec, threads);
  if (!(checkpoint_interval >= 0) || checkpoint_interval > 86400)
    throw invalid_parameter("checkpoint_interval", checkpoint_interval, "0 .. 86400 seconds");
  // The command line's rule for an output directory (stickslip sweep -o DIR,
  // with the same checks of the library): without resume or overwrite,
  // finished results there are never replaced; a resume into DIR without a
  // journal continues nothing: its finished outputs must be this
  // configuration's (then nothing runs and they are read back as they are).
  // One writer of the folder until its outputs are written
  // (io/output_lock.hpp): a second writer, CLI or Python, is refused.
  auto before = run::directory_state::of(output);
  std::optional<io::output_lock> lock;
  if (!output.empty()) {
    lock.emplace(output, is_sensitivity(spec) ? "stickslip.sensitivity (Python)"
                                              : "stickslip.sweep (Python)");
    before.journal_existed = io::journal_exists(output);  // under the lock
  }
  bool already_complete = false;
  if (!output.empty() && !overwrite) {
    if (!resume)
      io::refuse_to_replace(io::existing_sweep_results(output), "the results of an earlier run",
                            "pass overwrite=True to replace them, resume=True to continue an "
                            "interrupted sweep, or choose another output folder");
    else if (!io::journal_exists(output))
      already_complete = run::finished_outputs_of(spec, output).has_value();
  }
  if (already_complete) return {};
  io::run_metadata meta = io::make_metadata(0, nullptr, io::to_toml(spec));
  meta.command_line = command_line;
  run::stop_token stop;
  run::thread_runner runner(threads);
  std::atomic<std::uint64_t> done{0}, total{unit_count(spec)};
  auto count = [&](std::uint64_t d, std::uint64_t t) {
    done.store(d);
    total.store(t);
  };
  // Simulation on a worker thread; the NetCDF writes stay on this thread:
  // HDF5 keeps its error-printing switch per thread, and netCDF turns it off
  // only on the first thread that uses it, so files written from a worker
  // would make xarray's later reads on this thread print HDF5 diagnostics.
  run::run_outcome outcome;
  const bool interrupted = run_interruptibly(
      [&] {
        try {
          if (!output.empty()) {
            run::run_plan plan;
            plan.dir = output;
            plan.resume = resume;
            plan.overwrite = overwrite;
            plan.checkpoint_interval = std::chrono::duration<double>(checkpoint_interval);
            plan.stop = &stop;
            plan.progress = [&](std::uint64_t d, std::uint64_t t, double) { count(d, t); };
            outcome = run::run_journaled(spec, plan, meta, runner);
            return;
          }
          ordered_merger merger(spec);
          sweep_hooks hooks;
          hooks.progress = count;
          hooks.wanted = [&](const work_unit&) { return !stop.requested(); };
          const auto t0 = std::chrono::steady_clock::now();
          runner.run(spec, merger, hooks);
          if (stop.requested()) return;
          auto& rs = outcome.results.emplace(make_result_set(spec, std::move(merger)));
          rs.elapsed_seconds =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          rs.threads = runner.threads();
          rs.ranks = static_cast<unsigned>(runner.ranks());
        } catch (const error& e) {
          if (!output.empty()) run::clean_up_after_failure(e, output, before);
          throw;
        }
      },
      stop, progress, done, total);
  if (interrupted) throw py::error_already_set();
  py::gil_scoped_release release;
  if (!output.empty())
    run::write_outputs(outcome, output, keep_journal);
  else if (!is_sensitivity(spec))
    io::write_netcdf(*outcome.results, meta, netcdf_path);
  return is_sensitivity(spec) ? io::sensitivity_json(*outcome.results) : std::string();
}

// Ends a peak search stopped by Ctrl-C (run_interruptibly raises the
// pending KeyboardInterrupt).
struct peak_interrupted {};

// stickslip.peak(): the CLI's `peak` (precision/peak_sweep.hpp), the same
// numbers for the same arguments. It runs on a worker thread without the
// GIL; Ctrl-C starts no further unit and raises KeyboardInterrupt once the
// units in flight are done (a search has nothing to keep: no output).
py::dict peak_py(const py::dict& model, const std::string& over, const std::string& statistic,
                 double lo, double hi, double target, const std::string& method,
                 std::uint64_t seed, unsigned threads, std::uint64_t initial,
                 std::uint64_t budget, std::int64_t max_events) {
  precision::sweep_peak_request q;
  q.spec.base = parameters_from(model, {}, nullptr,
                                 "a number: stickslip.peak() does not take laws; it locates the "
                                 "maximum for one model (give a value), while stickslip.sweep() "
                                 "takes laws and grids together");
  q.spec.seed = seed;
  q.spec.max_events = max_events;
  q.over = canonical_symbol(over);
  q.statistic = &precision::peak_statistic("statistic", statistic);
  q.options.lo = lo;
  q.options.hi = hi;
  q.options.log_scan = lo > 0 && hi / lo >= 4;
  q.options.target_halfwidth = target;
  q.options.initial_realizations = initial;
  q.options.max_total_realizations = budget;
  q.method = precision::peak_method_named("method", method, q);
  run::stop_token stop;
  run::thread_runner runner(threads);
  q.run = [&](const sweep_spec& s) {
    auto rs = run::run_unless_stopped(runner, s, stop);
    if (!rs) throw peak_interrupted{};
    return std::move(*rs);
  };
  precision::peak_result r;
  const auto start = std::chrono::steady_clock::now();
  std::atomic<std::uint64_t> no_count{0};
  const bool interrupted = run_interruptibly(
      [&] {
        try {
          r = precision::find_peak_by_sweeps(q);
        } catch (const peak_interrupted&) {
        }
      },
      stop, py::none(), no_count, no_count);
  if (interrupted) throw py::error_already_set();
  py::dict d;
  d["statistic"] = q.statistic->summary_name;
  d["method"] = precision::to_string(q.method);
  d["over"] = q.over;
  d["range"] = py::make_tuple(lo, hi);
  d["target_halfwidth"] = target;
  d["target_met"] = r.target_met;
  d["argmax"] = r.argmax;
  d["argmax_ci95"] = py::make_tuple(r.argmax_lo, r.argmax_hi);
  d["argmax_sampling_halfwidth"] = r.sampling_halfwidth;
  d["argmax_model_bias"] = r.model_bias;
  d["max"] = r.max;
  d["max_ci95"] = py::make_tuple(r.max_lo, r.max_hi);
  d["realizations"] = r.realizations;
  d["stages"] = r.stages;
  d["window"] = py::make_tuple(r.window_lo, r.window_hi);
  d["seed"] = seed;
  d["elapsed_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return d;
}

}  // namespace

PYBIND11_MODULE(_stickslip, m) {
  m.doc() = "stickslip's compiled core (use the stickslip package, not this module)";
  m.attr("__version__") = stickslip::version;
  m.attr("git_revision") = stickslip::git_revision;
  static py::exception<stickslip::error> error_type(m, "Error", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const stickslip::error& e) {
      py::object err = py::reinterpret_borrow<py::object>(error_type.ptr())(e.what());
      err.attr("exit_code") = static_cast<int>(e.code());
      PyErr_SetObject(error_type.ptr(), err.ptr());
    }
  });
  py::class_<trace_segments>(m, "Segments",
                             "one realization's closed-form pieces (stickslip::segment), whole")
      .def("__len__", [](const trace_segments& s) { return s.items.size(); })
      // Pickled whole, as the structs' bytes (so a Realization goes through
      // pickle, copy.deepcopy and multiprocessing); the state starts with
      // sizeof(segment), and another layout is refused.
      .def(py::pickle(
          [](const trace_segments& s) {
            static_assert(std::is_trivially_copyable_v<segment>);
            std::string state(sizeof(std::uint64_t) + s.items.size() * sizeof(segment), '\0');
            const std::uint64_t size = sizeof(segment);
            std::memcpy(state.data(), &size, sizeof size);
            if (!s.items.empty())
              std::memcpy(state.data() + sizeof size, s.items.data(), s.items.size() * sizeof(segment));
            return py::bytes(state);
          },
          [](const py::bytes& b) {
            const std::string state = b;
            std::uint64_t size = 0;
            if (state.size() >= sizeof size) std::memcpy(&size, state.data(), sizeof size);
            if (state.size() < sizeof size || size != sizeof(segment) ||
                (state.size() - sizeof size) % sizeof(segment) != 0)
              throw error(exit_code::invalid_input,
                          "cannot unpickle the segments of a Realization made by another build "
                          "of stickslip: recompute it with stickslip.simulate()");
            trace_segments s;
            s.items.resize((state.size() - sizeof size) / sizeof(segment));
            if (!s.items.empty())
              std::memcpy(s.items.data(), state.data() + sizeof size, s.items.size() * sizeof(segment));
            return s;
          }));
  m.def("replay", &replay_py, py::arg("parameters"), py::arg("seed"), py::arg("realization"),
        py::arg("x0"), py::arg("xdot0"), py::arg("belt_start"), py::arg("switch_times"),
        py::arg("switch_levels"), py::arg("max_events"), py::arg("common_random_numbers") = false,
        py::arg("burn_in") = 0.0);
  m.def("run_sweep", &run_sweep_py, py::arg("base"), py::arg("axes"), py::arg("realizations"),
        py::arg("seed"), py::arg("block_size"), py::arg("bins"), py::arg("records"),
        py::arg("engine"), py::arg("max_events"), py::arg("threads"), py::arg("output"),
        py::arg("resume"), py::arg("keep_journal"), py::arg("checkpoint_interval"),
        py::arg("netcdf_path"),
        py::arg("command_line"), py::arg("progress"), py::arg("belt_start") = py::none(),
        py::arg("common_random_numbers") = false, py::arg("target_ci") = "",
        py::arg("min_realizations") = 1000, py::arg("overwrite") = false,
        py::arg("design") = py::none(), py::arg("statistics") = std::vector<std::string>{},
        py::arg("survival_bins") = survival_spec{}.bins, py::arg("burn_in") = 0.0,
        py::arg("observe_times") = py::none());
  m.def("replay_many", &replay_many_py, py::arg("parameters"), py::arg("seed"),
        py::arg("realizations"), py::arg("x0"), py::arg("xdot0"), py::arg("belt_start"),
        py::arg("switch_times"), py::arg("switch_levels"), py::arg("max_events"),
        py::arg("common_random_numbers"), py::arg("threads"));
  // The command line's parser of whole numbers, for the Python layer's one
  // coercion of integer arguments (stickslip/_parameters.py): its rule and
  // its message.
  m.def("parse_unsigned",
        [](const std::string& name, const std::string& text, std::uint64_t lo, std::uint64_t hi) {
          return io::parse_unsigned(name, text, lo, hi);
        },
        py::arg("name"), py::arg("text"), py::arg("lo"), py::arg("hi"));
  m.attr("max_realizations") = stickslip::max_realizations;
  m.attr("max_block_size") = stickslip::max_block_size;
  m.attr("max_histogram_bins") = stickslip::max_histogram_bins;
  m.def("sample_trajectory", &sample_trajectory_py, py::arg("segments"), py::arg("dt"));
  m.def("peak", &peak_py, py::arg("model"), py::arg("over"), py::arg("statistic"), py::arg("lo"),
        py::arg("hi"), py::arg("target_halfwidth"), py::arg("method"), py::arg("seed"),
        py::arg("threads"), py::arg("initial_realizations"), py::arg("max_realizations"),
        py::arg("max_events"));
  m.def("resolve_parameters", [](const py::dict& model) { return model_dict(parameters_from(model)); },
        py::arg("model"));
  // The parameter table (parameters.hpp, scalar_parameters): the Python
  // keywords, their defaults and units come from its rows.
  m.def("parameter_table", [] {
    py::list rows;
    const model_parameters defaults;
    for (const auto& row : scalar_parameters) {
      py::dict d;
      d["symbol"] = row.symbol;
      d["long_name"] = row.long_name;
      d["description"] = row.description;
      d["units"] = row.units;
      d["default"] = defaults.*row.field;
      d["unset_means_mu"] = row.domain == parameter_domain::positive_or_unset;
      rows.append(d);
    }
    return rows;
  });
  // How a keyword's text is told to be a law (parameter_law.hpp), as flags and TOML tell it.
  m.def("looks_like_law", [](const std::string& text) { return looks_like_law(text); },
        py::arg("text"));
  m.attr("default_max_events") = stickslip::default_max_events;
  // The estimate table (estimates.hpp): the sweep's Dataset is results.nc,
  // which maps its rows; this lists them for the tests and the docs.
  m.def("estimate_kinds", [] {
    py::list rows;
    for (const auto& row : estimate_kinds()) {
      py::dict d;
      d["name"] = row.name;
      d["variable"] = row.variable;
      d["value_suffix"] = row.value_suffix;
      d["value_member"] = row.value_member;
      static constexpr const char* index_names[] = {"none", "belt_rate", "generator_entry", "axis"};
      d["index"] = index_names[static_cast<int>(row.index)];
      d["extra"] = extra_name(row.extra);
      py::list has;  // (results.nc name, summary.json name) of the quantities that have it
      for (const auto& q : quantities())
        if (row.has(q)) has.append(py::make_tuple(q.name, q.summary_name));
      d["quantities"] = has;
      rows.append(d);
    }
    return rows;
  });
  // The record table (record_schema.hpp): Realization.record maps its
  // outcome rows; this lists every row for the Python layer and the tests.
  m.def("record_fields", [] {
    static constexpr const char* role_names[] = {"identity", "outcome", "internal"};
    py::list rows;
    for (const auto& field : record_table) {
      py::dict d;
      d["name"] = field.name;
      d["symbol"] = field.symbol;
      d["units"] = field.units;
      d["description"] = field.description;
      d["role"] = role_names[static_cast<int>(field.role)];
      rows.append(d);
    }
    return rows;
  });
  stickslip::register_sobol(m);
}
