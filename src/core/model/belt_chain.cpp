#include "stickslip/model/belt_chain.hpp"

#include <string>

#include "stickslip/error.hpp"

namespace stickslip {

belt_chain::belt_chain(const markov_belt& belt) {
  const std::size_t n = belt.level_count();
  mean_wait_.resize(n);
  jump_cdf_.assign(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double q = belt.leaving_rate(i);
    mean_wait_[i] = 1.0 / q;
    double sum = 0.0;
    std::size_t last = i;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      sum += belt.rate(i, j);
      jump_cdf_[i * n + j] = sum / q;
      if (belt.rate(i, j) > 0.0) last = j;
    }
    // The last reachable level takes all the remaining mass (rounding).
    for (std::size_t j = last; j < n; ++j)
      if (j != i) jump_cdf_[i * n + j] = 1.0;
  }
  const std::vector<double> pi = stationary_law(belt);
  stationary_cdf_.resize(n);
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) stationary_cdf_[i] = sum += pi[i];
  stationary_cdf_[n - 1] = 1.0;
}

std::size_t belt_chain::jump_target(std::size_t i, double u) const noexcept {
  const std::size_t n = level_count();
  for (std::size_t j = 0; j < n; ++j)
    if (j != i && u < jump_cdf_[i * n + j]) return j;
  return i == n - 1 ? n - 2 : n - 1;  // unreachable: the last reachable entry is 1
}

std::size_t belt_chain::stationary_level(double u) const noexcept {
  for (std::size_t i = 0; i < stationary_cdf_.size(); ++i)
    if (u < stationary_cdf_[i]) return i;
  return stationary_cdf_.size() - 1;
}

std::size_t draw_stationary_level(const belt_chain& chain, std::uint64_t seed,
                                  std::uint64_t point, std::uint64_t realization) noexcept {
  random_stream rs(seed, point, realization, substream::initial_conditions);
  return chain.stationary_level(random_stream::open_uniform(rs.next_block().v[3]));
}

void validate_level_switches(std::span<const level_switch> switches, std::size_t level_count,
                             std::size_t start_level) {
  std::size_t current = start_level;
  for (std::size_t i = 0; i < switches.size(); ++i) {
    const std::string name = "switch #" + std::to_string(i + 1);
    const double t = switches[i].time;
    if (!std::isfinite(t) || t < 0.0) throw invalid_parameter(name + " time", t, "finite and >= 0");
    if (i > 0 && !(t > switches[i - 1].time))
      throw invalid_parameter(name + " time", t,
                              "strictly greater than the previous one (" +
                                  std::to_string(switches[i - 1].time) + "): times must be sorted");
    if (switches[i].level >= level_count)
      throw invalid_parameter(name + " level", static_cast<double>(switches[i].level),
                              "an existing level index, 0.." + std::to_string(level_count - 1));
    if (switches[i].level == current)
      throw invalid_parameter(name + " level", static_cast<double>(current),
                              "a level other than the current one (" + std::to_string(current) +
                                  "): a switch must change the belt level");
    current = switches[i].level;
  }
}

std::vector<level_switch> alternating_switches(std::span<const double> times,
                                               std::size_t start_level) {
  std::vector<level_switch> out;
  out.reserve(times.size());
  std::size_t level = start_level;
  for (double t : times) {
    level = 1 - level;
    out.push_back({t, level});
  }
  return out;
}

}  // namespace stickslip
