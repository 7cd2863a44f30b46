// A realization with uncertain parameters replayed alone (io/uncertain_replay.hpp).
#include "stickslip/io/uncertain_replay.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/uncertain_realization.hpp"

namespace stickslip::io {
namespace {

// The sweep's realization_observer for the record, plus everything simulate
// prints: the initial state (from reset), episodes, events and segments.
struct traced_realization {
  realization_observer stats;
  realization_trace& out;
  bool keep_events, keep_segments;

  void reset(std::uint64_t realization, double x0, double xdot0, int belt) {
    stats.reset(realization, x0, xdot0, belt);
    out.initial = {x0, xdot0, belt};
  }
  void on_event(const event& e) {
    if (keep_events) out.events.push_back(e);
    stats.on_event(e);
  }
  void on_segment(const segment& s) {
    if (keep_segments) out.segments.push_back(s);
    stats.on_segment(s);
  }
  void on_episode(const episode& e) {
    out.episodes.push_back(e);
    stats.on_episode(e);
  }
  void on_piece(const motion_piece& p) noexcept { stats.on_piece(p); }
};

// "--mu is gamma(mean=5,cv=0.2)": the first law, for messages.
std::string first_law(const std::vector<uncertain_parameter>& laws) {
  if (laws.empty()) return "a law";
  std::string flag = "--" + laws.front().symbol;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return fmt::format("{} is {}", flag, to_string(laws.front().law));
}

}  // namespace

realization_report replay_uncertain(const replay_request& request,
                                    std::vector<uncertain_parameter> laws) {
  sweep_spec s;  // the one-point sweep whose realization this is
  s.base = request.parameters;
  s.uncertain = std::move(laws);
  s.seed = request.seed;
  s.initial = request.initial;
  s.max_events = request.max_events;
  s.common_random_numbers = request.common_random_numbers;
  s.burn_in = request.burn_in;
  validate(s);  // validate_laws among the sweep's checks

  const drawn_realization d = draw_realization(s, 0, request.realization);
  realization_report report{request, {}, s.uncertain, d.values};
  report.request.parameters = d.parameters;
  traced_realization obs{realization_observer(d.parameters, s.family_statistics, s.burn_in), report.trace,
                         request.keep_events, request.keep_segments};
  const event_counts counts =
      simulate_with_values(s, d.parameters, uncertain_stream_key(s, 0), request.realization, obs);
  obs.stats.finish();
  report.trace.record = obs.stats.record();
  report.trace.record.events = counts;
  return report;
}

error realization_required(const std::vector<uncertain_parameter>& laws) {
  return invalid_value("--realization", "(not given)",
                       fmt::format("a realization index R, since {}: one trajectory of an "
                                   "uncertain model is realization R of the sweep point, which "
                                   "draws its own values; give --realization R",
                                   first_law(laws)));
}

error fixed_input_with_laws(const std::string& flag, const std::string& value,
                            const std::vector<uncertain_parameter>& laws) {
  return invalid_value(flag, value,
                       fmt::format("not with a law ({}): realization R is replayed whole, as the "
                                   "sweep draws it",
                                   first_law(laws)));
}

}  // namespace stickslip::io
