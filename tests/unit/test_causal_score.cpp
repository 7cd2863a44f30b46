// The causal likelihood-ratio derivative of R over lambda
// (causal_score_moments in accumulators/score_moments.hpp): the engines'
// bookkeeping against a count made from a replay's events, and the
// estimate against two independent ones, common-random-number central
// differences and the full score. Fixed seeds; tolerances from standard
// errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "stickslip/replay.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"
#include "unit/figure_spec.hpp"

namespace stickslip {
namespace {

using testing_support::figure_spec;

// Z and Y of one realization computed from its replay alone: N(t) counted
// from the belt_switch events, the sticks from the episodes, the integrals
// of N(t) and t over each stick and over [0, t_a] done directly.
struct causal_values {
  double z = 0, y = 0;
};
causal_values from_trace(const realization_trace& tr, double lambda, double ta) {
  std::vector<double> switches;
  for (const auto& e : tr.events)
    if (e.kind == event_kind::belt_switch) switches.push_back(e.time);
  const auto count_upto = [&](double t) {
    double n = 0;
    for (double s : switches) n += s <= t ? 1.0 : 0.0;
    return n;
  };
  double z = 0;
  for (const auto& ep : tr.episodes) {
    if (ep.kind != mode::stick || !(ep.end > ep.start)) continue;
    // M(t) = N(t)/lambda - t; a switch ends every stick, so N is N(start)
    // over it: int M = N(start) (b - a)/lambda - (b^2 - a^2)/2.
    z += count_upto(ep.start) * (ep.end - ep.start) / lambda -
         (ep.end * ep.end - ep.start * ep.start) / 2;
  }
  double integral_n = 0;  // int_0^ta N(t) dt = sum over switches of (t_a - s)
  for (double s : switches) integral_n += ta - s;
  return {z / ta, (integral_n / lambda - ta * ta / 2) / ta};
}

// The switch count at each stick's start, the switch time sum and hence Z
// and Y, as the sweep computes them, equal a count from the replay's events
// (the paper's model on the reference and lane engines, and a family model:
// mu_s > mu_k with damping on the model engine).
TEST(CausalScore, EngineBookkeepingMatchesACountFromTheEvents) {
  for (const bool family : {false, true}) {
    sweep_spec s = figure_spec(0.5, {3.5}, 30, false, 3);
    if (family) {
      s.base.static_friction = 0.8;
      s.base.kinetic_friction = 0.5;
      s.base.damping = 0.3;
    }
    s.keep_records = true;
    const auto rs = run_sweep(s, 1);
    const model_parameters p = point_parameters(s, 0);
    double sz = 0, sy = 0, szz = 0;
    for (std::uint64_t r = 0; r < 30; ++r) {
      replay_request q;
      q.parameters = p;
      q.seed = s.seed;
      q.realization = r;
      const auto tr = replay(q);
      const auto v = from_trace(tr, 3.5, p.window);
      const auto& rec = rs.records[0][r];
      ASSERT_EQ(rec.events.belt_switches, tr.record.events.belt_switches);
      const double lambda = 3.5;
      const double z = (rec.stick_switch_moment / lambda - rec.stick_time_moment) / p.window;
      const double y = ((static_cast<double>(rec.events.belt_switches) * p.window -
                         rec.events.switch_time_sum) / lambda - p.window * p.window / 2) / p.window;
      EXPECT_NEAR(z, v.z, 1e-9) << "family " << family << " realization " << r;
      EXPECT_NEAR(y, v.y, 1e-9) << "family " << family << " realization " << r;
      sz += z, sy += y, szz += z * z;
    }
    // The point's accumulator holds the same values.
    const auto& m = rs.points[0].stats.stick_fraction_causal_score;
    ASSERT_EQ(m.count(), 30u);
    EXPECT_NEAR(m.sum(0), sz, 1e-9);
    EXPECT_NEAR(m.sum(1), sy, 1e-9);
    EXPECT_NEAR(m.sum(2), szz, 1e-9);
  }
}

struct paired_difference {
  double mean = 0, std_error = 0;
};
// (R(lambda + h) - R(lambda - h)) / 2h from points 0 and 2 of a
// common-random-number sweep with records, paired per realization.
paired_difference central_difference(const result_set& rs, double h) {
  const auto n = rs.records[0].size();
  double m = 0, m2 = 0;
  for (std::size_t r = 0; r < n; ++r) {
    const double d = (rs.records[2][r].stick_fraction - rs.records[0][r].stick_fraction) / (2 * h);
    m += d;
    m2 += d * d;
  }
  m /= static_cast<double>(n);
  const double var = (m2 / static_cast<double>(n) - m * m) * static_cast<double>(n) / (n - 1.0);
  return {m, std::sqrt(var / static_cast<double>(n))};
}

// The derivative check for the causal score: it must agree with
// common-random-number central differences within 3.5 combined standard
// errors at every lambda (mu = 5 and 0.5, and a damped family model with
// mu_s > mu_k), the test must have power (several derivatives far from 0),
// and near the peak of R(lambda) its variance must be far below the full
// score's (the reason the peak finder uses it).
TEST(CausalScore, AgreesWithCommonRandomNumberDifferencesAndHasLessVariance) {
  const std::uint64_t n = 20000;
  int strong = 0;
  struct case_t {
    double mu, lambda;
    bool family;
  };
  for (const auto c : {case_t{5, 0.3, false}, case_t{5, 1.5, false}, case_t{5, 3.7, false},
                       case_t{5, 12, false}, case_t{0.5, 1.0, false}, case_t{0.5, 3.5, false},
                       case_t{0.5, 6.0, false}, case_t{2, 1.0, true}}) {
    const double h = 0.04 * c.lambda;
    auto s = figure_spec(c.mu, {c.lambda - h, c.lambda, c.lambda + h}, n, true, 31);
    if (c.family) {
      s.base.static_friction = 3.0;
      s.base.kinetic_friction = 2.0;
      s.base.damping = 0.2;
    }
    s.keep_records = true;
    const auto rs = run_sweep(s, 2);
    const auto fd = central_difference(rs, h);
    const auto& mid = rs.points[1].stats;
    const auto causal = causal_score_derivative(mid.stick_fraction_causal_score);
    const auto full = score_derivative(mid.stick_fraction_score, mid.stick_fraction, c.lambda);
    std::printf("mu %.1f%s lambda %5.2f: causal %.5f +- %.5f, full score %.5f +- %.5f, CRN "
                "difference %.5f +- %.5f, variance ratio full/causal %.1f\n",
                c.mu, c.family ? " (family)" : "", c.lambda, causal.value, causal.std_error,
                full.value, full.std_error, fd.mean, fd.std_error,
                full.std_error * full.std_error / (causal.std_error * causal.std_error));
    ASSERT_TRUE(std::isfinite(causal.value));
    EXPECT_LT(std::abs(causal.value - fd.mean), 3.5 * std::hypot(causal.std_error, fd.std_error))
        << "mu " << c.mu << " lambda " << c.lambda;
    if (std::abs(fd.mean) > 6 * std::hypot(causal.std_error, fd.std_error)) ++strong;
    if (!c.family && c.lambda > 3 && c.lambda < 4) {  // near the peak of R(lambda)
      EXPECT_GT(full.std_error, 1.3 * causal.std_error) << "mu " << c.mu;
    }
  }
  EXPECT_GE(strong, 4);
}

// The reported standard error against the spread of the estimate over
// independent replicates (mu = 0.5 near the peak).
TEST(CausalScore, StandardErrorMatchesTheSpreadOverReplicates) {
  const int m = 60;
  double mean = 0, m2 = 0, se2 = 0;
  std::vector<double> values;
  for (int k = 0; k < m; ++k) {
    const auto rs = run_sweep(figure_spec(0.5, {3.5}, 2000, false, 700 + k), 2);
    const auto e = causal_score_derivative(rs.points[0].stats.stick_fraction_causal_score);
    values.push_back(e.value);
    se2 += e.std_error * e.std_error / m;
  }
  for (double v : values) mean += v / m;
  double m4 = 0;
  for (double v : values) {
    m2 += (v - mean) * (v - mean) / m;
    m4 += std::pow(v - mean, 4) / m;
  }
  const double var = m2 * m / (m - 1.0), var_se = std::sqrt(std::max(0.0, m4 - m2 * m2) / m);
  std::printf("causal score: replicate variance %.3g +- %.2g, mean reported SE^2 %.3g\n", var,
              var_se, se2);
  EXPECT_NEAR(var, se2, 3.5 * var_se);
}

// R's causal score is kept where it is read (keeps_causal_score): with the
// family statistics, and with means only when the derivatives are selected
// (the peak finder's score method); not for means only without them (a
// `sweep --statistics R`, whose lanes then skip its bookkeeping). Where it
// is kept, it is the same bits as with the family statistics (the
// bookkeeping checked against the events above), on the lanes and the
// reference engine alike; where not, it is empty, the records hold none of
// its sums, and R keeps its bits. The statistics keep the flag through the
// journal's codec.
TEST(CausalScore, KeptWhereItIsReadTheSameBitsOnEveryEngine) {
  std::vector<sweep_spec> models(3, figure_spec(3.0, {0.7, 3.8}, 120, false, 41));
  models[1].base.static_friction = 5.0;  // mu_s > mu_k: the family lanes
  models[2].base.damping = 0.6;          // damped: the scalar engine
  for (const auto& model : models)
    for (auto engine : {sweep_engine::fast, sweep_engine::reference}) {
      sweep_spec family = model;
      family.engine = engine;
      family.keep_records = true;
      family.block_size = 40;
      sweep_spec peak_score = family, means = family;
      peak_score.family_statistics = means.family_statistics = false;
      peak_score.means_only = means.means_only = true;
      peak_score.statistics.derivatives = true;
      ASSERT_TRUE(keeps_causal_score(family));
      ASSERT_TRUE(keeps_causal_score(peak_score));
      ASSERT_FALSE(keeps_causal_score(means));
      const auto f = run_sweep(family, 2), k = run_sweep(peak_score, 2), m = run_sweep(means, 2);
      for (std::size_t p = 0; p < f.points.size(); ++p) {
        const auto& want = f.points[p].stats;
        EXPECT_EQ(want.stick_fraction_causal_score.count(), 120u);
        EXPECT_EQ(k.points[p].stats.stick_fraction_causal_score, want.stick_fraction_causal_score)
            << "point " << p;
        EXPECT_EQ(m.points[p].stats.stick_fraction_causal_score.count(), 0u) << "point " << p;
        EXPECT_EQ(m.points[p].stats.stick_fraction, want.stick_fraction) << "point " << p;
        EXPECT_EQ(k.points[p].stats.stick_fraction, want.stick_fraction) << "point " << p;
        for (std::size_t r = 0; r < 120; ++r) {
          const auto &rf = f.records[p][r], &rk = k.records[p][r], &rm = m.records[p][r];
          EXPECT_EQ(rk.stick_switch_moment, rf.stick_switch_moment);
          EXPECT_EQ(rk.stick_time_moment, rf.stick_time_moment);
          EXPECT_EQ(rk.events.switch_time_sum, rf.events.switch_time_sum);
          EXPECT_EQ(rm.stick_switch_moment, 0.0);
          EXPECT_EQ(rm.stick_time_moment, 0.0);
          EXPECT_EQ(rm.events.switch_time_sum, 0.0);
          EXPECT_EQ(rm.events.belt_switches, rf.events.belt_switches);
        }
      }
      // A block's statistics through the journal's codec keep the flag.
      for (const sweep_spec* s : {&family, &peak_score, &means}) {
        const work_unit u{1, 0};
        const block_result b = simulate_block(*s, u);
        EXPECT_EQ(b.stats.keeps_causal_score(), keeps_causal_score(*s));
        const auto [u2, b2] = deserialize_unit_result(serialize(u, b));
        EXPECT_EQ(b2.stats.keeps_causal_score(), keeps_causal_score(*s));
        EXPECT_TRUE(b2.stats == b.stats);
      }
    }
}

// The journal's codec keeps the flag in bit 1 of the means-only byte, set
// only where the flag differs from the rule before it (family statistics or
// means only), so that journals written before read as before. Every one of
// the eight combinations of (family, means only, kept) goes through and
// comes back, bytes 0 to 3 are what the rule says, and a byte above 3 is
// refused by name. The byte is found as the one position where the
// encodings of two statistics that differ only in means-only differ.
TEST(CausalScore, TheJournalCodecKeepsEveryFlagCombination) {
  const model_parameters p;
  const histogram_spec h;
  const work_unit u{0, 0};
  const auto encode = [&](bool family, bool means, bool kept) {
    block_result b;
    b.stats = point_statistics(p, h, family, true, means, kept);
    return serialize(u, b);
  };
  // Where the means-only byte is.
  const auto a = encode(false, false, false), m = encode(false, true, false);
  ASSERT_EQ(a.size(), m.size());
  std::size_t at = a.size(), differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != m[i]) {
      at = i;
      ++differing;
    }
  ASSERT_EQ(differing, 1u);
  int seen_byte[4] = {0, 0, 0, 0};
  for (bool family : {false, true})
    for (bool means : {false, true})
      for (bool kept : {false, true}) {
        const auto bytes = encode(family, means, kept);
        const auto flag = static_cast<unsigned char>(bytes[at]);
        const bool old_rule = family || means;
        EXPECT_EQ(flag, (means ? 1u : 0u) | (kept != old_rule ? 2u : 0u))
            << "family " << family << " means " << means << " kept " << kept;
        if (flag < 4) ++seen_byte[flag];
        const auto back = deserialize_unit_result(bytes).second.stats;
        EXPECT_EQ(back.family_statistics, family);
        EXPECT_EQ(back.means_only, means);
        EXPECT_EQ(back.keeps_causal_score(), kept);
        EXPECT_EQ(serialize(u, block_result{back, {}}), bytes);  // canonical
      }
  for (int byte = 0; byte < 4; ++byte) EXPECT_EQ(seen_byte[byte], 2) << "byte " << byte;
  for (unsigned char bad : {4, 7, 255}) {
    auto bytes = encode(true, false, true);
    bytes[at] = static_cast<char>(bad);
    try {
      (void)deserialize_unit_result(bytes);
      ADD_FAILURE() << "byte " << int(bad) << " was accepted";
    } catch (const error& e) {
      EXPECT_NE(std::string(e.what()).find("means-only flag: " + std::to_string(bad) + " is not 0 to 3"),
                std::string::npos)
          << e.what();
    }
  }
}

// No causal score where the belt is not switched at the rate lambda.
TEST(CausalScore, OnlyWithPoissonSwitching) {
  sweep_spec s = figure_spec(5, {1.0}, 40, false, 5);
  s.axes.clear();
  s.base.belt_rates = {1.0, 2.0};
  EXPECT_EQ(run_sweep(s, 1).points[0].stats.stick_fraction_causal_score.count(), 0u);
  s.base.belt_rates.clear();
  EXPECT_EQ(run_sweep(s, 1).points[0].stats.stick_fraction_causal_score.count(), 40u);
}

}  // namespace
}  // namespace stickslip
