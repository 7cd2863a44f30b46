// Sweeps with uncertain parameters (sweep_spec::uncertain;
// uncertainty/uncertain_realization.hpp):
//   - results are bit-identical for 1 and 2 threads and for any block size;
//   - realization r replays alone (same key, same draws, same record);
//   - a realization's draws depend on nothing but (seed, point, r): not on
//     the other points, the other realizations or the blocks;
//   - the mixture oracle: with mu ~ uniform(a, b) the mean of R equals the
//     average over mu of fixed-mu sweeps (midpoint rule, independent seeds),
//     within 4 standard errors;
//   - the journal identity carries the laws; records carry the drawn values.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "same_bits.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/uncertain_realization.hpp"

namespace stickslip {
namespace {

using testing_support::same_bits;

// Every field to the bit, the drawn values included.
bool same_record(const realization_record& a, const realization_record& b) {
  if (!same_bits(a, b) || a.drawn_values.size() != b.drawn_values.size()) return false;
  for (std::size_t i = 0; i < a.drawn_values.size(); ++i)
    if (!same_bits(a.drawn_values[i], b.drawn_values[i])) return false;
  return true;
}
bool same_records(const std::vector<realization_record>& a, const std::vector<realization_record>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same_record(a[i], b[i])) return false;
  return true;
}

uncertain_parameter law(const char* symbol, const char* text) {
  return {symbol, parse_law(text, symbol)};
}

// The issue's example, scaled down: lambda on a grid, mu ~ gamma.
sweep_spec gamma_mu_sweep(std::uint64_t realizations = 300) {
  sweep_spec s;
  s.base.stiffness = 40;
  s.axes = {{"lambda", {1.0, 3.8}}};
  s.uncertain = {law("mu", "gamma(mean=5,cv=0.2)")};
  s.realizations = realizations;
  s.block_size = 40;
  s.seed = 11;
  s.keep_records = true;
  return s;
}

// A family point: damped, with mu_k and k uncertain below a fixed mu_s.
sweep_spec family_sweep() {
  sweep_spec s;
  s.base.stiffness = 20;
  s.base.damping = 0.3;
  s.base.static_friction = 6;
  s.base.kinetic_friction = 4;
  s.base.window = 20;
  s.axes = {{"V", {0.5, 1.0}}};
  s.uncertain = {law("mu_k", "uniform(3,5.5)"), law("k", "lognormal(mean=20,cv=0.3)")};
  s.realizations = 120;
  s.block_size = 25;
  s.keep_records = true;
  return s;
}

void expect_same_results(const result_set& a, const result_set& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_TRUE(same_bits(a.points[i].stats, b.points[i].stats)) << "point " << i;
    EXPECT_TRUE(a.points[i].stats == b.points[i].stats) << "point " << i;
  }
  ASSERT_EQ(a.records.size(), b.records.size());
  for (std::size_t i = 0; i < a.records.size(); ++i)
    EXPECT_TRUE(same_records(a.records[i], b.records[i])) << "point " << i;
}

TEST(UncertainSweep, SameBitsForOneAndTwoThreadsSameRealizationsForAnyBlocks) {
  for (const sweep_spec& s : {gamma_mu_sweep(), family_sweep()}) {
    const auto one = run_sweep(s, 1), two = run_sweep(s, 2);
    expect_same_results(one, two);
    // Other blocks and the other engine setting: the same realizations (the
    // statistics merge blocks, so their rounding depends on the block size).
    sweep_spec other_blocks = s;
    other_blocks.block_size = 7;
    other_blocks.engine = sweep_engine::reference;
    const auto blocks = run_sweep(other_blocks, 2);
    for (std::size_t i = 0; i < one.records.size(); ++i)
      EXPECT_TRUE(same_records(one.records[i], blocks.records[i])) << "point " << i;
    // Every realization drew, and not all the same value.
    ASSERT_EQ(one.records[0].size(), s.realizations);
    EXPECT_EQ(one.records[0][0].drawn_values.size(), s.uncertain.size());
    EXPECT_NE(one.records[0][0].drawn_values, one.records[0][1].drawn_values);
  }
}

TEST(UncertainSweep, EveryRealizationReplaysAlone) {
  for (const sweep_spec& s : {gamma_mu_sweep(), family_sweep()}) {
    const auto rs = run_sweep(s, 2);
    for (std::size_t point = 0; point < point_count(s); ++point)
      for (std::uint64_t r : {std::uint64_t{0}, std::uint64_t{17}, s.realizations - 1}) {
        // The key and the draws, from their definitions.
        const std::uint64_t key = uncertain_point_key(point_parameters(s, point), s.uncertain);
        const auto values = draw_values(s.uncertain, s.seed, key, r);
        const model_parameters drawn = with_values(point_parameters(s, point), s.uncertain, values);
        realization_observer obs = observe_with_values(s, drawn, key, r);
        realization_record replay = obs.record();
        replay.drawn_values = values;
        EXPECT_TRUE(same_record(replay, rs.records[point][r])) << "point " << point << " r " << r;
        const auto d = draw_realization(s, point, r);
        EXPECT_EQ(d.values, values);
        EXPECT_EQ(d.parameters, drawn);
      }
  }
}

TEST(UncertainSweep, DrawsDependOnlyOnSeedPointAndRealization) {
  const sweep_spec s = gamma_mu_sweep(200);
  const auto all = run_sweep(s, 1);
  // The second point alone, with fewer realizations in other blocks.
  sweep_spec alone = s;
  alone.axes = {{"lambda", {3.8}}};
  alone.realizations = 90;
  alone.block_size = 13;
  const auto part = run_sweep(alone, 1);
  for (std::uint64_t r = 0; r < alone.realizations; ++r)
    EXPECT_TRUE(same_record(part.records[0][r], all.records[1][r])) << r;
  // Without common random numbers the two points draw independently; with
  // them, realization r of every point draws the same values.
  EXPECT_NE(all.records[0][5].drawn_values, all.records[1][5].drawn_values);
  sweep_spec crn = s;
  crn.common_random_numbers = true;
  const auto c = run_sweep(crn, 1);
  for (std::uint64_t r = 0; r < 20; ++r)
    EXPECT_EQ(c.records[0][r].drawn_values, c.records[1][r].drawn_values) << r;
}

// The mixture oracle. With mu ~ uniform(2, 7) the point's mean R is
// E R = (1/5) int_2^7 g(mu) dmu, g(mu) = E[R | mu]. Estimate the integral
// by the midpoint rule over 40 fixed-mu points (another seed, so the two
// estimates are independent); its discretization error, h^2/24 |g''|, is
// orders below the standard errors.
TEST(UncertainSweep, MixtureMeanIsTheAverageOverTheLaw) {
  sweep_spec mix;
  mix.base.stiffness = 40;
  mix.uncertain = {law("mu", "uniform(2,7)")};
  mix.realizations = 16000;
  mix.block_size = 500;
  mix.seed = 3;
  const auto m = run_sweep(mix, 2).points[0].stats.stick_fraction;

  sweep_spec grid;
  grid.base.stiffness = 40;
  const int n = 40;
  grid.axes = {{"mu", {}}};
  for (int j = 0; j < n; ++j) grid.axes[0].values.push_back(2.0 + 5.0 * (j + 0.5) / n);
  grid.realizations = 400;
  grid.block_size = 400;
  grid.seed = 4;
  const auto g = run_sweep(grid, 2);
  double mean = 0, var = 0;
  for (const auto& p : g.points) {
    mean += p.stats.stick_fraction.mean() / n;
    var += p.stats.stick_fraction.variance() / p.stats.stick_fraction.count() / (n * n);
  }
  const double se = std::sqrt(var + m.variance() / m.count());
  EXPECT_LT(std::abs(m.mean() - mean), 4 * se)
      << "mixture " << m.mean() << " vs grid " << mean << " (se " << se << ")";
  // The test has power: the mixture is not the model at the law's mean.
  sweep_spec at_mean = grid;
  at_mean.axes.clear();
  at_mean.base.friction_coefficient = 4.5;
  at_mean.realizations = 16000;
  const auto c = run_sweep(at_mean, 2).points[0].stats.stick_fraction;
  EXPECT_GT(std::abs(m.mean() - c.mean()),
            4 * std::sqrt(c.variance() / c.count() + m.variance() / m.count()));
}

TEST(UncertainSweep, PointStandsForItsMediansAndKeepsValidScores) {
  sweep_spec s = gamma_mu_sweep(60);
  EXPECT_EQ(point_parameters(s, 0).friction_coefficient, quantile(s.uncertain[0].law, 0.5));
  EXPECT_EQ(point_parameters(s, 1).switch_rate, 3.8);
  // Given each draw of mu the score N - lambda t_a is centred: kept.
  EXPECT_EQ(run_sweep(s, 1).points[0].stats.stick_fraction_score.count(), 60u);
  // A law over lambda breaks the centring: the scores are left empty.
  s.axes = {{"mu", {5.0}}};
  s.uncertain = {law("lambda", "loguniform(0.5,10)")};
  const auto st = run_sweep(s, 1).points[0].stats;
  EXPECT_EQ(st.stick_fraction_score.count(), 0u);
  EXPECT_EQ(st.stick_fraction_causal_score.count(), 0u);
  EXPECT_EQ(st.stick_fraction.count(), 60u);
}

TEST(UncertainSweep, ValidationRefusesLawsThatCanLeaveTheDomain) {
  sweep_spec s = gamma_mu_sweep();
  s.axes = {{"mu", {4.0, 5.0}}};
  EXPECT_THROW(validate(s), error);  // a law and an axis for mu
  s = family_sweep();
  s.axes = {{"mu_s", {7.0, 5.0}}};  // mu_k ~ uniform(3, 5.5) can exceed mu_s = 5
  try {
    validate(s);
    ADD_FAILURE() << "accepted";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    EXPECT_NE(std::string(e.what()).find("--mu-k: uniform(min=3,max=5.5) can exceed mu_s = 5"),
              std::string::npos)
        << e.what();
  }
  // The base's own value of an uncertain parameter is not used: mu_k = mu = 5
  // above mu_s = 4.5 is no error when mu_k has a law below mu_s.
  s = family_sweep();
  s.base.kinetic_friction = 0;
  s.base.static_friction = 4.5;
  s.uncertain = {law("mu_k", "uniform(3,4)")};
  EXPECT_NO_THROW(validate(s));
  s = gamma_mu_sweep();
  s.uncertain = {law("lambda", "loguniform(1,1e7)")};  // the event bound at the largest draw
  s.axes = {{"k", {40.0}}};
  EXPECT_THROW(validate(s), error);
}

TEST(UncertainSweep, JournalIdentityCarriesTheLaws) {
  const sweep_spec s = gamma_mu_sweep();
  const auto back = deserialize_sweep_spec(serialize(s));
  EXPECT_EQ(back, s);
  sweep_spec other = s;
  other.uncertain[0] = law("mu", "gamma(mean=5,cv=0.25)");
  EXPECT_FALSE(same_results(s, other));
  EXPECT_NE(fingerprint(s), fingerprint(other));
  EXPECT_EQ(first_difference(s, other),
            "uncertain parameters: mu ~ gamma(mean=5,cv=0.2) vs mu ~ gamma(mean=5,cv=0.25)");
  other = s;
  other.sensitivity_statistic = "R";
  EXPECT_FALSE(same_results(s, other));
  EXPECT_NE(first_difference(s, other).find("sensitivity statistic"), std::string::npos);
  // A block with records round-trips with its drawn values.
  const work_unit u{1, 2};
  const block_result b = simulate_block(s, u);
  const auto [u2, b2] = deserialize_unit_result(serialize(u, b));
  EXPECT_EQ(u2, u);
  EXPECT_TRUE(same_records(b2.records, b.records));
  EXPECT_TRUE(b2.stats == b.stats);
  EXPECT_NO_THROW(check_block_shape(s, u, b2));
  // A sensitivity design's moments round-trip to the bit.
  block_result design = b;
  design.stats.sensitivity = sobol_moments(2);
  design.stats.sensitivity.add(1.0, 1.5, 0.25, std::vector{0.7, 1.2});
  design.stats.sensitivity.add(0.3, 0.1, 2.5, std::vector{0.9, 0.2});
  const auto [u3, b3] = deserialize_unit_result(serialize(u, design));
  EXPECT_TRUE(b3.stats.sensitivity == design.stats.sensitivity);
  EXPECT_EQ(b3.stats.sensitivity.rows(), 2u);
  const auto prefix = deserialize_merged_prefix(serialize_merged_prefix(0, 1, design.stats));
  EXPECT_TRUE(prefix.stats.sensitivity == design.stats.sensitivity);
  // A damaged law is refused, never misread.
  bytes damaged = serialize(s);
  const auto at = damaged.rfind("mu");
  ASSERT_NE(at, bytes::npos);
  damaged[at + 2] = 9;  // the family byte after the symbol
  EXPECT_THROW((void)deserialize_sweep_spec(damaged), error);
}

TEST(UncertainSweep, RecordsCsvHasAColumnPerUncertainParameter) {
  const sweep_spec s = gamma_mu_sweep(5);
  const auto rs = run_sweep(s, 1);
  const auto path = std::filesystem::temp_directory_path() / "stickslip_uncertain_records.csv";
  io::write_records_csv(rs, path.string());
  std::ifstream in(path);
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  std::filesystem::remove(path);
  EXPECT_EQ(header.rfind("point,lambda,mu,realization,", 0), 0u) << header;
  EXPECT_EQ(first.rfind(fmt::format("0,1,{},0,", rs.records[0][0].drawn_values[0]), 0), 0u) << first;
  // summary.json names each law by its canonical text.
  const std::string json = io::summary_json(rs, io::run_metadata{});
  const auto at = json.find("\"uncertain_parameters\"");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(json.find("\"mu\": \"gamma(mean=5,cv=0.2)\"", at), std::string::npos) << json.substr(at, 80);
  // ... and gives mu (with mu_s, mu_k) no single value in the base.
  const auto base = json.find("\"base\"");
  ASSERT_NE(base, std::string::npos);
  EXPECT_NE(json.find("\"mu\": null", base), std::string::npos) << json.substr(base, 200);
  EXPECT_LT(json.find("\"mu\": null", base), json.find("\"swept\"", base));
}

}  // namespace
}  // namespace stickslip
