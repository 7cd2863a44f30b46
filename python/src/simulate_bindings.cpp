// stickslip.simulate(), simulate_many() and Realization.trajectory(): one
// realization replayed exactly (replay.hpp, io::replay_uncertain with laws),
// read from keyword arguments as `simulate` reads its flags.
#include <pybind11/stl.h>

#include <cstring>
#include <optional>
#include <type_traits>

#include "bindings.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/uncertain_replay.hpp"
#include "stickslip/record_schema.hpp"
#include "stickslip/replay.hpp"
#include "stickslip/run/runner.hpp"
#include "stickslip/trajectory.hpp"

namespace stickslip::python {
namespace {

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

}  // namespace

void register_simulate(py::module_& m) {
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
  m.def("replay_many", &replay_many_py, py::arg("parameters"), py::arg("seed"),
        py::arg("realizations"), py::arg("x0"), py::arg("xdot0"), py::arg("belt_start"),
        py::arg("switch_times"), py::arg("switch_levels"), py::arg("max_events"),
        py::arg("common_random_numbers"), py::arg("threads"));
  m.def("sample_trajectory", &sample_trajectory_py, py::arg("segments"), py::arg("dt"));
}

}  // namespace stickslip::python
