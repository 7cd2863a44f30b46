// Laws of uncertain parameters (uncertainty/parameter_law.hpp) and their
// draws (uncertainty/uncertain_draws.hpp). Oracles independent of the code
// under test:
//   - the mean and variance of each law as integrals of its quantile over u
//     (midpoint rule) against law_mean / law_variance's closed forms;
//   - CDF(quantile(u)) = u with CDFs written here from std::erfc, a series
//     of the incomplete gamma function and Simpson's rule on the beta density;
//   - the Kolmogorov-Smirnov distance of 100k draws of the random streams
//     against those CDFs (tolerance: the 99.9 % critical value 1.95/sqrt n);
//   - parse/print round trips to the bit, and every bad input's message.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/random_stream.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"

namespace stickslip {
namespace {

// ---- independent CDFs ----
double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

// Regularized lower incomplete gamma P(a, x) by its series
// P = x^a e^-x / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)) (Abramowitz-Stegun 6.5.29).
double gamma_p(double a, double x) {
  if (x <= 0) return 0.0;
  double term = 1.0, sum = 1.0;
  for (int n = 1; n < 100000 && term > 1e-17 * sum; ++n) {
    term *= x / (a + n);
    sum += term;
  }
  return std::exp(a * std::log(x) - x - std::lgamma(a + 1.0)) * sum;
}

// Regularized incomplete beta I_x(p, q) for p, q >= 1 (bounded, smooth
// density): the trapezoid rule on 10^6 intervals of [0, 1], tabulated once
// and interpolated linearly (errors ~1e-11, far below the tolerances).
double beta_cdf(double p, double q, double x) {
  static std::vector<double> table;
  static double table_p = 0, table_q = 0;
  const int n = 1000000;
  if (table.empty() || table_p != p || table_q != q) {
    const double log_b = std::lgamma(p) + std::lgamma(q) - std::lgamma(p + q);
    auto f = [&](double t) {
      if (t <= 0 || t >= 1) return 0.0;
      return std::exp((p - 1) * std::log(t) + (q - 1) * std::log1p(-t) - log_b);
    };
    table.assign(n + 1, 0.0);
    for (int i = 1; i <= n; ++i)
      table[i] = table[i - 1] + 0.5 * (f((i - 1.0) / n) + f(static_cast<double>(i) / n)) / n;
    table_p = p;
    table_q = q;
  }
  if (x <= 0) return 0.0;
  if (x >= 1) return 1.0;
  const double t = x * n;
  const auto i = static_cast<std::size_t>(t);
  return table[i] + (t - static_cast<double>(i)) * (table[i + 1] - table[i]);
}

struct law_case {
  std::string text;
  std::function<double(double)> cdf;  // written from the law's definition
};

std::vector<law_case> cases() {
  return {
      {"uniform(min=2,max=7)", [](double x) { return std::clamp((x - 2) / 5, 0.0, 1.0); }},
      {"loguniform(min=0.5,max=10)",
       [](double x) { return std::clamp(std::log(x / 0.5) / std::log(20.0), 0.0, 1.0); }},
      {"normal(mean=1,sd=0.1)", [](double x) { return normal_cdf((x - 1) / 0.1); }},
      {"truncnormal(mean=1,sd=0.5,min=0.2,max=1.4)",
       [](double x) {
         const double lo = normal_cdf(-1.6), hi = normal_cdf(0.8);
         return std::clamp((normal_cdf((x - 1) / 0.5) - lo) / (hi - lo), 0.0, 1.0);
       }},
      // An interval far above the mean: the quantile works in the tail.
      {"truncnormal(mean=0,sd=1,min=5,max=9)",
       [](double x) {
         auto q = [](double z) { return 0.5 * std::erfc(z / std::numbers::sqrt2); };
         return std::clamp((q(5) - q(x)) / (q(5) - q(9)), 0.0, 1.0);
       }},
      {"lognormal(mean=5,cv=0.3)",
       [](double x) {
         const double s2 = std::log(1 + 0.09), mu = std::log(5.0) - s2 / 2;
         return x <= 0 ? 0.0 : normal_cdf((std::log(x) - mu) / std::sqrt(s2));
       }},
      {"gamma(mean=5,cv=0.2)", [](double x) { return gamma_p(25.0, x / 0.2); }},
      {"gamma(mean=2,cv=0.8)", [](double x) { return gamma_p(1.0 / 0.64, x / (2 * 0.64)); }},
      // beta on [1, 3] with mean 1.8 and sd 0.3: m' = 0.4, s' = 0.15,
      // p + q = 0.24 / 0.0225 - 1 = 9.666..., p = 3.8666..., q = 5.8.
      {"beta(mean=1.8,sd=0.3,min=1,max=3)",
       [](double x) {
         const double nu = 0.4 * 0.6 / (0.15 * 0.15) - 1;
         return beta_cdf(0.4 * nu, 0.6 * nu, (x - 1) / 2);
       }},
  };
}

TEST(ParameterLaw, MeanAndVarianceAreIntegralsOfTheQuantile) {
  // E X = int_0^1 Q(u) du, E X^2 = int Q(u)^2 du, by the midpoint rule; its
  // error at the tails is O(h sqrt(log 1/h)) for these laws, far below 1e-4.
  const int n = 400000;
  for (const auto& c : cases()) {
    const auto law = parse_law(c.text, "x");
    double s1 = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
      const double q = quantile(law, (i + 0.5) / n);
      s1 += q;
      s2 += q * q;
    }
    const double mean = s1 / n, var = s2 / n - mean * mean;
    EXPECT_NEAR(mean, law_mean(law), 2e-5 * std::abs(law_mean(law)) + 1e-9) << c.text;
    EXPECT_NEAR(var, law_variance(law), 1e-3 * law_variance(law)) << c.text;
  }
}

TEST(ParameterLaw, QuantileInvertsAnIndependentCdf) {
  for (const auto& c : cases()) {
    const auto law = parse_law(c.text, "x");
    for (double u : {1e-6, 0.001, 0.02, 0.1, 0.25, 0.5, 0.75, 0.9, 0.98, 0.999, 1 - 1e-6})
      EXPECT_NEAR(c.cdf(quantile(law, u)), u, 1e-9 + 1e-7 * std::min(u, 1 - u)) << c.text << " u=" << u;
    const auto [lo, hi] = support(law);
    EXPECT_GE(quantile(law, random_stream::open_uniform(0)), lo) << c.text;
    EXPECT_LE(quantile(law, random_stream::open_uniform(~std::uint64_t{0})), hi) << c.text;
  }
}

// A truncnormal that holds its mean, drawn near u = 1: the upper tail
// 1 - F(x) must be 1 - u to relative precision. Computed as Phi^-1 of a
// probability near 1, it lost all digits, and at the largest draw with a
// far upper end (b = 2e299 sd, fuzz_family_toml) Phi rounded to 1 and
// Boost.Math threw (exit 70). Oracle: F from std::erfc, written here.
TEST(ParameterLaw, TruncatedNormalKeepsItsUpperTailDigits) {
  {
    const auto law = parse_law("truncnormal(mean=0,sd=1,min=-10,max=10)", "x");
    const double mass = normal_cdf(10) - normal_cdf(-10);
    for (double t : {1e-6, 1e-9, 1e-12, 1e-15}) {
      const double u = 1 - t, tail = 1 - u;  // 1 - u exactly (Sterbenz)
      const double x = quantile(law, u);
      const double upper = (0.5 * std::erfc(x / std::numbers::sqrt2) -
                            0.5 * std::erfc(10 / std::numbers::sqrt2)) / mass;
      EXPECT_NEAR(upper / tail, 1.0, 1e-9) << "1 - u = " << tail;
    }
  }
  const auto law = parse_law("truncnormal(min=1e-300,mean=1e-61,max=1e300,sd=5.0)", "V");
  const double u = random_stream::open_uniform(~std::uint64_t{0});
  double x = 0;
  ASSERT_NO_THROW(x = quantile(law, u));
  // Half a normal above its mean: P(X > x) = 2 Q(x / sd) = 1 - u.
  EXPECT_NEAR(std::erfc(x / 5.0 / std::numbers::sqrt2) / (1 - u), 1.0, 1e-9) << x;
}

// Beta shapes where Boost.Math's inverse gives up (fuzz_family_toml; both
// were internal errors, exit 70). Oracles: near 0 the beta CDF is
// x^p / (p B(p, q)) (1 + O(x)), with B from std::lgamma; and a shape of
// 7.6e-93 leaves 1 - F(x) < 1e-88 for every x > 0, so the largest draw on
// [0, 1] is the smallest positive double, which (max - min) = 1e-61 scales
// to 0: the draw is min itself.
TEST(ParameterLaw, BetaQuantileWhereBoostGivesUp) {
  const double p = 1.02596, q = 3.47656e-05, m = p / (p + q);
  const auto law = parse_law(
      fmt::format("beta(mean={},sd={},min=0,max=1)", m, std::sqrt(m * (1 - m) / (p + q + 1))), "x");
  const double log_beta = std::lgamma(p) + std::lgamma(q) - std::lgamma(p + q);
  for (double u : {random_stream::open_uniform(0), 1.2015583915594926e-17, 1e-12}) {
    double x = 0;
    ASSERT_NO_THROW(x = quantile(law, u)) << u;
    const double cdf = std::exp(p * std::log(x) - std::log(p) - log_beta);
    EXPECT_NEAR(cdf / u, 1.0, 1e-6) << "u = " << u << ", x = " << x;
  }
  const auto flat = parse_law(
      "beta(min=1e-300,mean=1.3050275395632785e-154,max=1e-61,sd=1.3842526091178292e-108)", "m");
  double top = 0;
  ASSERT_NO_THROW(top = quantile(flat, random_stream::open_uniform(~std::uint64_t{0})));
  EXPECT_EQ(top, 1e-300);
}

TEST(ParameterLaw, DrawsFollowTheLawByKolmogorovSmirnov) {
  const std::size_t n = 100000;
  for (const auto& c : cases()) {
    const std::vector<uncertain_parameter> laws{{"mu", parse_law(c.text, "mu")}};
    std::vector<double> x(n);
    for (std::size_t r = 0; r < n; ++r) x[r] = draw_values(laws, 7, 0x1234, r)[0];
    std::sort(x.begin(), x.end());
    double d = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double f = c.cdf(x[i]);
      d = std::max({d, f - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - f});
    }
    // P(sqrt(n) D > 1.95) = 0.001 (Kolmogorov's limit law).
    EXPECT_LT(d, 1.95 / std::sqrt(static_cast<double>(n))) << c.text;
  }
}

TEST(ParameterLaw, CanonicalTextRoundTripsToTheBit) {
  std::uint64_t z = 12345;
  auto next = [&] {  // splitmix64: arbitrary bit patterns of doubles in a range
    z += 0x9e3779b97f4a7c15ULL;
    std::uint64_t x = z;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return random_stream::open_uniform(x ^ (x >> 31));
  };
  for (int i = 0; i < 2000; ++i) {
    const double a = 0.1 + 10 * next(), b = a + 1e-3 + next(), s = 1e-4 + 0.1 * next();
    for (const parameter_law& law :
         {parameter_law{law_family::uniform, {a, b}}, parameter_law{law_family::loguniform, {a, b}},
          parameter_law{law_family::normal, {a, s}},
          parameter_law{law_family::truncnormal, {a, s, a - s, b}},
          parameter_law{law_family::lognormal, {a, s}}, parameter_law{law_family::gamma, {b, s}},
          parameter_law{law_family::beta, {0.5 * (a + b), 0.1 * s * (b - a), a, b}}}) {
      const std::string text = to_string(law);
      const parameter_law back = parse_law(text, "x");
      ASSERT_EQ(back.family, law.family) << text;
      ASSERT_EQ(back.arguments.size(), law.arguments.size()) << text;
      for (std::size_t k = 0; k < law.arguments.size(); ++k)
        ASSERT_EQ(std::bit_cast<std::uint64_t>(back.arguments[k]),
                  std::bit_cast<std::uint64_t>(law.arguments[k]))
            << text;
    }
  }
  EXPECT_EQ(to_string(parse_law("gamma(cv=0.2, mean=5)", "mu")), "gamma(mean=5,cv=0.2)");
  EXPECT_EQ(to_string(parse_law(" uniform( 2 , 7 ) ", "mu")), "uniform(min=2,max=7)");
  EXPECT_EQ(to_string(parse_law("loguniform(0.5,10)", "lambda")), "loguniform(min=0.5,max=10)");
}

TEST(ParameterLaw, TellsLawsFromValuesAndGrids) {
  for (const char* t : {"gamma(mean=5,cv=0.2)", " uniform (1,2)", "foo(1)"}) EXPECT_TRUE(looks_like_law(t)) << t;
  for (const char* t : {"5", "1,2,3", "lin:1:2:3", "log:0.1:10:5", "", "(1,2)", "1e3", "-inf"})
    EXPECT_FALSE(looks_like_law(t)) << t;
}

// Every parse error exits 2 and names the parameter, the law text and what
// is allowed.
void expect_refused(const std::string& text, const std::string& why) {
  try {
    (void)parse_law(text, "--mu");
    ADD_FAILURE() << text << " was accepted";
  } catch (const error& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.code(), exit_code::invalid_input) << m;
    EXPECT_EQ(m.rfind("--mu: ", 0), 0u) << m;
    EXPECT_NE(m.find(text), std::string::npos) << m;
    EXPECT_NE(m.find(why), std::string::npos) << m;
    EXPECT_TRUE(m.find("allowed: ") != std::string::npos || m.find("known laws: ") != std::string::npos)
        << m;
  }
}

TEST(ParameterLaw, RefusesBadTextNamingParameterLawAndForm) {
  expect_refused("gama(mean=5,cv=0.2)", "unknown law 'gama'");
  expect_refused("gamma(mean=5)", "cv is missing");
  expect_refused("gamma(mean=5,cv=0.2,sd=1)", "gamma has no argument 'sd'");
  expect_refused("gamma(mean=5,mean=4,cv=0.2)", "mean is given twice");
  expect_refused("gamma(mean=5,cv=inf)", "not a finite number");
  expect_refused("gamma(mean=five,cv=0.2)", "not a finite number");
  expect_refused("normal(1,0.1)", "must be named");
  expect_refused("uniform(1,2,3)", "uniform takes 2");
  expect_refused("uniform(1,max=3)", "mixed");
  expect_refused("uniform(min=3,max=1)", "needs min < max");
  expect_refused("loguniform(0,1)", "needs 0 < min < max");
  expect_refused("normal(mean=1,sd=0)", "needs sd > 0");
  expect_refused("truncnormal(mean=0,sd=1,min=50,max=60)", "less than 1e-12");
  expect_refused("lognormal(mean=-1,cv=0.1)", "needs mean > 0");
  expect_refused("gamma(mean=1,cv=0)", "needs cv > 0");
  expect_refused("beta(mean=1,sd=0.1,min=1,max=2)", "min < mean < max");
  expect_refused("beta(mean=1.5,sd=0.5,min=1,max=2)", "sd^2 < (mean-min)(max-mean)");
  expect_refused("gamma(mean=5,cv=0.2", "not a law");
  expect_refused("gamma", "not a law");
}

void expect_invalid_laws(const model_parameters& base, const std::vector<uncertain_parameter>& laws,
                         const std::vector<std::string>& axes, const std::string& message) {
  try {
    validate_laws(base, laws, axes);
    ADD_FAILURE() << message << ": accepted";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

uncertain_parameter law(const char* symbol, const char* text) {
  return {symbol, parse_law(text, symbol)};
}

TEST(ValidateLaws, RefusesLawsThatCanLeaveTheDomain) {
  const model_parameters base;
  expect_invalid_laws(base, {law("m", "normal(mean=1,sd=0.1)")}, {},
                      "--m: normal(mean=1,sd=0.1) can give values <= 0; m must be > 0 (use "
                      "truncnormal, lognormal or gamma)");
  expect_invalid_laws(base, {law("lambda", "uniform(0,2)")}, {}, "--lambda: uniform(min=0,max=2) can give values <= 0");
  expect_invalid_laws(base, {law("c", "normal(mean=1,sd=0.1)")}, {}, "--c: normal(mean=1,sd=0.1) can give values < 0; c must be >= 0");
  expect_invalid_laws(base, {law("r1", "truncnormal(mean=1,sd=1,min=-1,max=2)")}, {},
                      "r1: truncnormal(mean=1,sd=1,min=-1,max=2) can give values <= 0");
  // mu_k > mu_s possible: law against the fixed value, and law against law.
  expect_invalid_laws(base, {law("mu_k", "uniform(3,6)")}, {}, "--mu-k: uniform(min=3,max=6) can exceed mu_s = 5");
  expect_invalid_laws(base, {law("mu_s", "uniform(4,8)")}, {}, "--mu-s: uniform(min=4,max=8) can fall below mu_k = 5");
  expect_invalid_laws(base, {law("mu_s", "uniform(4,8)"), law("mu_k", "uniform(1,4.5)")}, {},
                      "--mu-k: uniform(min=1,max=4.5) can exceed --mu-s: uniform(min=4,max=8)");
  expect_invalid_laws(base, {law("mu", "gamma(mean=5,cv=0.2)")}, {"mu"}, "also a grid axis");
  expect_invalid_laws(base, {law("mu", "gamma(mean=5,cv=0.2)"), law("mu", "uniform(1,2)")}, {}, "second law");
  expect_invalid_laws(base, {{"nu", parse_law("uniform(1,2)", "nu")}}, {}, "nu: uniform(min=1,max=2): unknown parameter");
  expect_invalid_laws(base, {law("mu", "uniform(1,2)"), law("mu_s", "uniform(3,4)")}, {}, "mu sets mu_s and mu_k both");
  expect_invalid_laws(base, {law("v3", "uniform(1,2)")}, {}, "the belt has fewer levels");
  // The backstop at the extreme draws: a tiny window allows no model.
  expect_invalid_laws(base, {law("k", "loguniform(1e-70,1)")}, {}, "can give a model that is not valid");
}

TEST(ValidateLaws, AcceptsLawsInsideTheDomain) {
  model_parameters base;
  base.static_friction = 6;
  base.kinetic_friction = 4;
  EXPECT_NO_THROW(validate_laws(model_parameters{}, std::vector{law("mu", "gamma(mean=5,cv=0.2)"),
                                                                law("k", "lognormal(mean=40,cv=0.1)"),
                                                                law("lambda", "loguniform(0.5,10)")},
                                std::vector<std::string>{"V"}));
  EXPECT_NO_THROW(validate_laws(base, std::vector{law("mu_k", "uniform(3,6)")}));
  EXPECT_NO_THROW(validate_laws(base, std::vector{law("c", "truncnormal(mean=0.1,sd=0.1,min=0,max=1)")}));
  EXPECT_NO_THROW(validate_laws(base, std::vector{law("v1", "normal(mean=1,sd=0.1)")}));
  EXPECT_NO_THROW(validate_laws(base, std::vector{law("r2", "gamma(mean=2,cv=0.5)")}));
}

TEST(UncertainDraws, WordsAreAddressedByIndexAlone) {
  // Word offset + i does not depend on which other words are drawn.
  const auto all = uncertain_uniforms(3, 99, 17, 0, 11);
  for (std::size_t off = 0; off < 8; ++off)
    for (std::size_t cnt = 1; off + cnt <= 11; ++cnt) {
      const auto part = uncertain_uniforms(3, 99, 17, off, cnt);
      for (std::size_t i = 0; i < cnt; ++i) ASSERT_EQ(part[i], all[off + i]);
    }
  // The words are those of substream 3 of realization 17, as random_stream
  // draws them (the stream's contract, random_stream.hpp).
  random_stream rs(3, 99, 17, substream::uncertain_parameters);
  const auto w = rs.next_block();
  EXPECT_EQ(all[1], random_stream::open_uniform(w.v[1]));
  // Another realization, key or seed draws other words.
  EXPECT_NE(uncertain_uniforms(3, 99, 18, 0, 1)[0], all[0]);
  EXPECT_NE(uncertain_uniforms(3, 98, 17, 0, 1)[0], all[0]);
  EXPECT_NE(uncertain_uniforms(4, 99, 17, 0, 1)[0], all[0]);
}

TEST(UncertainDraws, ValuesAreQuantilesOfTheWords) {
  const std::vector laws{law("mu", "gamma(mean=5,cv=0.2)"), law("k", "uniform(30,50)")};
  const auto u = uncertain_uniforms(5, 7, 3, 2, 2);
  const auto v = draw_values(laws, 5, 7, 3, 2);
  EXPECT_EQ(v[0], quantile(laws[0].law, u[0]));
  EXPECT_EQ(v[1], 30 + 20 * u[1]);
  const auto p = with_values(model_parameters{}, laws, v);
  EXPECT_EQ(p.friction_coefficient, v[0]);
  EXPECT_EQ(p.stiffness, v[1]);
}

TEST(UncertainDraws, PointKeyIgnoresTheBaseValueButNotTheLaw) {
  const std::vector laws{law("mu", "gamma(mean=5,cv=0.2)")};
  model_parameters a, b;
  b.friction_coefficient = 3;
  EXPECT_EQ(uncertain_point_key(a, laws), uncertain_point_key(b, laws));
  EXPECT_NE(uncertain_point_key(a, laws), point_key(a));
  EXPECT_NE(uncertain_point_key(a, laws), uncertain_point_key(a, std::vector{law("mu", "gamma(mean=5,cv=0.3)")}));
  EXPECT_NE(uncertain_point_key(a, laws), uncertain_point_key(a, std::vector{law("k", "gamma(mean=5,cv=0.2)")}));
  b = a;
  b.stiffness = 40;
  EXPECT_NE(uncertain_point_key(a, laws), uncertain_point_key(b, laws));
  // The medians stand for the point.
  EXPECT_EQ(with_medians(a, laws).friction_coefficient, quantile(laws[0].law, 0.5));
}

}  // namespace
}  // namespace stickslip
