// Text of simulate's outputs. Numbers are printed with fmt "{}", the shortest
// text that reads back to the same double; JSON goes through json_emitter.
#include "stickslip/io/realization_output.hpp"

#include <fmt/format.h>

#include <type_traits>

#include "json_emitter.hpp"
#include "stickslip/record_schema.hpp"
#include "stickslip/trajectory.hpp"

namespace stickslip::io {

std::string episodes_csv(const realization_report& r) {
  std::string out = "mode,start,end,x_start,belt_velocity,censored\n";
  for (const auto& e : r.trace.episodes)
    out += fmt::format("{},{},{},{},{},{}\n", to_string(e.kind), e.start, e.end,
                       e.position_at_start, e.belt_velocity, e.censored ? 1 : 0);
  return out;
}

std::string events_csv(const realization_report& r) {
  std::string out = "kind,time,x,xdot,v\n";
  for (const auto& e : r.trace.events)
    out += fmt::format("{},{},{},{},{}\n", to_string(e.kind), e.time, e.position, e.velocity,
                       e.belt_velocity);
  return out;
}

std::string trajectory_csv(const realization_report& r, double step) {
  std::string out = "t,x,xdot,v,mode\n";
  for (const auto& q : sample_trajectory(r.trace.segments, step))
    out += fmt::format("{},{},{},{},{}\n", q.time, q.position, q.velocity, q.belt_velocity,
                       to_string(q.kind));
  return out;
}

namespace {

using detail::json_emitter;
using detail::layout;

void emit_initial_conditions(json_emitter& j, const realization_report& r) {
  j.key("initial_conditions");
  j.begin_object();
  j.member("x0", r.trace.initial.position);
  j.member("xdot0", r.trace.initial.velocity);
  j.member("belt_start", r.trace.initial.belt_direction);
  j.key("given");
  j.begin_object();
  j.member("x0", r.request.x0.has_value());
  j.member("xdot0", r.request.xdot0.has_value());
  j.member("belt_start", r.request.belt_start.has_value());
  j.end_object();
  j.end_object();
}

void emit_draws(json_emitter& j, const realization_report& r) {
  j.key("laws");
  j.begin_object();
  for (const auto& u : r.uncertain) j.member(u.symbol, to_string(u.law));
  j.end_object();
  j.key("drawn");
  j.begin_object();
  for (std::size_t i = 0; i < r.uncertain.size() && i < r.drawn.size(); ++i)
    j.member(r.uncertain[i].symbol, r.drawn[i]);
  j.end_object();
}

// "statistics": the record's outcome fields (record_schema.hpp), null where
// the realization has no such value (no first stick); "event_counts": the
// counts again, named by event kind as the events are.
void emit_statistics(json_emitter& j, const realization_report& r) {
  const auto& s = r.trace.record;
  j.key("statistics");
  j.begin_object();
  for_each_record_field(record_role::outcome, [&](const record_field& field) {
    j.key(field.name);
    if (field.exists && !field.exists(s)) return j.null();
    visit_field(field, s, [&](const auto& v) {
      using type = std::remove_cvref_t<decltype(v)>;
      if constexpr (std::is_same_v<type, std::uint32_t>)
        j.value(static_cast<std::uint64_t>(v));
      else
        j.value(v);
    });
  });
  j.end_object();
  j.key("event_counts");
  j.begin_object();
  j.member(to_string(event_kind::belt_switch), s.events.belt_switches);
  j.member(to_string(event_kind::stick_onset), s.events.stick_onsets);
  j.member(to_string(event_kind::stick_break), s.events.stick_breaks);
  j.member(to_string(event_kind::slip_reversal), s.events.slip_reversals);
  j.end_object();
}

void emit_episodes(json_emitter& j, const realization_report& r) {
  j.key("episodes");
  j.begin_array(layout::multi_line);
  for (const auto& e : r.trace.episodes) {
    j.begin_object();
    j.member("mode", to_string(e.kind));
    j.member("start", e.start);
    j.member("end", e.end);
    j.member("x_start", e.position_at_start);
    j.member("belt_velocity", e.belt_velocity);
    j.member("censored", e.censored);
    j.end_object();
  }
  j.end_array();
}

void emit_events(json_emitter& j, const realization_report& r) {
  j.key("events");
  j.begin_array(layout::multi_line);
  for (const auto& e : r.trace.events) {
    j.begin_object();
    j.member("kind", to_string(e.kind));
    j.member("time", e.time);
    j.member("x", e.position);
    j.member("xdot", e.velocity);
    j.member("v", e.belt_velocity);
    j.end_object();
  }
  j.end_array();
}

}  // namespace

std::string realization_json(const realization_report& r, bool with_events) {
  detail::text_sink out;
  json_emitter j(out);
  j.begin_object(layout::multi_line);
  j.key("parameters");
  j.begin_object();
  emit_model_members(j, r.request.parameters);
  j.end_object();
  j.member("seed", r.request.seed);
  j.member("realization", r.request.realization);
  if (r.request.burn_in > 0.0) j.member("burn_in", r.request.burn_in);
  if (!r.uncertain.empty()) emit_draws(j, r);
  emit_initial_conditions(j, r);
  // "poisson" for the paper's telegraph belt, "markov" for any other belt.
  j.member("switch_times", r.request.switch_times.has_value()          ? "given"
                           : r.request.parameters.is_paper_model() ? "poisson"
                                                                   : "markov");
  emit_statistics(j, r);
  emit_episodes(j, r);
  if (with_events) emit_events(j, r);
  j.end_object();
  out.put('\n');
  return out.str();
}

}  // namespace stickslip::io
