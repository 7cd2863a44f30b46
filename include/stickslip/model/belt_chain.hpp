// Belt switching for the model family: sources of (time, next level) pairs.
//
//   markov_level_switches: the Markov chain of the belt. In level i the
//     holding time is W ~ Exp(q_i), drawn exactly like poisson_switches (the
//     same counter-based stream, substream::belt_switches, the same inverse
//     transform W = -log(U) / q_i with the shared log kernel), so that for the
//     paper's belt (two levels, both rates lambda) the switch times are the
//     same bits as poisson_switches'. The next level is drawn only when there
//     are more than two levels: j != i with probability q_ij / q_i, by one
//     uniform from its own substream (belt_level_substream), draw index = jump
//     index. Every draw is a pure function of (seed, point, realization,
//     substream, index).
//   given_level_switches: a replayed, measured or hand-made list of (t, level).
//
// A source yields non-decreasing times through next(); time +infinity means
// "no more switches".
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/fast_math.hpp"
#include "stickslip/model/oscillator_model.hpp"
#include "stickslip/random_stream.hpp"

namespace stickslip {

// The substream of the next-level draws (after initial_conditions = 0 and
// belt_switches = 1 of random_stream.hpp).
inline constexpr substream belt_level_substream = substream::belt_levels;

struct level_switch {
  double time;        // when the belt jumps
  std::size_t level;  // the index of the level it jumps to
  friend bool operator==(const level_switch&, const level_switch&) = default;
};

// What the sources and the start-level draw need from a belt, computed once
// per model (no allocation per realization).
class belt_chain {
 public:
  // Precondition: validate(belt) passed.
  explicit belt_chain(const markov_belt& belt);

  [[nodiscard]] std::size_t level_count() const noexcept { return mean_wait_.size(); }
  [[nodiscard]] double mean_wait(std::size_t i) const noexcept { return mean_wait_[i]; }
  // The level reached from level i by a jump whose uniform is u in (0, 1):
  // the first j != i with u < sum_{l <= j, l != i} q_il / q_i.
  [[nodiscard]] std::size_t jump_target(std::size_t i, double u) const noexcept;
  // The level whose stationary cumulative probability first exceeds u.
  [[nodiscard]] std::size_t stationary_level(double u) const noexcept;

 private:
  std::vector<double> mean_wait_;   // 1 / q_i
  std::vector<double> jump_cdf_;    // row-major, jump_cdf_[i n + j]; the last reachable j is 1
  std::vector<double> stationary_cdf_;
};

// The starting level drawn from the stationary law, from the fourth word of
// the first block of substream::initial_conditions (draw_initial_conditions
// uses the first three), so it is a pure function of (seed, point, realization).
[[nodiscard]] std::size_t draw_stationary_level(const belt_chain& chain, std::uint64_t seed,
                                                std::uint64_t point,
                                                std::uint64_t realization) noexcept;

class markov_level_switches {
 public:
  // One source per realization, made where it is used: not copied (its
  // unread logs are left uninitialized until the first refill).
  markov_level_switches(const markov_level_switches&) = delete;
  markov_level_switches& operator=(const markov_level_switches&) = delete;
  markov_level_switches(const belt_chain& chain, std::size_t start_level, std::uint64_t seed,
                        std::uint64_t point, std::uint64_t realization) noexcept
      : chain_(&chain),
        level_(start_level),
        waits_(seed, point, realization, substream::belt_switches),
        jumps_(seed, point, realization, belt_level_substream) {}

  [[nodiscard]] level_switch next() noexcept {
    time_ += -next_log_uniform() * chain_->mean_wait(level_);  // W ~ Exp(q_i)
    if (chain_->level_count() == 2) {
      level_ = 1 - level_;
    } else {
      level_ = chain_->jump_target(
          level_, random_stream::open_uniform(draw(jumps_, jump_block_, jump_left_)));
    }
    return {time_, level_};
  }

 private:
  static std::uint64_t draw(random_stream& rs, random_stream::philox::ctr_type& block,
                            int& left) noexcept {
    if (left == 0) {
      block = rs.next_block();
      left = 4;
    }
    return block.v[4 - left--];
  }

  // log(U) of the next wait uniform: the logs of the next
  // poisson_switches::chunk uniforms at once, as poisson_switches draws them
  // (fm::log_uniforms: the same bits as detail::fm::log of each),
  // out of line once per chunk. One block of four at a time, the dispatched
  // call and its partial vector cost the damped engine 11 % of its time.
  [[nodiscard]] double next_log_uniform() noexcept {
    if (wait_next_ == wait_chunk) [[unlikely]] refill_wait_logs();
    return wait_logs_[wait_next_++];
  }
  [[gnu::noinline]] void refill_wait_logs() noexcept {
    detail::fm::log_uniforms(waits_, wait_logs_,
                             std::size_t{poisson_switches::blocks_per_chunk});
    wait_next_ = 0;
  }
  static constexpr int wait_chunk = poisson_switches::chunk;

  const belt_chain* chain_;
  std::size_t level_;
  double time_ = 0.0;
  random_stream waits_, jumps_;
  random_stream::philox::ctr_type jump_block_{};
  int wait_next_ = wait_chunk, jump_left_ = 0;
  alignas(64) double wait_logs_[wait_chunk];  // read only after a refill (wait_next_)
};

class given_level_switches {
 public:
  // Preconditions (validate_level_switches at the edge): times finite, >= 0,
  // strictly increasing; levels exist; each differs from the one before.
  explicit given_level_switches(std::span<const level_switch> switches) noexcept
      : switches_(switches) {}
  [[nodiscard]] level_switch next() noexcept {
    if (i_ < switches_.size()) return switches_[i_++];
    return {std::numeric_limits<double>::infinity(), 0};
  }

 private:
  std::span<const level_switch> switches_;
  std::size_t i_ = 0;
};

// Throws stickslip::error naming the first offending entry: a time that is
// not finite, negative or not after the previous one, a level index
// >= level_count, or (given the starting level) a switch to the level the
// belt is already on: the chain only jumps between distinct levels, and the
// engine's switch rules (a switch ends every stick) assume the level changes.
void validate_level_switches(std::span<const level_switch> switches, std::size_t level_count,
                             std::size_t start_level);

// Two-level replay lines carry only times ("go to the other level"): the
// (t, level) list that alternates from `start_level`.
[[nodiscard]] std::vector<level_switch> alternating_switches(std::span<const double> times,
                                                             std::size_t start_level);

}  // namespace stickslip
