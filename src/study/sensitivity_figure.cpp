#include "stickslip/study/sensitivity_figure.hpp"

#include <fmt/format.h>

#include <string>

#include "stickslip/io/writers.hpp"
#include "stickslip/study/plot_figures.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "stickslip/uncertainty/sobol.hpp"

namespace stickslip::study {

figure write_sensitivity_figure(const result_set& rs, const std::string& dir, bool render) {
  const auto& stats = rs.points.front().stats;
  const sobol_estimates est = sobol_indices(stats.sensitivity);
  const auto& q = sensitivity_quantity(rs.spec);
  // Drawn by the bars of study/plot_figures.hpp, as `stickslip plot` draws
  // a sensitivity.nc.
  bar_plot p;
  p.text.stem = io::sensitivity_figure_stem;
  p.text.title = fmt::format("Sobol' indices of E[{} | theta]; parameter share {:.2f}, "
                             "intrinsic {:.2f}",
                             q.summary_name, est.parameter_share.value, est.intrinsic_share.value);
  p.text.caption = fmt::format(
      "First-order (Saltelli) and total-order (Jansen) Sobol' indices of the mean response "
      "E[{} | theta] over the uncertain inputs, with 95 % intervals (delta method); {} design "
      "rows, {} realizations, seed {}. Parameter share {:.3f} [{:.3f}, {:.3f}], intrinsic "
      "share {:.3f} [{:.3f}, {:.3f}].",
      q.summary_name, est.rows, stats.realizations * runs_per_row(rs.spec), rs.spec.seed, est.parameter_share.value,
      est.parameter_share.low, est.parameter_share.high, est.intrinsic_share.value,
      est.intrinsic_share.low, est.intrinsic_share.high);
  p.text.xlabel = "uncertain input";
  p.text.ylabel = "Sobol' index (1)";
  bar_group first{"first order", {}, {}, {}}, total{"total order", {}, {}, {}};
  for (std::size_t i = 0; i < rs.spec.uncertain.size(); ++i) {
    p.categories.push_back(rs.spec.uncertain[i].symbol);
    p.text.caption += fmt::format(" {} ~ {}.", rs.spec.uncertain[i].symbol,
                                  to_string(rs.spec.uncertain[i].law));
    first.value.push_back(est.first_order[i].value);
    first.low.push_back(est.first_order[i].low);
    first.high.push_back(est.first_order[i].high);
    total.value.push_back(est.total_order[i].value);
    total.low.push_back(est.total_order[i].low);
    total.high.push_back(est.total_order[i].high);
  }
  p.groups = {std::move(first), std::move(total)};
  figure f = write_plot_figure(p, dir, render && gnuplot_available());
  f.key = "sensitivity";
  return f;
}

}  // namespace stickslip::study
