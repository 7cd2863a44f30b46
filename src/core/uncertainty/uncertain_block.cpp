// The sweep's blocks of a point with uncertain parameters
// (uncertainty/uncertain_realization.hpp).
#include <algorithm>
#include <string>

#include "stickslip/engines/point_engine.hpp"
#include "stickslip/error.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/uncertainty/uncertain_realization.hpp"

namespace stickslip {
namespace {

// Whether a law changes the switching law or the window the scores are
// centred with (K = N - lambda t_a, K_j = N_j - r_j T_j).
bool scores_centred_wrongly(const std::vector<uncertain_parameter>& laws) {
  return std::any_of(laws.begin(), laws.end(), [](const uncertain_parameter& u) {
    return u.symbol == "lambda" || u.symbol == "ta" || u.symbol == "r1" || u.symbol == "r2";
  });
}

// Empties every likelihood-ratio accumulator (the schema's score columns and
// R's causal score); the sizes stay, so blocks still merge.
void drop_scores(point_statistics& st) {
  for (const auto& q : quantities()) {
    if (q.score) st.*q.score = {};
    if (q.rate_score) st.*q.rate_score = {};
    if (q.generator_score)
      std::fill((st.*q.generator_score).begin(), (st.*q.generator_score).end(), score_moments{});
  }
  st.stick_fraction_causal_score = {};
}

}  // namespace

void validate_uncertain_points(const sweep_spec& s) {
  if (s.uncertain.empty()) return;
  std::vector<std::string> axes;
  model_parameters first = s.base;
  for (const auto& ax : s.axes) {
    axes.push_back(canonical_symbol(ax.name));
    if (!ax.values.empty()) set_parameter(first, axes.back(), ax.values.front());
  }
  validate_laws(first, s.uncertain, axes);
  for (std::size_t k = 0; k < s.axes.size(); ++k)
    for (std::size_t i = 1; i < s.axes[k].values.size(); ++i) {
      model_parameters p = first;
      set_parameter(p, axes[k], s.axes[k].values[i]);
      validate_laws(p, s.uncertain, axes);
    }
}

std::uint64_t uncertain_stream_key(const sweep_spec& s, std::size_t point) {
  return s.common_random_numbers ? common_stream_key
                                 : uncertain_point_key(point_parameters(s, point), s.uncertain);
}

realization_observer observe_with_values(const sweep_spec& s, const model_parameters& drawn,
                                         std::uint64_t key, std::uint64_t realization) {
  realization_observer obs(drawn, s.family_statistics, s.burn_in, &s.observe_times);
  state_sampling_observer with_states(obs);
  const event_counts counts = obs.observes_times()
                                  ? simulate_with_values(s, drawn, key, realization, with_states)
                                  : simulate_with_values(s, drawn, key, realization, obs);
  obs.finish();
  obs.record().events = counts;
  return obs;
}

drawn_realization draw_realization(const sweep_spec& s, std::size_t point,
                                   std::uint64_t realization) {
  drawn_realization d;
  d.values = draw_values(s.uncertain, s.seed, uncertain_stream_key(s, point), realization);
  d.parameters = with_values(point_parameters(s, point), s.uncertain, d.values);
  validate(d.parameters);  // validate_laws checked the extremes; this is every draw
  return d;
}

block_result simulate_block_uncertain(const sweep_spec& s, const work_unit& u) {
  detail::count_engine_run(point_engine::uncertain);
  const model_parameters point = point_parameters(s, u.point);  // at the medians
  const std::uint64_t key = uncertain_stream_key(s, u.point);
  block_result out;
  out.stats = block_statistics(s, histogram_parameters(s, u.point));
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, first + s.block_size);
  if (s.keep_records) out.records.reserve(last - first);
  for (std::uint64_t r = first; r < last; ++r) {
    std::vector<double> values = draw_values(s.uncertain, s.seed, key, r);
    const model_parameters drawn = with_values(point, s.uncertain, values);
    validate(drawn);
    realization_observer obs = observe_with_values(s, drawn, key, r);
    if (!out.stats.keeps_causal_score()) drop_causal_score(obs.record());
    out.stats.add(obs.samples(), drawn.window);
    if (s.keep_records) {
      out.records.push_back(obs.record());
      out.records.back().drawn_values = std::move(values);
    }
  }
  if (scores_centred_wrongly(s.uncertain)) drop_scores(out.stats);
  return out;
}

}  // namespace stickslip
