// The pybind11 extension behind the stickslip Python package: a thin layer
// over the library. replay() for stickslip.simulate(), run_sweep() for
// stickslip.sweep() through the run layer (journal, resume, stop token), with
// the GIL released while simulating; Ctrl-C requests a stop. The pure-Python
// package (python/stickslip) turns the results into pandas and xarray.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <mutex>
#include <thread>

#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/replay.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/trajectory.hpp"
#include "stickslip/version.hpp"

namespace py = pybind11;
using namespace stickslip;

namespace {

model_parameters parameters_from(const py::dict& values) {
  model_parameters p;
  for (const auto& [k, v] : values) parameter_by_name(p, py::cast<std::string>(k)) = py::cast<double>(v);
  return p;
}

py::dict replay_py(const py::dict& params, std::uint64_t seed, std::uint64_t realization,
                   std::optional<double> x0, std::optional<double> xdot0,
                   std::optional<int> belt_start, std::optional<std::vector<double>> switch_times,
                   std::int64_t max_events, bool common_random_numbers) {
  replay_request r;
  r.common_random_numbers = common_random_numbers;
  r.parameters = parameters_from(params);
  r.seed = seed;
  r.realization = realization;
  r.x0 = x0;
  r.xdot0 = xdot0;
  if (belt_start && *belt_start != 1 && *belt_start != -1)
    throw invalid_value("belt_start", std::to_string(*belt_start), "+1, -1 or None (random)");
  r.belt_start = belt_start;
  r.switch_times = std::move(switch_times);
  r.max_events = max_events;
  realization_trace t;
  {
    py::gil_scoped_release release;
    t = replay(r);
  }
  py::list episodes, events, segments;
  for (const auto& e : t.episodes)
    episodes.append(py::make_tuple(to_string(e.kind), e.start, e.end, e.position_at_start,
                                   e.belt_velocity, e.censored));
  for (const auto& e : t.events)
    events.append(py::make_tuple(to_string(e.kind), e.time, e.position, e.velocity, e.belt_velocity));
  for (const auto& s : t.segments)
    segments.append(py::make_tuple(to_string(s.kind), s.start, s.end, s.position, s.velocity,
                                   s.belt_velocity, s.center, s.omega));
  py::dict out;
  out["episodes"] = episodes;
  out["events"] = events;
  out["segments"] = segments;
  out["x0"] = t.initial.position;
  out["xdot0"] = t.initial.velocity;
  out["belt_start"] = t.initial.belt_direction;
  const auto& rec = t.record;
  py::dict record;
  record["S_T"] = rec.sticks;
  record["S_L"] = rec.slips;
  record["R"] = rec.stick_fraction;
  record["first_stick_start"] = rec.first_stick_start;
  record["first_stick_duration"] = rec.first_stick_duration;
  record["first_stick_censored"] = rec.first_stick_censored;
  record["belt_switches"] = rec.events.belt_switches;
  record["stick_onsets"] = rec.events.stick_onsets;
  record["stick_breaks"] = rec.events.stick_breaks;
  record["slip_reversals"] = rec.events.slip_reversals;
  out["record"] = record;
  return out;
}

// x, x', v every dt and at both ends of every closed-form piece: the one
// trajectory sampler (trajectory.hpp), as `simulate --trajectory` uses it.
// `rows` holds replay()'s segment tuples.
py::list sample_trajectory_py(const py::list& rows, double dt) {
  std::vector<segment> segments;
  segments.reserve(rows.size());
  for (const auto& row : rows) {
    const auto r = py::cast<py::tuple>(row);
    segments.push_back(segment{py::cast<std::string>(r[0]) == "stick" ? mode::stick : mode::slip,
                               py::cast<double>(r[1]), py::cast<double>(r[2]),
                               py::cast<double>(r[3]), py::cast<double>(r[4]),
                               py::cast<double>(r[5]), py::cast<double>(r[6]),
                               py::cast<double>(r[7])});
  }
  py::list out;
  for (const auto& p : sample_trajectory(segments, dt))
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

sweep_spec spec_from(const py::dict& base, const std::vector<std::pair<std::string, std::vector<double>>>& axes,
                     std::uint64_t realizations, std::uint64_t seed, std::uint64_t block_size,
                     std::size_t bins, bool records, const std::string& engine,
                     std::int64_t max_events) {
  sweep_spec s;
  s.base = parameters_from(base);
  for (const auto& [name, values] : axes) s.axes.push_back(axis{name, values});
  s.realizations = realizations;
  s.seed = seed;
  s.block_size = block_size;
  s.histograms.bins = bins;
  s.keep_records = records;
  s.engine = io::parse_engine("engine", engine);
  s.max_events = max_events;
  validate(s);
  return s;
}

// Runs the sweep and writes results.nc to `netcdf_path` (and, with an output
// directory, every output file there through the run layer: journal,
// resume). Raises KeyboardInterrupt when interrupted (the journal of an
// output directory then holds every finished unit).
void run_sweep_py(const py::dict& base, const std::vector<std::pair<std::string, std::vector<double>>>& axes,
                  std::uint64_t realizations, std::uint64_t seed, std::uint64_t block_size,
                  std::size_t bins, bool records, const std::string& engine, std::int64_t max_events,
                  unsigned threads, const std::string& output, bool resume, bool keep_journal,
                  double checkpoint_interval, const std::string& netcdf_path, const std::string& command_line,
                  const py::object& progress, bool common_random_numbers,
                  const std::string& target_ci, std::uint64_t min_realizations) {
  sweep_spec spec =
      spec_from(base, axes, realizations, seed, block_size, bins, records, engine, max_events);
  // Issue 13: common random numbers, adaptive sampling (realizations is then the cap).
  spec.common_random_numbers = common_random_numbers;
  if (!target_ci.empty()) {
    io::parse_target_ci("target_ci", target_ci, spec);
    spec.min_realizations = min_realizations;
  }
  validate(spec);
  if (!(checkpoint_interval >= 0) || checkpoint_interval > 86400)
    throw invalid_parameter("checkpoint_interval", checkpoint_interval, "0 .. 86400 seconds");
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
  const auto before = run::directory_state::of(output);
  const bool interrupted = run_interruptibly(
      [&] {
        try {
          if (!output.empty()) {
            run::run_plan plan;
            plan.dir = output;
            plan.resume = resume;
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
  else
    io::write_netcdf(*outcome.results, meta, netcdf_path);
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
  m.def("replay", &replay_py, py::arg("parameters"), py::arg("seed"), py::arg("realization"),
        py::arg("x0"), py::arg("xdot0"), py::arg("belt_start"), py::arg("switch_times"),
        py::arg("max_events"), py::arg("common_random_numbers") = false);
  m.def("run_sweep", &run_sweep_py, py::arg("base"), py::arg("axes"), py::arg("realizations"),
        py::arg("seed"), py::arg("block_size"), py::arg("bins"), py::arg("records"),
        py::arg("engine"), py::arg("max_events"), py::arg("threads"), py::arg("output"),
        py::arg("resume"), py::arg("keep_journal"), py::arg("checkpoint_interval"),
        py::arg("netcdf_path"),
        py::arg("command_line"), py::arg("progress"), py::arg("common_random_numbers") = false,
        py::arg("target_ci") = "", py::arg("min_realizations") = 1000);
  m.def("sample_trajectory", &sample_trajectory_py, py::arg("segments"), py::arg("dt"));
  m.attr("default_max_events") = stickslip::default_max_events;
}
