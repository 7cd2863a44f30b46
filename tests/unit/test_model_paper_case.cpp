// The paper's model inside the family: for the paper's parameters and the
// same switch times, simulate_model (model/model_engine.hpp) must give the
// same bits as simulate() (integrator.hpp): every episode, event and counter.
// And the Markov belt source must draw the paper's Poisson switch times bit
// for bit from the same stream.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/model_engine.hpp"
#include "stickslip/random_stream.hpp"

namespace stickslip {
namespace {

struct recorded {
  std::vector<episode> episodes;
  std::vector<event> events;
  event_counts counts;
};

struct recorder {
  recorded* out;
  void on_event(const event& e) { out->events.push_back(e); }
  template <class Segment>
  void on_segment(const Segment&) {}
  void on_episode(const episode& e) { out->episodes.push_back(e); }
};

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_identical(const recorded& paper, const recorded& family, const std::string& what) {
  ASSERT_EQ(paper.counts, family.counts) << what;
  ASSERT_EQ(paper.episodes.size(), family.episodes.size()) << what;
  for (std::size_t i = 0; i < paper.episodes.size(); ++i) {
    const episode &p = paper.episodes[i], &f = family.episodes[i];
    ASSERT_EQ(p.kind, f.kind) << what << " episode " << i;
    ASSERT_TRUE(same_bits(p.start, f.start) && same_bits(p.end, f.end) &&
                same_bits(p.position_at_start, f.position_at_start) &&
                same_bits(p.belt_velocity, f.belt_velocity) && p.censored == f.censored)
        << what << " episode " << i << ": " << p.start << " " << f.start << " " << p.end << " "
        << f.end << " " << p.position_at_start << " " << f.position_at_start;
  }
  ASSERT_EQ(paper.events.size(), family.events.size()) << what;
  for (std::size_t i = 0; i < paper.events.size(); ++i) {
    const event &p = paper.events[i], &f = family.events[i];
    ASSERT_TRUE(p.kind == f.kind && same_bits(p.time, f.time) && same_bits(p.position, f.position) &&
                same_bits(p.velocity, f.velocity) && same_bits(p.belt_velocity, f.belt_velocity))
        << what << " event " << i;
  }
}

model_parameters random_paper_parameters(std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); };
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(uniform(std::log(lo), std::log(hi)));
  };
  model_parameters p;
  p.switch_rate = log_uniform(0.01, 100.0);
  p.friction_coefficient = log_uniform(0.01, 20.0);
  p.stiffness = log_uniform(0.5, 100.0);
  p.mass = uniform(0.5, 2.0);
  p.belt_speed = uniform(0.5, 2.0);
  p.window = uniform(1.0, 50.0);
  return p;
}

TEST(ModelPaperCase, PoissonAndMarkovSourcesDrawTheSameTimes) {
  model_parameters p;
  p.switch_rate = 3.7;
  const oscillator_model model = model_of(p);
  const belt_chain chain(model.belt);
  for (std::uint64_t r = 0; r < 20; ++r) {
    poisson_switches poisson(p.switch_rate, 42, 7, r);
    markov_level_switches markov(chain, r % 2, 42, 7, r);
    std::size_t level = r % 2;
    for (int i = 0; i < 200; ++i) {
      const level_switch s = markov.next();
      level = 1 - level;
      ASSERT_TRUE(same_bits(poisson.next(), s.time)) << "realization " << r << " switch " << i;
      ASSERT_EQ(s.level, level);
    }
  }
}

// Paper parameters from the oracle's ranges, paper initial conditions and
// given switch times: the family engine reproduces simulate() bit for bit.
TEST(ModelPaperCase, SameBitsAsThePaperEngineOnGivenSwitches) {
  std::mt19937_64 rng(0x9a9e4ULL);
  for (int n = 0; n < 2000; ++n) {
    const model_parameters p = random_paper_parameters(rng);
    const initial_conditions ic = draw_initial_conditions({}, 11, 0, static_cast<std::uint64_t>(n));
    std::vector<double> times;
    std::exponential_distribution<> wait(p.switch_rate);
    for (double t = wait(rng); t < p.window; t += wait(rng)) times.push_back(t);

    recorded paper, family;
    recorder paper_obs{&paper}, family_obs{&family};
    given_switches paper_switches(times);
    paper.counts = simulate(p, ic, paper_switches, paper_obs);

    const oscillator_model model = model_of(p);
    const std::vector<level_switch> levels =
        alternating_switches(times, ic.belt_direction > 0 ? 0 : 1);
    given_level_switches family_switches(levels);
    const model_initial_state start{ic.position, ic.velocity, ic.belt_direction > 0 ? 0u : 1u};
    family.counts = simulate_model(model, start, family_switches, family_obs);
    expect_identical(paper, family, "scenario " + std::to_string(n));
  }
}

// The paper's sweep path: Poisson switches against the Markov source from the
// same (seed, point, realization), including starts exactly on the belt
// velocity (a stick at t = 0) and on the outward band edge (grazing).
TEST(ModelPaperCase, SameBitsAsThePaperEngineOnDrawnSwitches) {
  model_parameters p;
  p.gravity = 8.0;
  p.friction_coefficient = 0.5;  // a = 1 exactly
  for (double lambda : {0.05, 1.0, 10.0, 100.0}) {
    p.switch_rate = lambda;
    const oscillator_model model = model_of(p);
    const belt_chain chain(model.belt);
    for (std::uint64_t r = 0; r < 300; ++r) {
      initial_conditions ic = draw_initial_conditions({}, 5, point_key(p), r);
      if (r % 3 == 1) ic.velocity = ic.belt_direction * p.belt_speed;
      if (r % 3 == 2) ic = {ic.belt_direction * 1.0, ic.belt_direction * p.belt_speed, ic.belt_direction};
      recorded paper, family;
      recorder paper_obs{&paper}, family_obs{&family};
      poisson_switches poisson(p.switch_rate, 5, point_key(p), r);
      paper.counts = simulate(p, ic, poisson, paper_obs);
      const std::size_t level = ic.belt_direction > 0 ? 0 : 1;
      markov_level_switches markov(chain, level, 5, point_key(p), r);
      family.counts = simulate_model(model, {ic.position, ic.velocity, level}, markov, family_obs);
      expect_identical(paper, family, "lambda " + std::to_string(lambda) + " r " + std::to_string(r));
    }
  }
}

}  // namespace
}  // namespace stickslip
