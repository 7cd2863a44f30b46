#include "stickslip/study/sensitivity_figure.hpp"

#include <fmt/format.h>

#include <string>

#include "figures_common.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "stickslip/uncertainty/sobol.hpp"

namespace stickslip::study {

figure write_sensitivity_figure(const result_set& rs, const std::string& dir, bool render) {
  const auto& stats = rs.points.front().stats;
  const sobol_estimates est = sobol_indices(stats.sensitivity);
  const auto& q = sensitivity_quantity(rs.spec);
  figure f;
  f.key = "sensitivity";
  f.dir = dir;
  f.stem = "sensitivity";
  f.title = fmt::format("Sobol' indices of E[{} | theta]", q.summary_name);
  f.caption = fmt::format(
      "First-order (Saltelli) and total-order (Jansen) Sobol' indices of the mean response "
      "E[{} | theta] over the uncertain inputs, with 95 % intervals (delta method); {} design "
      "rows, {} realizations, seed {}. Parameter share {:.3f} [{:.3f}, {:.3f}], intrinsic "
      "share {:.3f} [{:.3f}, {:.3f}].",
      q.summary_name, est.rows, stats.realizations * runs_per_row(rs.spec), rs.spec.seed, est.parameter_share.value,
      est.parameter_share.low, est.parameter_share.high, est.intrinsic_share.value,
      est.intrinsic_share.low, est.intrinsic_share.high);
  std::string dat =
      "# input  law  first_order  low  high  total_order  low  high\n"
      "# Sobol' indices of the mean response (stickslip sensitivity)\n";
  for (std::size_t i = 0; i < rs.spec.uncertain.size(); ++i) {
    const auto& u = rs.spec.uncertain[i];
    dat += fmt::format("{} {} {} {} {} {} {} {}\n", detail::gp_string(u.symbol),
                       detail::gp_string(to_string(u.law)), detail::num(est.first_order[i].value),
                       detail::num(est.first_order[i].low), detail::num(est.first_order[i].high),
                       detail::num(est.total_order[i].value), detail::num(est.total_order[i].low),
                       detail::num(est.total_order[i].high));
  }
  const int width = 800, height = 500;
  const std::string body = fmt::format(
      "  set title {}\n"
      "  set ylabel \"Sobol' index (1)\"\n"
      "  set xlabel \"uncertain input\"\n"
      "  set yrange [*<0:1<*]\n"
      "  set style data histograms\n"
      "  set style histogram errorbars gap 2 lw 1.5\n"
      "  set style fill solid 0.6 border -1\n"
      "  set boxwidth 0.9\n"
      "  set key top right\n"
      "  plot \"sensitivity.dat\" using 3:4:5:xticlabels(1) title \"first order\" lt 1, \\\n"
      "       \"\" using 6:7:8 title \"total order\" lt 2\n",
      detail::gp_string(fmt::format("Sobol' indices of E[{} | {{/Symbol q}}]; parameter share "
                                    "{:.2f}, intrinsic {:.2f}",
                                    q.summary_name, est.parameter_share.value,
                                    est.intrinsic_share.value)));
  const std::string script = detail::gp_preamble(f, width, height) +
                             detail::gp_render_loop(f, width, height, body);
  detail::finish_figure(f, dat, script, render && gnuplot_available());
  return f;
}

}  // namespace stickslip::study
