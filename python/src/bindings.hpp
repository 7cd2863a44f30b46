// What the binding files of the _stickslip module share
// (python/src/*_bindings.cpp, module.cpp): the model read from keyword
// arguments as the CLI reads its flags, and the worker thread that keeps
// Ctrl-C and the progress callback alive while the library runs.
#pragma once
#include <pybind11/pybind11.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "stickslip/parameters.hpp"
#include "stickslip/run/stop.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"

namespace stickslip::python {

namespace py = pybind11;

// Numbers as the CLI reads them: fmt "{}" is the shortest text that reads
// back to the same double, so the CLI's parsers (and their messages) apply.
[[nodiscard]] std::string list_text(const std::vector<double>& values);

// The model from stickslip's keyword arguments, applied as the CLI applies
// its flags (apps/stickslip/model_flags.cpp): the belt (levels, rates,
// generator) first, then the scalars in the order given with mu first, so
// that mu sets mu_s and mu_k both and a later mu_s / mu_k / vI / rI refines.
//   model: {symbol: value} in the order given, plus "belt_levels",
//   "belt_rates": [values] and "belt_generator": [[row]].
// A value that is text is a law (parse_law, with the CLI's messages), put in
// `laws` in io::sort_laws' order; without `laws`, one is refused (`refusal`).
[[nodiscard]] model_parameters parameters_from(const py::dict& model, model_parameters p = {},
                                               std::vector<uncertain_parameter>* laws = nullptr,
                                               const char* refusal = "");

// The model as the CLI records it (simulate --format json "parameters",
// io/output/json_emitter.cpp): every recorded scalar resolved, the belt
// levels, the generator (rows), and for two levels the rates r1, r2.
[[nodiscard]] py::dict model_dict(const model_parameters& p);

// "+1", "-1", "stationary" or a level number, read as --belt-start is.
[[nodiscard]] int belt_start_from(const std::string& text, const model_parameters& p);

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

// The functions of each binding file, registered by PYBIND11_MODULE (module.cpp).
void register_simulate(py::module_& m);  // simulate_bindings.cpp: replay, replay_many, ...
void register_sweep(py::module_& m);     // sweep_bindings.cpp: run_sweep
void register_peak(py::module_& m);      // peak_bindings.cpp: peak
void register_sobol(py::module_& m);     // sobol_bindings.cpp: sobol_indices

}  // namespace stickslip::python
