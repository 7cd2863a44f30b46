// The evidence figure for the parameter-set question: mean R against lambda
// at the three mu the paper quotes, one curve per candidate set, with the
// paper's claimed maxima marked.
#include <filesystem>

#include "figures_common.hpp"

namespace stickslip::study {

using detail::gp_string;
using detail::num;

std::vector<figure> write_candidate_figures(const study_result& r, const std::string& dir,
                                            bool render) {
  std::filesystem::create_directories(dir);
  render = render && gnuplot_available();
  std::vector<const set_study*> all;
  for (const auto& s : r.sets) all.push_back(&s);
  for (const auto& s : r.candidates) all.push_back(&s);

  figure f;
  f.key = "candidates";
  f.dir = dir;
  f.stem = "candidates_R";
  f.title = "Which parameters did the paper's figures use?";
  f.caption =
      "Mean R against lambda at mu = 0.5, 5 and 7 for every candidate parameter set (m = 1 kg, "
      "t_a = 50 s throughout). Black diamonds: the paper's claims (mu = 0.5: 15.0 %, mu = 5: "
      "almost 80 % at lambda = 3.8 1/s, mu = 7: 81.89 %, all maxima in lambda in [3.5, 3.8] "
      "1/s, drawn as a horizontal bar). A set reproduces the paper when its curves peak on the "
      "diamonds.";
  // One block per (mu, set): lambda mean(R) ci_lo ci_hi.
  std::string dat;
  const double mus[] = {0.5, 5.0, 7.0};
  std::string body = fmt::format("  set multiplot layout 1,3 title {}\n",
                                 gp_string("Mean R vs λ for each candidate parameter set "
                                           "(m=1 kg, t_a=50 s); ◆ = the paper's claims"));
  int block = 0;
  for (double mu : mus) {
    std::string plots;
    int lt = 1;
    for (const auto* s : all) {
      const auto pts = points_at_mu(s->sweep, mu);
      if (pts.empty()) continue;
      dat += fmt::format("# mu = {}, set {} ({}): lambda mean(R) ci95_lo ci95_hi\n", num(mu),
                         s->set.id, s->set.label);
      for (auto* q : pts) {
        const auto& mv = q->stats.stick_fraction;
        dat += fmt::format("{} {} {} {}\n", num(q->parameters.switch_rate), num(mv.mean()),
                           num(mv.mean() - mv.ci95_half_width()),
                           num(mv.mean() + mv.ci95_half_width()));
      }
      dat += "\n\n";
      plots += fmt::format("{}\"candidates_R.dat\" index {} u 1:2 w lp lt {} pt 7 ps 0.4 "
                           "title {}",
                           plots.empty() ? "" : ", ", block, lt++,
                           gp_string(s->set.id == "printed" || s->set.id == "concluded"
                                         ? s->set.id + ": " + s->set.label
                                         : s->set.label));
      ++block;
    }
    const double claim = mu == 0.5 ? 0.150 : (mu == 5.0 ? 0.80 : 0.8189);
    const double at = mu == 5.0 ? 3.8 : 3.65;
    const double bar = mu == 5.0 ? 0.0 : 0.15;
    body += mu == 0.5 ? "  set key top right font \",9\"\n" : "  unset key\n";
    body += fmt::format(
        "  set title \"μ = {}\"\n"
        "  plot {}, \"+\" u ({}):({}):({}) every ::0::0 w xerrorbars lt 7 pt 13 ps 2 "
        "title \"paper\"\n",
        mu, plots, num(at), num(claim), num(bar));
  }
  body += "  unset multiplot\n";
  std::string script = detail::gp_preamble(f, 1600, 600) +
                       "set logscale x\nset autoscale xfix\nset xlabel \"λ, belt switch rate [1/s]\"\n"
                       "set ylabel \"mean R [-]\"\n"
                       "set yrange [0:1]\n" +
                       detail::gp_render_loop(f, 1600, 600, body);
  detail::finish_figure(f, dat, script, render);
  return {f};
}

}  // namespace stickslip::study
