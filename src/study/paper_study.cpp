// Running the study of the founding paper: each set's main sweep, then the
// peak search and the 0.1.0 quadratic fit for each mu (design.cpp says what).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "stickslip/error.hpp"
#include "stickslip/study/paper_study.hpp"

namespace stickslip::study {

namespace {

using clock = std::chrono::steady_clock;
double seconds_since(clock::time_point t0) {
  return std::chrono::duration<double>(clock::now() - t0).count();
}

}  // namespace

maximum_view best_maximum(const mu_refinement& r) {
  if (r.located.valid) {
    const auto& p = r.located.result;
    return {p.max, p.max_lo, p.max_hi, p.argmax, p.argmax_lo, p.argmax_hi, true};
  }
  return {r.grid_max,        r.grid_max - r.grid_max_ci95, r.grid_max + r.grid_max_ci95,
          r.grid_max_lambda, r.grid_max_lambda,            r.grid_max_lambda,
          false};
}

const mu_refinement* find_refinement(const set_study& s, double mu) {
  const mu_refinement* nearest = nullptr;
  for (const auto& r : s.refinements)
    if (!nearest || std::abs(r.mu - mu) < std::abs(nearest->mu - mu)) nearest = &r;
  return nearest && std::abs(nearest->mu - mu) < 1e-9 ? nearest : nullptr;
}

std::vector<const point_result*> points_at_mu(const result_set& rs, double mu) {
  std::vector<const point_result*> out;
  for (const auto& p : rs.points)
    if (p.parameters.friction_coefficient == mu) out.push_back(&p);
  std::sort(out.begin(), out.end(), [](auto* a, auto* b) {
    return a->parameters.switch_rate < b->parameters.switch_rate;
  });
  return out;
}

namespace {

sweep_spec base_spec(const parameter_set& set, const study_options& o) {
  sweep_spec s;
  s.base = set.base;
  s.seed = o.seed;
  s.realizations = o.realizations;
  // x0, x'0 ~ U[-1, 1] (paper, Sec. 5); the belt starts at +V or -V with equal
  // odds (by the symmetry x -> -x of the model and of U[-1,1]^2 this gives
  // the same statistics as always starting at +V).
  s.initial = initial_condition_law{};
  // The study reports the paper's statistics only; the family's cost it
  // about 15 % (sweep_spec::family_statistics, docs/performance.md).
  s.family_statistics = false;
  return s;
}

// Every sweep of the study goes through the caller's executor (the command
// line's is journaled: resume, MPI), else through run_sweep.
result_set execute(const study_options& o, const sweep_spec& s, const std::string& id) {
  return o.execute ? o.execute(s, id) : run_sweep(s, o.threads);
}

// The peak search for one mu over the main grid's lambda range: R over
// lambda with common random numbers (`stickslip peak`'s default method).
located_peak locate_peak(const sweep_spec& base, const std::vector<double>& lambda,
                         double halfwidth, const study_options& o, const std::string& id) {
  located_peak l;
  auto& q = l.request;
  q.spec = base;
  q.spec.axes.clear();
  q.over = "lambda";
  q.statistic = &precision::peak_statistic("statistic", "R");
  q.options.lo = *std::min_element(lambda.begin(), lambda.end());
  q.options.hi = *std::max_element(lambda.begin(), lambda.end());
  q.options.log_scan = q.options.hi >= 4 * q.options.lo;
  q.options.target_halfwidth = halfwidth;
  q.options.max_total_realizations = o.peak_max_realizations;
  q.method = precision::peak_method::common;
  q.threads = o.threads;
  try {
    l.result = o.locate ? o.locate(q, id) : precision::find_peak_by_sweeps(q);
    l.valid = true;
  } catch (const error& e) {
    // The first scan peaked at an end of the range: no interior maximum to
    // locate; the report quotes the grid maximum and says why.
    if (e.code() != exit_code::invalid_input) throw;
    l.note = e.what();
  }
  return l;
}

mu_refinement refine_mu(const parameter_set& set, const result_set& sweep, double mu,
                        const study_options& o, std::uint64_t realizations, double halfwidth) {
  mu_refinement r;
  r.mu = mu;
  const auto pts = points_at_mu(sweep, mu);
  if (pts.empty()) throw invalid_parameter("refinement mu", mu, "a mu of the main grid");
  std::size_t best = 0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    if (pts[i]->stats.stick_fraction.mean() > pts[best]->stats.stick_fraction.mean()) best = i;
  r.grid_argmax = best;
  r.grid_max = pts[best]->stats.stick_fraction.mean();
  r.grid_max_ci95 = pts[best]->stats.stick_fraction.ci95_half_width();
  r.grid_max_lambda = pts[best]->parameters.switch_rate;

  sweep_spec s = base_spec(set, o);
  s.base.friction_coefficient = mu;
  std::vector<double> lambda;
  for (const auto* q : pts) lambda.push_back(q->parameters.switch_rate);
  r.located = locate_peak(s, lambda, halfwidth, o, fmt::format("{}-peak-mu-{}", set.id, mu));
  s.realizations = realizations;
  s.axes = {axis{"lambda", refinement_grid(r.grid_max_lambda, o.refine_log_half_width,
                                           o.refine_points)}};
  r.fine = execute(o, s, fmt::format("{}-refine-mu-{}", set.id, mu));
  std::vector<double> lam, mean, se;
  for (const auto& p : r.fine.points) {
    lam.push_back(p.parameters.switch_rate);
    mean.push_back(p.stats.stick_fraction.mean());
    se.push_back(p.stats.stick_fraction.std_error());
  }
  // Bootstrap seed: the study seed, tagged by set and mu so every fit has its own stream.
  const std::uint64_t tag = point_key(s.base);
  r.quadratic = fit_peak(lam, mean, se, r.grid_max_lambda, o.seed, tag);
  return r;
}

// One parameter set's part of the study: its main sweep over (mu, lambda),
// then a refinement of the maximum of mean R for each mu of `refine`.
struct design {
  parameter_set set;
  std::vector<double> lambda, mu, refine;
  std::uint64_t realizations = 0, refine_realizations = 0;
  double peak_halfwidth = 0;
  bool candidate = false;  // one of the other candidate sets (reduced design)
};

std::vector<design> study_designs(const study_options& o) {
  const auto lambda =
      !o.lambda.empty() ? o.lambda : (o.quick ? quick_lambda_grid() : paper_lambda_grid());
  const auto mu = !o.mu.empty() ? o.mu : (o.quick ? quick_mu_grid() : paper_mu_grid());
  const auto refine = !o.refine_mu.empty() ? o.refine_mu : mu;
  std::vector<design> out;
  for (const auto& set : {printed_parameters(), concluded_parameters()})
    out.push_back({set, lambda, mu, refine, o.realizations, o.refine_realizations,
                   o.peak_halfwidth, false});
  if (o.candidates) {
    // The other candidates on a reduced design: the three mu the paper
    // quotes, the same lambda grid, fewer realizations.
    const std::vector<double> mu3{0.5, 5, 7};
    for (const auto& c : candidate_parameter_sets()) {
      if (c.id == "printed" || c.id == "concluded") continue;
      out.push_back({c, lambda, mu3, mu3, o.candidate_realizations,
                     o.candidate_refine_realizations, o.candidate_peak_halfwidth, true});
    }
  }
  return out;
}

std::pair<std::string, sweep_spec> main_sweep_of(const design& d, const study_options& o) {
  sweep_spec s = base_spec(d.set, o);
  s.realizations = d.realizations;
  s.axes = {axis{"mu", d.mu}, axis{"lambda", d.lambda}};
  return {d.set.id + "-sweep", s};
}

set_study run_design(const design& d, const study_options& o, const study_log& log) {
  const auto t0 = clock::now();
  set_study st;
  st.set = d.set;
  const auto [id, s] = main_sweep_of(d, o);
  if (log)
    log(fmt::format("[{}] sweep: {} mu x {} lambda x {} realizations", d.set.id, d.mu.size(),
                    d.lambda.size(), d.realizations));
  st.sweep = execute(o, s, id);
  st.sweep_seconds = st.sweep.elapsed_seconds;
  for (double m : d.refine) {
    if (log)
      log(fmt::format("[{}] locating the maximum of mean R for mu = {} (peak to +-{} in "
                      "lambda; the 0.1.0 quadratic on {} lambda x {})",
                      d.set.id, m, d.peak_halfwidth, o.refine_points, d.refine_realizations));
    st.refinements.push_back(
        refine_mu(d.set, st.sweep, m, o, d.refine_realizations, d.peak_halfwidth));
  }
  st.seconds = seconds_since(t0);
  if (log) log(fmt::format("[{}] done in {:.1f} s", d.set.id, st.seconds));
  return st;
}

}  // namespace

set_study run_set_study(const parameter_set& set, const study_options& o, const study_log& log) {
  for (const auto& d : study_designs(o))
    if (d.set.id == set.id) return run_design(d, o, log);
  auto d = study_designs(o).front();
  d.set = set;
  return run_design(d, o, log);
}

std::vector<std::pair<std::string, sweep_spec>> main_sweeps(const study_options& o) {
  std::vector<std::pair<std::string, sweep_spec>> out;
  for (const auto& d : study_designs(o)) out.push_back(main_sweep_of(d, o));
  return out;
}

study_result run_paper_study(const study_options& o, const study_log& log) {
  const auto t0 = clock::now();
  study_result r;
  r.options = o;
  r.threads = o.threads ? o.threads : std::max(1u, std::thread::hardware_concurrency());
  for (const auto& d : study_designs(o))
    (d.candidate ? r.candidates : r.sets).push_back(run_design(d, o, log));
  r.seconds = seconds_since(t0);
  return r;
}

}  // namespace stickslip::study
