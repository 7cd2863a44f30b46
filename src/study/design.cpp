// The design of the reproduction: grids, parameter sets, the --quick options.
// Why these grids and these sets: docs/reproduction.md.
#include <cmath>

#include "stickslip/error.hpp"
#include "stickslip/study/design.hpp"

namespace stickslip::study {

namespace {

std::vector<double> log_spaced(double lo, double hi, std::size_t n, bool include_lo,
                               bool include_hi) {
  // n values of lo (hi/lo)^(i/m); the interval ends are dropped on request.
  std::vector<double> v;
  const std::size_t first = include_lo ? 0 : 1;
  const std::size_t m = n - 1 + first + (include_hi ? 0 : 1);
  for (std::size_t i = first; v.size() < n; ++i)
    v.push_back(lo * std::pow(hi / lo, static_cast<double>(i) / static_cast<double>(m)));
  return v;
}

double round_to(double x, double digits) {
  const double f = std::pow(10.0, digits);
  return std::round(x * f) / f;
}

}  // namespace

std::vector<double> paper_lambda_grid() {
  std::vector<double> g;
  for (double x : log_spaced(0.1, 2.6, 20, true, false)) g.push_back(round_to(x, 4));
  for (int i = 0; i <= 7; ++i) g.push_back(round_to(2.6 + 0.3 * i, 4));  // 2.6 .. 4.7
  for (double x : log_spaced(4.7, 30.0, 12, false, true)) g.push_back(round_to(x, 4));
  return g;
}

std::vector<double> paper_mu_grid() { return {0.5, 1, 2, 3, 4, 5, 6, 7}; }
std::vector<double> quick_lambda_grid() { return {0.1, 0.5, 1, 2, 3.5, 3.8, 10, 30}; }
std::vector<double> quick_mu_grid() { return {0.5, 5, 7}; }

std::vector<double> refinement_grid(double center, double log_half_width, std::size_t n) {
  if (n < 2) throw invalid_parameter("refinement points", static_cast<double>(n), ">= 2");
  std::vector<double> g;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = -log_half_width + 2.0 * log_half_width * static_cast<double>(i) /
                                           static_cast<double>(n - 1);
    g.push_back(center * std::exp(u));
  }
  return g;
}

parameter_set printed_parameters() {
  parameter_set s;
  s.id = "printed";
  s.label = "m=1 kg, k=4 N/m, g=9.81 m/s^2, V=1 m/s";
  s.why = "the values printed in Sec. 5 of the paper (g is not printed; standard gravity)";
  s.base = model_parameters{};
  s.base.mass = 1.0;
  s.base.stiffness = 4.0;
  s.base.gravity = 9.81;
  s.base.belt_speed = 1.0;
  s.base.window = 50.0;
  return s;
}

parameter_set concluded_parameters() {
  parameter_set s = printed_parameters();
  s.id = "concluded";
  s.label = "m=1 kg, k=40 N/m, g=9.81 m/s^2, V=1 m/s";
  s.why = "k = 40 N/m: gives the printed d_max = 2 m g mu/(k V) = 2.45 ~ 2.5 s for mu = 5 and "
          "matches the reported maxima of mean R (see the candidates table)";
  s.base.stiffness = 40.0;
  return s;
}

std::vector<parameter_set> candidate_parameter_sets() {
  std::vector<parameter_set> c{printed_parameters(), concluded_parameters()};
  parameter_set s = printed_parameters();
  s.id = "k40_g10";
  s.label = "k=40 N/m, g=10 m/s^2";
  s.why = "k = 40 with rounded gravity: d_max = 2.5 s exactly";
  s.base.stiffness = 40.0;
  s.base.gravity = 10.0;
  c.push_back(s);
  s = printed_parameters();
  s.id = "k4_g1";
  s.label = "k=4 N/m, g=1 m/s^2";
  s.why = "printed k with g = 1: d_max = 2.5 s exactly, same band a = mu/4 as k=40, g=10, "
          "but natural frequency 2 rad/s instead of 6.3";
  s.base.gravity = 1.0;
  c.push_back(s);
  s = printed_parameters();
  s.id = "k4_V10";
  s.label = "k=4 N/m, g=9.81 m/s^2, V=10 m/s";
  s.why = "printed k and g with belt speed 10 m/s: d_max = 2.45 s, the other way to read "
          "the d_max typo";
  s.base.belt_speed = 10.0;
  c.push_back(s);
  return c;
}

study_options quick_options() {
  study_options o;
  o.quick = true;
  o.realizations = 200;
  o.refine_realizations = 400;
  o.refine_points = 7;
  o.candidate_realizations = 100;
  o.candidate_refine_realizations = 200;
  o.peak_halfwidth = 0.25;
  o.candidate_peak_halfwidth = 0.25;
  o.peak_max_realizations = 5'000'000;
  return o;
}

}  // namespace stickslip::study
