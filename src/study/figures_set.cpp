// The figures of one parameter set: the paper's Fig. 2, 4, 5, 6a, 6b, 7, a
// convergence figure and the refinement of the maximum of mean R.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "figures_common.hpp"
#include "stickslip/error.hpp"
#include "stickslip/trajectory.hpp"

namespace stickslip::study {

using detail::gp_preamble;
using detail::gp_render_loop;
using detail::gp_string;
using detail::num;

namespace {

constexpr const char* lambda_label = "λ, belt switch rate [1/s]";

figure make(const std::string& dir, const std::string& key, const std::string& stem,
            std::string title, std::string caption) {
  figure f;
  f.key = key;
  f.dir = dir;
  f.stem = stem;
  f.title = std::move(title);
  f.caption = std::move(caption);
  return f;
}

std::string set_note(const set_study& s) {
  return detail::parameter_line(s.set.base);
}

// ---- Fig. 2: one realization ----
figure fig2(const set_study& s, const std::string& dir, bool render) {
  const double mu = detail::nearest_mu(s.sweep, 5.0), lambda = 1.0, t_end = 15.0;
  model_parameters p = s.set.base;
  p.friction_coefficient = mu;
  p.switch_rate = lambda;
  const auto trace = sample_realization(s.sweep.spec, p, 0, 0.005, t_end);
  auto f = make(dir, "fig2", "fig2_realization", "Fig. 2: one realization",
                fmt::format("One realization (number 0, seed {}) at mu = {}, lambda = {} 1/s, "
                            "first {} s of t_a = {} s; {}. Top: position x(t) with the stick "
                            "band |x| <= a = mu m g/k = {:.4g} m. Bottom: mass velocity x'(t) "
                            "and belt velocity v(t). Shaded: stick intervals. Sampled every 5 "
                            "ms from the exact closed-form segments.",
                            s.sweep.spec.seed, mu, lambda, t_end, p.window, set_note(s),
                            p.band_half_width()));
  std::string dat = "# t[s] x[m] xdot[m/s] v[m/s] stick(0/1)\n";
  std::vector<std::pair<double, double>> sticks;
  for (std::size_t i = 0; i < trace.size(); ++i) {
    const auto& q = trace[i];
    dat += fmt::format("{} {} {} {} {}\n", num(q.t), num(q.x), num(q.xdot), num(q.v),
                       q.stick ? 1 : 0);
    if (q.stick && (i == 0 || !trace[i - 1].stick)) sticks.emplace_back(q.t, q.t);
    if (q.stick) sticks.back().second = q.t;
  }
  std::string objects;
  int id = 1;
  for (auto [a, b] : sticks)
    objects += fmt::format(
        "set object {} rect from {}, graph 0 to {}, graph 1 fc rgb \"#f0c000\" fs solid 0.3 "
        "noborder behind\n",
        id++, num(a), num(b));
  const double a = p.band_half_width();
  std::string body = fmt::format(
      "  set multiplot layout 2,1 title {title}\n"
      "  set xrange [0:{tend}]\n"
      "  set ylabel \"x, position [m]\"\n"
      "  unset xlabel\n"
      "  plot \"fig2_realization.dat\" u 1:2 w l lt 1 title \"x(t)\", "
      "{a} w l lt 8 dt 2 title \"band edges ±a\", -{a} w l lt 8 dt 2 notitle, "
      "NaN w boxes fc rgb \"#f0c000\" fs solid 0.3 title \"stick\"\n"
      "  set ylabel \"velocity [m/s]\"\n"
      "  set xlabel \"t, time [s]\"\n"
      "  plot \"fig2_realization.dat\" u 1:3 w l lt 2 title \"x'(t), mass\", "
      "\"\" u 1:4 w l lt 7 lw 1.5 title \"v(t), belt\", "
      "NaN w boxes fc rgb \"#f0c000\" fs solid 0.3 title \"stick\"\n"
      "  unset multiplot\n",
      fmt::arg("title", gp_string(fmt::format("One realization: μ={}, λ={} 1/s, {}", mu, lambda,
                                              set_note(s)))),
      fmt::arg("tend", num(t_end)), fmt::arg("a", num(a)));
  std::string script = gp_preamble(f, 1100, 750) + objects +
                       "set key outside right top\n"
                       "set lmargin at screen 0.07\nset rmargin at screen 0.80\n" +
                       gp_render_loop(f, 1100, 750, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

// ---- Fig. 4: histograms of the first stick duration ----
figure fig4(const set_study& s, const std::string& dir, bool render) {
  const double mu = detail::nearest_mu(s.sweep, 5.0);
  const auto lams = detail::nearest_lambdas(s.sweep, {0.1, 0.5, 1.0, 2.0, 3.8, 10.0});
  const auto pts = points_at_mu(s.sweep, mu);
  model_parameters p = s.set.base;
  p.friction_coefficient = mu;
  const double dmax = p.max_stick_duration();
  auto f = make(dir, "fig4", "fig4_first_stick_hist",
                "Fig. 4: normalized histograms of the first stick duration D_1",
                fmt::format("Normalized histograms (densities, {} bins on [0, d_max]) of the "
                            "first stick duration D_1 at mu = {} for {} values of lambda, {} "
                            "realizations each; {}. Line: the same for D, all sticks pooled (the "
                            "paper's text speaks of D, its caption of the first stick). Dashed: "
                            "d_max = 2 m g mu/(k V) = {:.4g} s. Realizations without any stick "
                            "are left out of D_1.",
                            s.sweep.spec.histograms.bins, mu, lams.size(),
                            s.sweep.spec.realizations, set_note(s), dmax));
  std::string dat = "# blocks (gnuplot index) in the order of the lambda values below\n";
  std::string body = fmt::format("  set multiplot layout 2,3 title {}\n",
                                 gp_string(fmt::format("First stick duration D_1, μ={}, {}; "
                                                       "dashed: d_{{max}}={:.3g} s",
                                                       mu, set_note(s), dmax)));
  int block = 0;
  for (double lam : lams) {
    const auto it = std::find_if(pts.begin(), pts.end(), [&](auto* q) {
      return q->parameters.switch_rate == lam;
    });
    if (it == pts.end()) continue;
    const auto& h = (*it)->stats.first_stick_duration_hist;
    const auto& hd = (*it)->stats.stick_duration_hist;  // same bins: [0, d_max]
    dat += fmt::format("# lambda = {} 1/s; columns: bin center [s], density of D_1 [1/s], "
                       "count of D_1, density of D (all sticks) [1/s]\n",
                       num(lam));
    double top = 0;  // the highest bar or step of either histogram
    for (std::size_t i = 0; i < h.bins(); ++i) {
      dat += fmt::format("{} {} {} {}\n", num(h.center(i)), num(h.density(i)), h.count(i),
                         i < hd.bins() ? num(hd.density(i)) : "NaN");
      top = std::max({top, h.density(i), i < hd.bins() ? hd.density(i) : 0.0});
    }
    dat += "\n\n";
    body += fmt::format(
        "  set title \"λ = {} 1/s (n = {})\"\n"
        "  set xlabel \"D_1, first stick duration [s]\"\n"
        "  set ylabel \"density [1/s]\"\n"
        "  set xrange [0:{dmax}*1.05]\n"
        "  set yrange [0:{ymax}]\n"
        "  set arrow 1 from {dmax}, graph 0 to {dmax}, graph 1 nohead dt 2 lc rgb \"#555555\"\n"
        "  plot \"fig4_first_stick_hist.dat\" index {blk} u 1:2 w boxes lt 1 fs solid 0.5 "
        "title \"D_1, first stick\", \"\" index {blk} u 1:4 w histeps lt 2 lw 1.5 title "
        "\"D, all sticks\"\n",
        fmt::format("{:.3g}", lam), h.total(), fmt::arg("dmax", num(dmax)),
        fmt::arg("blk", block),
        // Explicit, with room for the key: gnuplot's autoscale ignores the
        // histeps line, which clipped the D peak at d_max for small lambda.
        fmt::arg("ymax", num(top > 0 ? 1.25 * top : 1.0)));
    ++block;
  }
  body += "  unset multiplot\n";
  std::string script = gp_preamble(f, 1300, 800) + "set boxwidth 1.0 relative\nset key top right font \",9\"\n" +
                       gp_render_loop(f, 1300, 800, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

// A mean with its CI band against lambda at one mu (Fig. 5, 6a, 6b).
std::string band_dat(const std::vector<const point_result*>& pts,
                     const mean_variance point_statistics::*stat, const std::string& what) {
  std::string dat = fmt::format("# lambda[1/s] mean({0}) ci95_lo ci95_hi n\n", what);
  for (auto* q : pts) {
    const auto& mv = q->stats.*stat;
    dat += fmt::format("{} {} {} {} {}\n", num(q->parameters.switch_rate), num(mv.mean()),
                       num(mv.mean() - mv.ci95_half_width()),
                       num(mv.mean() + mv.ci95_half_width()), mv.count());
  }
  return dat;
}

figure fig5(const set_study& s, const std::string& dir, bool render) {
  const double mu = detail::nearest_mu(s.sweep, 5.0);
  auto f = make(dir, "fig5", "fig5_stick_duration", "Fig. 5: mean stick duration",
                fmt::format("Estimated mean stick duration (all sticks pooled) against lambda "
                            "at mu = {}, with the 95 % confidence band (normal approximation, "
                            "mean ± 1.96 SE); {} realizations per point; {}.",
                            mu, s.sweep.spec.realizations, set_note(s)));
  const auto dat = band_dat(points_at_mu(s.sweep, mu), &point_statistics::stick_duration, "D [s]");
  const std::string body = fmt::format(
      "  set title {}\n"
      "  plot \"fig5_stick_duration.dat\" u 1:3:4 w filledcurves lt 1 title \"95 % CI\", "
      "\"\" u 1:2 w lp lt 1 pt 7 ps 0.6 title \"mean stick duration\"\n",
      gp_string(fmt::format("Mean stick duration, μ={}, {}", mu, set_note(s))));
  const std::string script = gp_preamble(f, 1000, 650) + "set logscale x\nset autoscale xfix\n" +
                             fmt::format("set xlabel {}\n", gp_string(lambda_label)) +
                             "set ylabel \"mean stick duration [s]\"\n" +
                             gp_render_loop(f, 1000, 650, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

figure fig6a(const set_study& s, const std::string& dir, bool render) {
  const double mu = detail::nearest_mu(s.sweep, 5.0);
  auto f = make(dir, "fig6a", "fig6a_sticks_per_time", "Fig. 6a: number of sticks per time",
                fmt::format("Estimated mean number of sticks divided by t_a, E[S_T]/t_a, "
                            "against lambda at mu = {}, with the 95 % confidence band; {} "
                            "realizations per point; {}.",
                            mu, s.sweep.spec.realizations, set_note(s)));
  const auto dat =
      band_dat(points_at_mu(s.sweep, mu), &point_statistics::sticks_per_time, "S_T/t_a [1/s]");
  const std::string body = fmt::format(
      "  set title {}\n"
      "  plot \"fig6a_sticks_per_time.dat\" u 1:3:4 w filledcurves lt 2 title \"95 % CI\", "
      "\"\" u 1:2 w lp lt 2 pt 7 ps 0.6 title \"mean S_T/t_a\", x w l lt 8 dt 3 title "
      "\"belt switch rate λ\"\n",
      gp_string(fmt::format("Sticks per unit time, μ={}, {}", mu, set_note(s))));
  const std::string script = gp_preamble(f, 1000, 650) + "set logscale xy\nset autoscale xfix\n" +
                             fmt::format("set xlabel {}\n", gp_string(lambda_label)) +
                             "set ylabel \"S_T / t_a, sticks per second [1/s]\"\n"
                             "set key left top\n" +
                             gp_render_loop(f, 1000, 650, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

// "lambda R lambda_lo lambda_hi R_lo R_hi" of the located maximum, or of the
// grid maximum (with its CI) when there is none.
std::string peak_row(const mu_refinement& r) {
  const auto p = best_maximum(r);
  return fmt::format("{} {} {} {} {} {}", num(p.lambda), num(p.R), num(p.lambda_lo),
                     num(p.lambda_hi), num(p.R_lo), num(p.R_hi));
}

figure fig6b(const set_study& s, const std::string& dir, bool render) {
  const double mu = detail::nearest_mu(s.sweep, 5.0);
  const auto* r = find_refinement(s, mu);
  auto f = make(dir, "fig6b", "fig6b_stick_fraction", "Fig. 6b: mean relative stick time R",
                fmt::format("Estimated mean of R (total stick time / t_a) against lambda at "
                            "mu = {}, with the 95 % confidence band; {} realizations per point; "
                            "{}. Marked: the maximum located by the refinement (lambda*, R*) "
                            "with 95 % bootstrap intervals, and the paper's claim (almost 80 % "
                            "at lambda = 3.8 1/s).",
                            mu, s.sweep.spec.realizations, set_note(s)));
  auto dat = band_dat(points_at_mu(s.sweep, mu), &point_statistics::stick_fraction, "R");
  dat += "\n\n# refined maximum: lambda* R* lambda_lo lambda_hi R_lo R_hi\n";
  dat += r ? peak_row(*r) + "\n" : "NaN NaN NaN NaN NaN NaN\n";
  const std::string body = fmt::format(
      "  set title {}\n"
      "  plot \"fig6b_stick_fraction.dat\" index 0 u 1:3:4 w filledcurves lt 3 title "
      "\"95 % CI\", \"\" index 0 u 1:2 w lp lt 3 pt 7 ps 0.6 title \"mean R\", "
      "\"\" index 1 u 1:2:3:4:5:6 w xyerrorbars lt 7 pt 5 ps 1.2 title \"maximum λ*, R* "
      "(95 % CI)\", $paper u 1:2 w p lt 2 pt 9 ps 2 title \"paper: ≈80 % at λ=3.8\"\n",
      gp_string(fmt::format("Mean relative stick time R, μ={}, {}", mu, set_note(s))));
  const std::string script = gp_preamble(f, 1000, 650) + "set logscale x\nset autoscale xfix\n" +
                             fmt::format("set xlabel {}\n", gp_string(lambda_label)) +
                             "set ylabel \"mean R = total stick time / t_a [-]\"\n"
                             "set key bottom center\n"
                             "$paper << EOD\n3.8 0.8\nEOD\n" +
                             gp_render_loop(f, 1000, 650, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

figure fig7(const set_study& s, const std::string& dir, bool render) {
  auto f = make(dir, "fig7", "fig7_stick_fraction_all_mu", "Fig. 7: mean R for every mu",
                fmt::format("Estimated mean of R against lambda for every mu of the grid, {} "
                            "realizations per point; {}. Markers: the maximum of each curve "
                            "located by the refinement (lambda*, R*) with 95 % intervals.",
                            s.sweep.spec.realizations, set_note(s)));
  std::vector<double> mus;
  for (const auto& ax : s.sweep.spec.axes)
    if (ax.name == "mu") mus = ax.values;
  std::string dat;
  std::string plots;
  int block = 0;
  for (double mu : mus) {
    dat += fmt::format("# mu = {}: lambda[1/s] mean(R) ci95_lo ci95_hi n\n", num(mu));
    const auto pts = points_at_mu(s.sweep, mu);
    for (auto* q : pts) {
      const auto& mv = q->stats.stick_fraction;
      dat += fmt::format("{} {} {} {} {}\n", num(q->parameters.switch_rate), num(mv.mean()),
                         num(mv.mean() - mv.ci95_half_width()),
                         num(mv.mean() + mv.ci95_half_width()), mv.count());
    }
    dat += "\n\n";
    plots += fmt::format("{}\"fig7_stick_fraction_all_mu.dat\" index {} u 1:2 w l lt {} "
                         "title \"μ = {}\"",
                         plots.empty() ? "" : ", ", block, block + 1, mu);
    ++block;
  }
  dat += "# maxima: lambda* R* lambda_lo lambda_hi R_lo R_hi mu\n";
  for (const auto& r : s.refinements) dat += peak_row(r) + " " + num(r.mu) + "\n";
  plots += fmt::format(", \"\" index {} u 1:2:3:4:5:6 w xyerrorbars lt 7 pt 7 ps 0.8 title "
                       "\"maxima (95 % CI)\"",
                       block);
  const std::string body =
      fmt::format("  set title {}\n  plot {}\n",
                  gp_string(fmt::format("Mean relative stick time R for every μ, {}",
                                        set_note(s))),
                  plots);
  const std::string script = gp_preamble(f, 1100, 700) + "set logscale x\nset autoscale xfix\n" +
                             fmt::format("set xlabel {}\n", gp_string(lambda_label)) +
                             "set ylabel \"mean R = total stick time / t_a [-]\"\n"
                             "set key outside right top\n" +
                             gp_render_loop(f, 1100, 700, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

figure convergence(const set_study& s, const std::string& dir, bool render) {
  const double mu = detail::nearest_mu(s.sweep, 5.0);
  const auto lams = detail::nearest_lambdas(s.sweep, {0.1, 3.8, 30.0});
  auto f = make(dir, "convergence", "convergence_R", "Fig. S1: convergence of mean R",
                fmt::format("The paper's convergence study, redone: the running estimate of "
                            "mean R after n realizations (one point per block of {}) at mu = "
                            "{} for lambda = {}; {}. Top: running mean minus the final mean, "
                            "with its 95 % confidence band. Bottom: the CI half-width, with the "
                            "n^(-1/2) law dashed. The paper chose 2000 realizations.",
                            s.sweep.spec.block_size, mu, fmt::join(lams, ", "), set_note(s)));
  std::string dat, top, bottom;
  int block = 0;
  double ref_n = 0, ref_hw = 0;
  for (double lam : lams) {
    for (const auto* q : points_at_mu(s.sweep, mu)) {
      if (q->parameters.switch_rate != lam || q->stats.convergence.empty()) continue;
      const double final_mean = q->stats.convergence.back().R_mean;
      dat += fmt::format("# lambda = {} 1/s, final mean R = {}: realizations mean(R) "
                         "ci95_lo ci95_hi ci95_half_width mean-final\n",
                         num(lam), num(final_mean));
      for (const auto& c : q->stats.convergence)
        dat += fmt::format("{} {} {} {} {} {}\n", c.realizations, num(c.R_mean),
                           num(c.R_mean - c.R_ci95_half_width),
                           num(c.R_mean + c.R_ci95_half_width), num(c.R_ci95_half_width),
                           num(c.R_mean - final_mean));
      dat += "\n\n";
      if (q->stats.convergence.back().R_ci95_half_width > ref_hw) {
        ref_n = static_cast<double>(q->stats.convergence.back().realizations);
        ref_hw = q->stats.convergence.back().R_ci95_half_width;
      }
      top += fmt::format(
          "{0}\"convergence_R.dat\" index {1} u 1:($6-$5):($6+$5) w filledcurves lt {2} "
          "notitle, \"\" index {1} u 1:6 w l lt {2} title \"λ = {3} 1/s\"",
          top.empty() ? "" : ", ", block, block + 1, lam);
      bottom += fmt::format("{0}\"convergence_R.dat\" index {1} u 1:5 w l lt {2} title "
                            "\"λ = {3} 1/s\"",
                            bottom.empty() ? "" : ", ", block, block + 1, lam);
      ++block;
    }
  }
  if (bottom.empty()) bottom = "NaN notitle";
  if (top.empty()) top = "NaN notitle";
  const std::string body = fmt::format(
      "  set multiplot layout 2,1 title {}\n"
      "  unset logscale\n"
      "  set ylabel \"running mean R − final mean [-]\"\n"
      "  plot {}, 0 w l lt 8 dt 2 notitle\n"
      "  set logscale xy\n"
      "  set ylabel \"95 % CI half-width of mean R [-]\"\n"
      "  plot {}, {}*sqrt({}/x) w l lt 7 dt 2 title \"∝ n^{{-1/2}}\"\n"
      "  unset multiplot\n"
      "  unset logscale\n",
      gp_string(fmt::format("Convergence of mean R, μ={}, {}", mu, set_note(s))), top, bottom,
      num(ref_hw), num(ref_n));
  const std::string script = gp_preamble(f, 1000, 800) +
                             "set xlabel \"n, number of realizations\"\nset autoscale xfix\n"
                             "set key outside right top\n"
                             "set lmargin at screen 0.1\nset rmargin at screen 0.8\n" +
                             gp_render_loop(f, 1000, 800, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

figure refinement(const set_study& s, const std::string& dir, bool render) {
  auto f = make(dir, "refinement", "refinement_peak", "Fig. S2: refinement of the maximum of mean R",
                fmt::format("For each mu: mean R on the refinement grid ({} lambda values, "
                            "geometric, around the grid maximum; {} realizations each) with "
                            "95 % error bars, the weighted quadratic fit in ln(lambda) that "
                            "stickslip 0.1.0 used, and the maximum lambda* located by `peak` "
                            "with its 95 % interval (sampling + local-model bias); {}.",
                            s.refinements.empty() ? 0 : s.refinements[0].fine.points.size(),
                            s.refinements.empty() ? 0 : s.refinements[0].fine.spec.realizations,
                            set_note(s)));
  std::string dat, body;
  const std::size_t n = s.refinements.size();
  const std::size_t cols = n <= 3 ? n : 4, rows = (n + cols - 1) / std::max<std::size_t>(cols, 1);
  body += fmt::format("  set multiplot layout {},{} title {}\n", std::max<std::size_t>(rows, 1),
                      std::max<std::size_t>(cols, 1),
                      gp_string(fmt::format("Refinement of the maximum of mean R, {}",
                                            set_note(s))));
  int block = 0;
  for (const auto& r : s.refinements) {
    dat += fmt::format("# mu = {}: lambda[1/s] mean(R) ci95_lo ci95_hi fit\n", num(r.mu));
    for (const auto& q : r.fine.points) {
      const auto& mv = q.stats.stick_fraction;
      const double u = std::log(q.parameters.switch_rate / r.quadratic.center);
      dat += fmt::format("{} {} {} {} {}\n", num(q.parameters.switch_rate), num(mv.mean()),
                         num(mv.mean() - mv.ci95_half_width()),
                         num(mv.mean() + mv.ci95_half_width()),
                         num(r.quadratic.b0 + r.quadratic.b1 * u + r.quadratic.b2 * u * u));
    }
    dat += fmt::format("\n\n# peak: lambda* R* lambda_lo lambda_hi R_lo R_hi\n{}\n\n\n",
                       peak_row(r));
    const auto p = best_maximum(r);
    const auto& q = r.quadratic;
    body += fmt::format(
        "  set title \"μ = {}: λ* = {:.3f} [{:.3f}, {:.3f}]\"\n"
        "  plot \"refinement_peak.dat\" index {} u 1:2:3:4 w yerrorbars lt 1 pt 7 ps 0.5 "
        "title \"mean R\", {} + {}*log(x/{}) + {}*log(x/{})**2 w l lt 2 title "
        "\"0.1.0 quadratic fit\", \"\" index {} u 1:2:3:4 w xerrorbars lt 7 pt 5 ps 1 title "
        "\"λ* of peak (95 % CI)\"\n",
        r.mu, p.lambda, p.lambda_lo, p.lambda_hi, 2 * block, num(q.b0), num(q.b1),
        num(q.center), num(q.b2), num(q.center), 2 * block + 1);
    ++block;
  }
  body += "  unset multiplot\n";
  const int w = static_cast<int>(380 * std::max<std::size_t>(cols, 1)) + 100;
  const int h = static_cast<int>(330 * std::max<std::size_t>(rows, 1)) + 60;
  const std::string script = gp_preamble(f, w, h) +
                             "set xlabel \"λ [1/s]\"\nset ylabel \"mean R [-]\"\nset autoscale xfix\n"
                             "set samples 200\n"
                             "set key bottom center font \",8\"\nset format y \"%.3f\"\n" +
                             gp_render_loop(f, w, h, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

}  // namespace

std::vector<trace_point> sample_realization(const sweep_spec& spec, const model_parameters& p,
                                            std::uint64_t realization, double dt, double t_end) {
  segment_recorder c;
  (void)simulate_realization(spec, p, realization, c);
  std::vector<trace_point> out;
  for (const auto& q : sample_trajectory(c.segments, dt, t_end))
    out.push_back({q.time, q.position, q.velocity, q.belt_velocity, q.kind == mode::stick});
  return out;
}

std::vector<figure> write_set_figures(const set_study& s, const std::string& dir, bool render) {
  std::filesystem::create_directories(dir);
  render = render && gnuplot_available();
  std::vector<figure> out;
  out.push_back(fig2(s, dir, render));
  out.push_back(fig4(s, dir, render));
  out.push_back(fig5(s, dir, render));
  out.push_back(fig6a(s, dir, render));
  out.push_back(fig6b(s, dir, render));
  out.push_back(fig7(s, dir, render));
  out.push_back(convergence(s, dir, render));
  if (!s.refinements.empty()) out.push_back(refinement(s, dir, render));
  return out;
}

}  // namespace stickslip::study
