// Laws of uncertain model parameters (uncertainty/parameter_law.hpp): the
// table of families, the parser, quantiles (Boost.Math), supports and moments.
#include "stickslip/uncertainty/parameter_law.hpp"

#include <boost/math/distributions/beta.hpp>
#include <boost/math/distributions/gamma.hpp>
#include <boost/math/distributions/lognormal.hpp>
#include <boost/math/distributions/normal.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <tuple>

#include "stickslip/error.hpp"

namespace stickslip {
namespace {

// One row per family: its name, its arguments in canonical order, and
// whether two positional arguments (min, max) are allowed. The parser, the
// canonical text and the messages all iterate this table.
struct family_info {
  law_family family;
  const char* name;
  std::array<const char*, 4> arguments;
  std::size_t arity;
  bool positional;
  const char* form;  // how the law is written, for messages
};

constexpr std::array<family_info, 7> family_table{{
    {law_family::uniform, "uniform", {"min", "max"}, 2, true, "uniform(min=A,max=B) with A < B"},
    {law_family::loguniform, "loguniform", {"min", "max"}, 2, true,
     "loguniform(min=A,max=B) with 0 < A < B"},
    {law_family::normal, "normal", {"mean", "sd"}, 2, false, "normal(mean=M,sd=S) with S > 0"},
    {law_family::truncnormal, "truncnormal", {"mean", "sd", "min", "max"}, 4, false,
     "truncnormal(mean=M,sd=S,min=A,max=B) with S > 0, A < B"},
    {law_family::lognormal, "lognormal", {"mean", "cv"}, 2, false,
     "lognormal(mean=M,cv=C) with M > 0, 1e-150 < C < 1e150"},
    {law_family::gamma, "gamma", {"mean", "cv"}, 2, false,
     "gamma(mean=M,cv=C) with M > 0, 1e-5 <= C < 1e150"},
    {law_family::beta, "beta", {"mean", "sd", "min", "max"}, 4, false,
     "beta(mean=M,sd=S,min=A,max=B) with A < M < B, 0 < S^2 < (M-A)(B-M)"},
}};

const family_info& info_of(law_family f) noexcept {
  return family_table[static_cast<std::size_t>(f)];
}

std::string known_laws() {
  std::string s;
  for (const auto& f : family_table) s += (s.empty() ? "" : "; ") + std::string(f.form);
  return s;
}

// invalid_input (exit 2): "<parameter>: <law text>: <problem>; <allowed>".
error invalid_law(std::string_view parameter, std::string_view text, const std::string& problem,
                  const std::string& allowed) {
  return {exit_code::invalid_input,
          fmt::format("{}: {}: {}; {}", parameter, text, problem, allowed)};
}

std::string_view trim(std::string_view s) noexcept {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool parse_number(std::string_view s, double& out) noexcept {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc{} && end == s.data() + s.size();
}

// The standard normal's upper tail Q(x) = P(Z > x) = erfc(x / sqrt 2) / 2,
// accurate far into the tail (no cancellation in 1 - Phi).
double upper_tail(double x) noexcept { return 0.5 * std::erfc(x / std::numbers::sqrt2); }
double density(double x) noexcept {
  return std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi);
}

// Double precision throughout (Boost's default computes the special
// functions of double arguments in long double): about 2x faster per draw,
// still within a few ulps.
using law_policy =
    boost::math::policies::policy<boost::math::policies::promote_double<false>>;

const boost::math::normal_distribution<double, law_policy> standard_normal{0.0, 1.0};

// truncnormal on the standardized interval [a, b] = [(A-M)/S, (B-M)/S]. Work
// in the tail away from the mean, where the probabilities are not rounded
// to 1: reflect an interval above the mean (a > 0) to -b .. -a, so that
// Phi(a), Phi(b) are lower-tail values Q(-a), Q(-b).
struct standard_interval {
  double a, b;
  bool reflected;
  double pa, pb;  // Phi(a), Phi(b) of the (possibly reflected) interval
};
standard_interval standardize(const parameter_law& law) noexcept {
  const auto& x = law.arguments;  // mean, sd, min, max
  double a = (x[2] - x[0]) / x[1], b = (x[3] - x[0]) / x[1];
  const bool reflected = a > 0.0;
  if (reflected) std::tie(a, b) = std::pair{-b, -a};
  return {a, b, reflected, upper_tail(-a), upper_tail(-b)};
}

double check_positive_mass(const parameter_law& law) {
  const auto s = standardize(law);
  return s.pb - s.pa;
}

// Constraints of each family on its own arguments (the table's `form`).
void check_arguments(const parameter_law& law, std::string_view text, std::string_view parameter) {
  const auto& f = info_of(law.family);
  const auto& x = law.arguments;
  auto fail = [&](const std::string& problem) {
    throw invalid_law(parameter, text, problem, std::string("allowed: ") + f.form);
  };
  switch (law.family) {
    case law_family::uniform:
      if (!(x[0] < x[1])) fail("needs min < max");
      break;
    case law_family::loguniform:
      if (!(x[0] > 0.0 && x[0] < x[1])) fail("needs 0 < min < max");
      break;
    case law_family::normal:
      if (!(x[1] > 0.0)) fail("needs sd > 0");
      break;
    case law_family::truncnormal:
      if (!(x[1] > 0.0)) fail("needs sd > 0");
      if (!(x[2] < x[3])) fail("needs min < max");
      // Below 1e-12 of the normal's mass the interval is a typing error, and
      // the quantile's tail probabilities would lose their digits.
      if (!(check_positive_mass(law) >= 1e-12))
        fail(fmt::format("[min, max] holds {:.3g} of normal(mean={},sd={}), less than 1e-12",
                         check_positive_mass(law), x[0], x[1]));
      break;
    case law_family::lognormal:
    case law_family::gamma: {
      if (!(x[0] > 0.0)) fail("needs mean > 0");
      if (!(x[1] > 0.0)) fail("needs cv > 0");
      // The derived shape and scale must be ordinary positive doubles, or the
      // quantile has nothing to compute with (cv = 1e-200 or 1e300).
      const double c2 = x[1] * x[1];
      const bool ok = law.family == law_family::gamma
                          ? std::isnormal(1.0 / c2) && std::isnormal(x[0] * c2) && 1.0 / c2 <= 1e10
                          : std::isnormal(std::log1p(c2)) && std::isfinite(std::log(x[0]));
      // (the range is the family's allowed text, which the failure adds: it
      // said "C > 0" there beside "1e-5 <= cv" here, a new user found)
      if (!ok) fail("needs a cv whose shape and scale are ordinary positive numbers");
      break;
    }
    case law_family::beta: {
      if (!(x[2] < x[0] && x[0] < x[3])) fail("needs min < mean < max");
      if (!(x[1] > 0.0 && x[1] * x[1] < (x[0] - x[2]) * (x[3] - x[0])))
        fail("needs 0 < sd^2 < (mean-min)(max-mean)");
      const double width = x[3] - x[2];
      const double m = (x[0] - x[2]) / width, sd = x[1] / width;
      const double nu = m * (1.0 - m) / (sd * sd) - 1.0;
      // Shapes above 1e10 are a point mass for any use here, and Boost's
      // quantile iterates for minutes on them: refused, like shapes that vanish.
      if (!(std::isnormal(m * nu) && std::isnormal((1.0 - m) * nu) && std::isfinite(width) &&
            m * nu <= 1e10 && (1.0 - m) * nu <= 1e10))
        fail("needs an sd whose beta shapes lie in (0, 1e10] (sd not vanishingly small "
             "against max - min and mean - min)");
      break;
    }
  }
}

// beta(mean, sd, min, max) = min + (max - min) Beta(p, q): on [0, 1] the mean
// m' = (M - A)/(B - A) and variance s'^2 = S^2/(B - A)^2 give, from
// m' = p/(p+q) and s'^2 = m'(1-m')/(p+q+1), p + q = m'(1-m')/s'^2 - 1.
boost::math::beta_distribution<double, law_policy> unit_beta(const parameter_law& law) {
  const auto& x = law.arguments;
  const double width = x[3] - x[2];
  const double m = (x[0] - x[2]) / width, s = x[1] / width;
  const double nu = m * (1.0 - m) / (s * s) - 1.0;
  return {m * nu, (1.0 - m) * nu};
}

// lognormal(mean, cv): log X ~ normal(mu, sigma) with E X = exp(mu + sigma^2/2)
// and cv^2 = exp(sigma^2) - 1, so sigma^2 = log(1 + cv^2), mu = log M - sigma^2/2.
boost::math::lognormal_distribution<double, law_policy> log_normal(const parameter_law& law) {
  const double s2 = std::log1p(law.arguments[1] * law.arguments[1]);
  return {std::log(law.arguments[0]) - 0.5 * s2, std::sqrt(s2)};
}

// gamma(mean, cv): shape k and scale theta with k theta = M, 1/sqrt(k) = cv.
boost::math::gamma_distribution<double, law_policy> gamma_law(const parameter_law& law) {
  const double c2 = law.arguments[1] * law.arguments[1];
  return {1.0 / c2, law.arguments[0] * c2};
}

// The quantile of a gamma or beta law at u. Boost.Math's inverses give up
// on some valid shapes (beta(1.03, 3.5e-5) at u = 5.6e-17: "evaluation
// exceeded 200 iterations"; a shape of 7.6e-93 near u = 1: "range arguments
// in wrong order"; both found by fuzz_family_toml). There, the smallest x in
// [lo, hi] with F(x) >= u is found by bisection on the bits of x (which
// order non-negative doubles): at most 64 CDF evaluations, deterministic,
// and exact to the double. Above the median the complement is compared,
// 1 - u being exact there, so the upper tail keeps its digits.
template <class Law>
double inverse_cdf(const Law& law, double u, double lo, double hi) {
  try {
    return boost::math::quantile(law, u);
  } catch (const std::exception&) {
  }
  auto at_or_above = [&](double x) {
    return u <= 0.5 ? boost::math::cdf(law, x) >= u
                    : boost::math::cdf(boost::math::complement(law, x)) <= 1.0 - u;
  };
  std::uint64_t a = std::bit_cast<std::uint64_t>(lo), b = std::bit_cast<std::uint64_t>(hi);
  while (a < b) {
    const std::uint64_t mid = a + (b - a) / 2;
    if (at_or_above(std::bit_cast<double>(mid))) b = mid;
    else a = mid + 1;
  }
  return std::bit_cast<double>(a);
}

}  // namespace

const char* to_string(law_family f) noexcept { return info_of(f).name; }

std::string to_string(const parameter_law& law) {
  const auto& f = info_of(law.family);
  std::string s = std::string(f.name) + '(';
  // fmt's "{}" is the shortest text that reads back to the same double:
  // parse_law(to_string(law)) == law bit for bit.
  for (std::size_t i = 0; i < law.arguments.size() && i < f.arity; ++i)
    s += fmt::format("{}{}={}", i ? "," : "", f.arguments[i], law.arguments[i]);
  return s + ')';
}

bool looks_like_law(std::string_view text) noexcept {
  text = trim(text);
  std::size_t i = 0;
  while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_'))
    ++i;
  if (i == 0 || !std::isalpha(static_cast<unsigned char>(text[0]))) return false;
  const std::string_view rest = trim(text.substr(i));
  return !rest.empty() && rest.front() == '(';
}

parameter_law parse_law(std::string_view text_in, std::string_view parameter) {
  const std::string_view text = trim(text_in);
  const auto open = text.find('(');
  if (open == std::string_view::npos || text.back() != ')')
    throw invalid_law(parameter, text, "not a law",
                      "allowed: NAME(ARG=VALUE,...), one of: " + known_laws());
  const std::string_view name = trim(text.substr(0, open));
  const auto row = std::find_if(family_table.begin(), family_table.end(),
                                [&](const family_info& f) { return name == f.name; });
  if (row == family_table.end())
    throw invalid_law(parameter, text, fmt::format("unknown law '{}'", name),
                      "known laws: " + known_laws());
  const family_info& f = *row;
  auto fail = [&](const std::string& problem) {
    throw invalid_law(parameter, text, problem, std::string("allowed: ") + f.form);
  };
  // The arguments, split at commas (no nesting: the values are numbers).
  std::vector<std::string_view> items;
  std::string_view inside = text.substr(open + 1, text.size() - open - 2);
  if (inside.find_first_of("()") != std::string_view::npos) fail("unbalanced parentheses");
  if (!trim(inside).empty()) {
    for (std::size_t start = 0;;) {
      const auto comma = inside.find(',', start);
      items.push_back(trim(inside.substr(start, comma - start)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
  }
  parameter_law law{f.family, std::vector<double>(f.arity, 0.0)};
  std::array<bool, 4> given{};
  std::size_t positional = 0, named = 0;
  for (std::size_t k = 0; k < items.size(); ++k) {
    const std::string_view item = items[k];
    const auto eq = item.find('=');
    std::size_t slot = 0;
    std::string_view value = item;
    if (eq == std::string_view::npos) {
      if (!f.positional)
        fail(fmt::format("'{}' has no name: the arguments of {} must be named", item, f.name));
      slot = positional++;
      if (slot >= f.arity)
        fail(fmt::format("{} arguments: {} takes {} (min, max)", items.size(), f.name, f.arity));
    } else {
      ++named;
      const std::string_view key = trim(item.substr(0, eq));
      value = item.substr(eq + 1);
      const auto* it = std::find_if(f.arguments.begin(), f.arguments.begin() + f.arity,
                                    [&](const char* a) { return a && key == a; });
      if (it == f.arguments.begin() + f.arity)
        fail(fmt::format("{} has no argument '{}'", f.name, key));
      slot = static_cast<std::size_t>(it - f.arguments.begin());
      if (given[slot]) fail(fmt::format("{} is given twice", key));
    }
    if (positional > 0 && named > 0)
      fail("positional and named arguments mixed: name both or neither");
    double v = 0.0;
    if (!parse_number(value, v) || !std::isfinite(v))
      fail(fmt::format("{} = '{}' is not a finite number", f.arguments[slot], trim(value)));
    given[slot] = true;
    law.arguments[slot] = v;
  }
  for (std::size_t i = 0; i < f.arity; ++i)
    if (!given[i]) fail(fmt::format("{} is missing", f.arguments[i]));
  check_arguments(law, text, parameter);
  return law;
}

double quantile(const parameter_law& law, double u) {
  const auto& x = law.arguments;
  switch (law.family) {
    case law_family::uniform:
      return std::clamp(x[0] + (x[1] - x[0]) * u, x[0], x[1]);
    case law_family::loguniform: {
      const double la = std::log(x[0]), lb = std::log(x[1]);
      return std::clamp(std::exp(la + (lb - la) * u), x[0], x[1]);
    }
    case law_family::normal:
      return x[0] + x[1] * boost::math::quantile(standard_normal, u);
    case law_family::truncnormal: {
      // Inverse transform of Phi restricted to [a, b]:
      // z = Phi^-1(Phi(a) + u (Phi(b) - Phi(a))), in the reflected frame
      // when the interval lies above the mean (standardize).
      const auto s = standardize(law);
      const double mass = s.pb - s.pa;
      const double p = s.reflected ? s.pb - u * mass : s.pa + u * mass;
      constexpr double inf = std::numeric_limits<double>::infinity();
      double z;
      if (p <= 0.5) {
        z = p <= 0.0 ? -inf : boost::math::quantile(standard_normal, std::clamp(p, s.pa, s.pb));
      } else {
        // Above the median Phi(z) is rounded near 1 (to 1 itself when b is far
        // out, where Boost.Math would throw): invert the upper tail instead,
        // Q(z) = Q(b) + (1 - u)(Phi(b) - Phi(a)). Only an interval that holds
        // the mean gets here, never the reflected frame (b <= 0 there).
        const double q = upper_tail(s.b) + (1.0 - u) * mass;
        z = q <= 0.0 ? inf : boost::math::quantile(boost::math::complement(standard_normal, std::min(q, 0.5)));
      }
      if (s.reflected) z = -z;
      return std::clamp(x[0] + x[1] * z, x[2], x[3]);
    }
    case law_family::lognormal:
      return boost::math::quantile(log_normal(law), u);
    case law_family::gamma:
      return inverse_cdf(gamma_law(law), u, 0.0, std::numeric_limits<double>::max());
    case law_family::beta:
      return std::clamp(x[2] + (x[3] - x[2]) * inverse_cdf(unit_beta(law), u, 0.0, 1.0), x[2], x[3]);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::pair<double, double> support(const parameter_law& law) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const auto& x = law.arguments;
  switch (law.family) {
    case law_family::uniform:
    case law_family::loguniform:
      return {x[0], x[1]};
    case law_family::normal:
      return {-inf, inf};
    case law_family::truncnormal:
    case law_family::beta:
      return {x[2], x[3]};
    case law_family::lognormal:
    case law_family::gamma:
      return {0.0, inf};
  }
  return {-inf, inf};
}

double law_mean(const parameter_law& law) {
  const auto& x = law.arguments;
  switch (law.family) {
    case law_family::uniform:
      return 0.5 * (x[0] + x[1]);
    case law_family::loguniform:  // int_A^B x dx / (x log(B/A))
      return (x[1] - x[0]) / std::log(x[1] / x[0]);
    case law_family::truncnormal: {
      // E Z on [a, b] = (phi(a) - phi(b)) / (Phi(b) - Phi(a)); reflected: -E.
      const auto s = standardize(law);
      const double ez = (density(s.a) - density(s.b)) / (s.pb - s.pa);
      return x[0] + x[1] * (s.reflected ? -ez : ez);
    }
    case law_family::normal:
    case law_family::lognormal:
    case law_family::gamma:
    case law_family::beta:
      return x[0];
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double law_variance(const parameter_law& law) {
  const auto& x = law.arguments;
  switch (law.family) {
    case law_family::uniform:
      return (x[1] - x[0]) * (x[1] - x[0]) / 12.0;
    case law_family::loguniform: {  // E X^2 = (B^2 - A^2) / (2 log(B/A))
      const double l = std::log(x[1] / x[0]), m = (x[1] - x[0]) / l;
      return (x[1] * x[1] - x[0] * x[0]) / (2.0 * l) - m * m;
    }
    case law_family::normal:
    case law_family::beta:
      return x[1] * x[1];
    case law_family::truncnormal: {
      // Var Z on [a, b] = 1 + (a phi(a) - b phi(b))/Z - ((phi(a) - phi(b))/Z)^2,
      // Z = Phi(b) - Phi(a) (Johnson, Kotz, Balakrishnan 1994, ch. 13);
      // the reflection does not change it.
      const auto s = standardize(law);
      const double z = s.pb - s.pa;
      const double e = (density(s.a) - density(s.b)) / z;
      return x[1] * x[1] * (1.0 + (s.a * density(s.a) - s.b * density(s.b)) / z - e * e);
    }
    case law_family::lognormal:
    case law_family::gamma:
      return x[0] * x[0] * x[1] * x[1];
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace stickslip
