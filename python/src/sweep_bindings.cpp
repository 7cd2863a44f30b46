// stickslip.sweep() and stickslip.sensitivity(): a sweep read from keyword
// arguments with the CLI's rules and messages, run through the run layer
// (journal, resume, stop token) on a worker thread, its outputs written.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <optional>

#include "bindings.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/output_lock.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/run/result_memory.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"

namespace stickslip::python {
namespace {

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
                  std::optional<std::size_t> survival_bins, double burn_in,
                  const py::object& observe_times) {
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
  if (survival_bins) {
    if (!spec.statistics.survival)
      throw invalid_value("survival_bins", std::to_string(*survival_bins),
                          "only with the survival statistics (statistics=\"survival\" or \"all\")");
    spec.survival.bins = *survival_bins;
  }
  spec.burn_in = burn_in;  // the CLI's --burn-in (validate() checks 0 <= T < t_a)
  spec.observe_times = observe_times_from(observe_times);  // the CLI's --observe-times
  resolve_survival_grid(spec);
  validate(spec);
  // Refused before anything is allocated, with or without an output folder
  // (run_journaled checks it too; the in-memory path below does not go
  // there), with what the run will hold: an output folder's run goes window
  // by window through a large grid, the in-memory one holds every point.
  run::thread_runner runner(threads);
  run::check_result_memory(
      spec, threads, output.empty() ? 0 : run::memory_window(spec, run::run_plan{}, runner));
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
                            fmt::format("pass overwrite=True to replace them, resume=True to "
                                        "continue an interrupted {}, or choose another output "
                                        "folder",
                                        design.is_none() ? "sweep" : "study"));
    else if (!io::journal_exists(output))
      already_complete = run::finished_outputs_of(spec, output).has_value();
  }
  if (already_complete) {
    // An unmet target, as the finished outputs record it (the CLI's --resume
    // says it again too).
    if (!is_sensitivity(spec))
      if (const auto note = io::read_finished_warning(output); !note.empty())
        if (PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 2) != 0) throw py::error_already_set();
    return {};
  }
  io::run_metadata meta = io::make_metadata(0, nullptr, io::to_toml(spec));
  meta.command_line = command_line;
  run::stop_token stop;
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
  std::vector<std::string> removed;
  {
    py::gil_scoped_release release;
    if (!output.empty())
      removed = run::write_outputs(outcome, output, keep_journal);
    else if (!is_sensitivity(spec))
      io::write_netcdf(*outcome.results, meta, netcdf_path);
  }
  // overwrite=True: name the earlier run's outputs that this one does not
  // write and removed (the CLI's note; records.csv without records=True).
  if (const auto note = io::removed_outputs_note(removed); !note.empty())
    if (PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 2) != 0) throw py::error_already_set();
  // an unreachable --target-ci (target_halfwidth=...), as the CLI warns of it
  if (const auto note = unmet_target_note(*outcome.results); !note.empty())
    if (PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 2) != 0) throw py::error_already_set();
  py::gil_scoped_release release;
  return is_sensitivity(spec) ? io::sensitivity_json(*outcome.results) : std::string();
}

}  // namespace

void register_sweep(py::module_& m) {
  m.def("run_sweep", &run_sweep_py, py::arg("base"), py::arg("axes"), py::arg("realizations"),
        py::arg("seed"), py::arg("block_size"), py::arg("bins"), py::arg("records"),
        py::arg("engine"), py::arg("max_events"), py::arg("threads"), py::arg("output"),
        py::arg("resume"), py::arg("keep_journal"), py::arg("checkpoint_interval"),
        py::arg("netcdf_path"),
        py::arg("command_line"), py::arg("progress"), py::arg("belt_start") = py::none(),
        py::arg("common_random_numbers") = false, py::arg("target_ci") = "",
        py::arg("min_realizations") = 1000, py::arg("overwrite") = false,
        py::arg("design") = py::none(), py::arg("statistics") = std::vector<std::string>{},
        py::arg("survival_bins") = py::none(), py::arg("burn_in") = 0.0,
        py::arg("observe_times") = py::none());
}

}  // namespace stickslip::python
