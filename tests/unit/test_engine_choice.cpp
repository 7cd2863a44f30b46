// One place chooses the engine of a point (engines/point_engine.hpp). For a
// table of models (the paper's, mu_s > mu_k, damped, three levels, a resting
// level) under sweep_engine::fast and ::reference: engine_for gives the
// expected engine, and every site runs that engine and no other (the
// process-wide counts of engine runs): simulate_block, simulate_units,
// simulate_block_reference; replay and the lane engine's rerun after
// max_events run the reference engine for every model, the paper's
// included. Points with laws and sensitivity designs run their own engines,
// and a draw of the paper's model there runs simulate. Inside the engines,
// the realizations each integrator ran (simulate, simulate_model), counted
// by the integrators themselves, say which one did the work.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "stickslip/detail/fast_block.hpp"
#include "stickslip/engines/engine_choice.hpp"
#include "stickslip/engines/integration_counts.hpp"
#include "stickslip/error.hpp"
#include "stickslip/replay.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"

namespace stickslip {
namespace {

constexpr std::array all_engines{point_engine::lanes, point_engine::reference,
                                 point_engine::uncertain, point_engine::sensitivity,
                                 point_engine::paper_integrator};

// The engine runs `run` made, by engine.
std::array<std::uint64_t, all_engines.size()> runs_of(const auto& run) {
  std::array<std::uint64_t, all_engines.size()> before{}, after{};
  for (std::size_t i = 0; i < all_engines.size(); ++i) before[i] = detail::engine_runs(all_engines[i]);
  run();
  for (std::size_t i = 0; i < all_engines.size(); ++i)
    after[i] = detail::engine_runs(all_engines[i]) - before[i];
  return after;
}

// The realizations each integrator ran during `run`: {paper, model}.
struct integrated {
  std::uint64_t paper = 0, model = 0;
  friend bool operator==(const integrated&, const integrated&) = default;
};
std::ostream& operator<<(std::ostream& os, const integrated& n) {
  return os << "{simulate: " << n.paper << ", simulate_model: " << n.model << "}";
}
integrated integrations_of(const auto& run) {
  const integrated before{detail::integrations(integrator::paper),
                          detail::integrations(integrator::model)};
  run();
  return {detail::integrations(integrator::paper) - before.paper,
          detail::integrations(integrator::model) - before.model};
}

// Exactly `count` runs of `engine` and none of any other.
void expect_only(const std::array<std::uint64_t, all_engines.size()>& runs, point_engine engine,
                 std::uint64_t count, const std::string& what) {
  for (std::size_t i = 0; i < all_engines.size(); ++i)
    EXPECT_EQ(runs[i], all_engines[i] == engine ? count : 0)
        << what << ": " << to_string(all_engines[i]) << " (expected " << to_string(engine) << ")";
}

struct model_case {
  const char* name;
  model_parameters parameters;
  bool lanes;  // whether the lane engine runs it
  bool paper;  // whether it is the paper's model
};

std::vector<model_case> models() {
  model_parameters paper;
  paper.stiffness = 40.0;
  paper.window = 10.0;
  auto unequal = paper;
  unequal.static_friction = 6.0;
  unequal.kinetic_friction = 4.0;
  auto damped = paper;
  damped.damping = 0.632;
  auto three = paper;
  three.belt_levels = {1.0, 0.0, -1.0};
  three.belt_generator = {-2, 1, 1, 1, -1, 0, 0.5, 0.5, -1};
  auto resting = paper;
  resting.belt_levels = {1.0, 0.0};
  auto same_as_paper = paper;  // the paper's model written with mu_s, mu_k
  same_as_paper.static_friction = same_as_paper.kinetic_friction = paper.friction_coefficient;
  return {{"paper", paper, true, true},          {"paper as mu_s = mu_k", same_as_paper, true, true},
          {"mu_s > mu_k", unequal, true, false}, {"damped", damped, false, false},
          {"three levels", three, false, false}, {"resting level", resting, true, false}};
}

sweep_spec spec_of(const model_parameters& p, sweep_engine engine) {
  sweep_spec s;
  s.base = p;
  s.realizations = 12;
  s.block_size = 4;
  s.seed = 3;
  s.engine = engine;
  validate(s);
  return s;
}

TEST(EngineChoice, EachModelAndEngineSetting) {
  for (const auto& m : models()) {
    const point_engine reference = point_engine::reference;
    EXPECT_EQ(draw_engine(m.parameters),
              m.paper ? point_engine::paper_integrator : point_engine::reference)
        << m.name;
    for (sweep_engine asked : {sweep_engine::fast, sweep_engine::reference}) {
      const std::string what = std::string(m.name) + ", " + to_string(asked);
      const sweep_spec s = spec_of(m.parameters, asked);
      const point_engine expected =
          asked == sweep_engine::fast && m.lanes ? point_engine::lanes : reference;
      EXPECT_EQ(engine_for(s, point_parameters(s, 0)), expected) << what;

      expect_only(runs_of([&] { (void)simulate_block(s, work_unit{0, 1}); }), expected, 1,
                  what + ", simulate_block");
      // Inside the engine: the lanes run no scalar integrator; the reference
      // engine runs simulate_model for every realization, also of the
      // paper's model, and never simulate.
      const integrated block_runs = expected == point_engine::lanes ? integrated{} : integrated{0, 4};
      EXPECT_EQ(integrations_of([&] { (void)simulate_block(s, work_unit{0, 1}); }), block_runs)
          << what << ", simulate_block";
      // simulate_units hands a run of blocks to the lane engine at once.
      const std::vector<work_unit> units{{0, 0}, {0, 1}, {0, 2}};
      expect_only(runs_of([&] { (void)simulate_units(s, units); }), expected,
                  expected == point_engine::lanes ? 1 : 3, what + ", simulate_units");
      expect_only(runs_of([&] { (void)simulate_block_reference(s, work_unit{0, 0}); }), reference,
                  1, what + ", simulate_block_reference");
      EXPECT_EQ(integrations_of([&] { (void)simulate_units(s, units); }),
                (expected == point_engine::lanes ? integrated{} : integrated{0, 12}))
          << what << ", simulate_units";
      EXPECT_EQ(integrations_of([&] { (void)simulate_block_reference(s, work_unit{0, 0}); }),
                (integrated{0, 4}))
          << what << ", simulate_block_reference";
    }
    replay_request r;
    r.parameters = m.parameters;
    r.seed = 3;
    r.realization = 2;
    expect_only(runs_of([&] { (void)replay(r); }), reference, 1, std::string(m.name) + ", replay");
    EXPECT_EQ(integrations_of([&] { (void)replay(r); }), (integrated{0, 1}))
        << m.name << ", replay";
  }
}

// Only the points the lane engine runs reach it; it refuses the others.
TEST(EngineChoice, TheLaneEngineRefusesOtherPoints) {
  for (const auto& m : models()) {
    const sweep_spec s = spec_of(m.parameters, sweep_engine::fast);
    if (m.lanes) continue;
    EXPECT_THROW((void)detail::simulate_block_lanes(s, work_unit{0, 0}), error) << m.name;
    EXPECT_THROW((void)detail::trace_realizations_lanes(s, 0, 0, 2), error) << m.name;
  }
}

// Over max_events the lane engine reruns the block on the model's reference
// engine, which throws the reference's error.
TEST(EngineChoice, TheLaneRerunUsesTheReferenceEngine) {
  for (const auto& m : models()) {
    if (!m.lanes) continue;
    sweep_spec s = spec_of(m.parameters, sweep_engine::fast);
    s.max_events = 3;
    const point_engine reference = point_engine::reference;
    const auto reruns = detail::lane_reference_reruns();
    integrated inside;
    const auto runs = runs_of([&] {
      inside = integrations_of([&] {
        EXPECT_THROW((void)simulate_block(s, work_unit{0, 0}), error) << m.name;
      });
    });
    EXPECT_EQ(inside.paper, 0u) << m.name;  // the rerun runs simulate_model, which throws
    EXPECT_EQ(inside.model, 1u) << m.name;
    EXPECT_EQ(detail::lane_reference_reruns(), reruns + 1) << m.name;
    EXPECT_EQ(runs[static_cast<std::size_t>(point_engine::lanes)], 1u) << m.name;
    EXPECT_EQ(runs[static_cast<std::size_t>(reference)], 1u) << m.name;
    const auto traced = runs_of([&] {
      EXPECT_THROW((void)detail::trace_realizations_lanes(s, 0, 0, 3), error) << m.name;
    });
    EXPECT_EQ(traced[static_cast<std::size_t>(reference)], 1u) << m.name;
  }
}

TEST(EngineChoice, LawsAndSensitivityDesignsRunTheirOwnEngines) {
  for (sweep_engine asked : {sweep_engine::fast, sweep_engine::reference}) {
    sweep_spec s = spec_of(models().front().parameters, asked);
    s.uncertain = {{"mu", parse_law("uniform(2,7)", "mu")}};
    EXPECT_EQ(engine_for(s, point_parameters(s, 0)), point_engine::uncertain);
    expect_only(runs_of([&] { (void)simulate_units(s, {{0, 0}, {0, 1}}); }),
                point_engine::uncertain, 2, "laws");
    // mu drawn on the paper's base: every draw is a paper model, run by
    // simulate (draw_engine); a law of mu_k makes every draw a family model.
    EXPECT_EQ(integrations_of([&] { (void)simulate_units(s, {{0, 0}, {0, 1}}); }),
              (integrated{8, 0}));
    sweep_spec family = s;
    family.uncertain = {{"mu_k", parse_law("uniform(2,4)", "mu_k")}};
    validate(family);
    EXPECT_EQ(integrations_of([&] { (void)simulate_units(family, {{0, 0}}); }),
              (integrated{0, 4}));
    sensitivity_choice design;
    design.samples = 8;
    design.block_size = 4;
    set_sensitivity_design(s, design);
    EXPECT_EQ(engine_for(s, point_parameters(s, 0)), point_engine::sensitivity);
    expect_only(runs_of([&] { (void)simulate_block(s, work_unit{0, 0}); }),
                point_engine::sensitivity, 1, "sensitivity");
    // 4 rows of d + 3 = 4 realizations each, every draw of mu a paper model.
    EXPECT_EQ(integrations_of([&] { (void)simulate_block(s, work_unit{0, 0}); }),
              (integrated{16, 0}));
  }
}

}  // namespace
}  // namespace stickslip
