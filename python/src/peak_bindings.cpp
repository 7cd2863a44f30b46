// stickslip.peak(): the CLI's `peak` (precision/peak_sweep.hpp), its sweeps
// run on a worker thread that Ctrl-C stops.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "stickslip/precision/peak_sweep.hpp"
#include "stickslip/run/runner.hpp"

namespace stickslip::python {
namespace {

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

void register_peak(py::module_& m) {
  m.def("peak", &peak_py, py::arg("model"), py::arg("over"), py::arg("statistic"), py::arg("lo"),
        py::arg("hi"), py::arg("target_halfwidth"), py::arg("method"), py::arg("seed"),
        py::arg("threads"), py::arg("initial_realizations"), py::arg("max_realizations"),
        py::arg("max_events"));
}

}  // namespace stickslip::python
