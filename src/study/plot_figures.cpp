// Curves, heat maps and bars as .dat + .gp, rendered by gnuplot
// (study/plot_figures.hpp). Numbers in the .dat files are shortest
// round-trip text, so they read back as the very doubles that were plotted.
#include "stickslip/study/plot_figures.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "figures_common.hpp"

namespace stickslip::study {
namespace {

constexpr int width = 900, height = 550;

std::string exact(double x) { return std::isnan(x) ? "NaN" : fmt::format("{}", x); }

std::string label(const std::string& s) { return detail::gp_string(literal_text(s)); }

// The head of a figure's script: the shared preamble, which names
// `stickslip reproduce` as its writer (these figures come from plot and
// sensitivity too), and the caption as a comment.
std::string script_head(const figure& f, const figure_text& t) {
  std::string pre = detail::gp_preamble(f, width, height);
  const std::string by = "`stickslip reproduce`";
  if (const auto at = pre.find(by); at != std::string::npos) pre.replace(at, by.size(), "`stickslip`");
  return pre + "# " + t.caption + "\n";
}

std::string axes_body(const figure_text& t) {
  return fmt::format("  set title {}\n  set xlabel {}\n  set ylabel {}\n", label(t.title),
                     label(t.xlabel), label(t.ylabel));
}

figure new_figure(const figure_text& t, const std::string& dir, const std::string& key) {
  figure f;
  f.key = key;
  f.dir = dir;
  f.stem = t.stem;
  f.title = t.title;
  f.caption = t.caption;
  return f;
}

const char* with_clause(curve_style s) {
  switch (s) {
    case curve_style::points: return "linespoints pt 7 ps 0.8";
    case curve_style::lines: return "lines";
    case curve_style::steps: return "lines";  // the .dat holds the steps
    case curve_style::histogram: return "histeps";
  }
  return "lines";
}

figure write_curves(const curve_plot& p, const std::string& dir, bool render) {
  figure f = new_figure(p.text, dir, "curves");
  std::string dat = fmt::format("# {}\n# blocks (gnuplot index), one per series; columns: x y "
                                "low high (95 % interval; NaN: none)\n", p.text.title);
  std::string plots;
  for (std::size_t i = 0; i < p.series.size(); ++i) {
    const auto& s = p.series[i];
    dat += fmt::format("# series {}: {}\n", i, s.label);
    const bool band = !s.low.empty();
    const auto row = [&](double x, std::size_t k) {
      dat += fmt::format("{} {} {} {}\n", exact(x), exact(s.y[k]), exact(band ? s.low[k] : NAN),
                         exact(band ? s.high[k] : NAN));
    };
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      // A step function holds each value up to the next x: the row repeated
      // there makes lines and bands alike draw the steps.
      if (p.style == curve_style::steps && k > 0) row(s.x[k], k - 1);
      row(s.x[k], k);
    }
    dat += "\n\n";
    const std::string src = plots.empty() ? detail::gp_string(f.stem + ".dat") : "\"\"";
    if (!plots.empty()) plots += ", \\\n       ";
    if (band)
      plots += fmt::format("{} index {} using 1:3:4 with filledcurves lt {} notitle, \\\n       \"\" ",
                           src, i, i + 1);
    else
      plots += src + " ";
    plots += fmt::format("index {} using 1:2 with {} lt {} title {}", i, with_clause(p.style),
                         i + 1, label(s.label));
  }
  std::string body = axes_body(p.text);
  if (p.logx) body += "  set logscale x\n";
  body += "  set autoscale xfix\n  set key outside top center horizontal\n  plot " + plots + "\n";
  const std::string script = script_head(f, p.text) + detail::gp_render_loop(f, width, height, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

// The edges of the cells centred on `v`: halfway between neighbours
// (geometrically on a log axis), the outer ones mirrored.
std::vector<double> cell_edges(const std::vector<double>& v, bool log) {
  const auto mid = [log](double a, double b) { return log ? std::sqrt(a * b) : 0.5 * (a + b); };
  const auto mirror = [log](double at, double other) {
    return log ? at * at / other : 2 * at - other;
  };
  std::vector<double> e(v.size() + 1);
  if (v.size() == 1) {
    e[0] = log ? v[0] / 1.25 : v[0] - 0.5;
    e[1] = log ? v[0] * 1.25 : v[0] + 0.5;
    return e;
  }
  for (std::size_t i = 1; i < v.size(); ++i) e[i] = mid(v[i - 1], v[i]);
  e.front() = mirror(v.front(), e[1]);
  e.back() = mirror(v.back(), e[v.size() - 1]);
  return e;
}

figure write_map(const map_plot& p, const std::string& dir, bool render) {
  figure f = new_figure(p.text, dir, "map");
  const auto ex = cell_edges(p.x, p.logx), ey = cell_edges(p.y, p.logy);
  std::string dat = fmt::format("# {}\n# columns: x y x_low x_high y_low y_high z\n", p.text.title);
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    for (std::size_t j = 0; j < p.y.size(); ++j)
      dat += fmt::format("{} {} {} {} {} {} {}\n", exact(p.x[i]), exact(p.y[j]), exact(ex[i]),
                         exact(ex[i + 1]), exact(ey[j]), exact(ey[j + 1]),
                         exact(p.z[i * p.y.size() + j]));
    dat += "\n";
  }
  std::string body = axes_body(p.text);
  body += fmt::format("  set cblabel {}\n", label(p.zlabel));
  if (p.logx) body += "  set logscale x\n";
  if (p.logy) body += "  set logscale y\n";
  body +=
      "  set autoscale xfix\n  set autoscale yfix\n  unset grid\n  unset key\n"
      "  set style fill solid 1.0 noborder\n"
      "  set palette defined (0 \"#440154\", 1 \"#3b528b\", 2 \"#21918c\", 3 \"#5ec962\", 4 "
      "\"#fde725\")\n";
  body += fmt::format("  plot {} using 1:2:3:4:5:6:7 with boxxyerror fs solid 1.0 noborder "
                      "lc palette notitle\n",
                      detail::gp_string(f.stem + ".dat"));
  const std::string script = script_head(f, p.text) + detail::gp_render_loop(f, width, height, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

figure write_bars(const bar_plot& p, const std::string& dir, bool render) {
  figure f = new_figure(p.text, dir, "bars");
  std::string dat = fmt::format("# {}\n# columns: category", p.text.title);
  for (const auto& g : p.groups) dat += fmt::format("  {} low high", g.label);
  dat += "\n";
  for (std::size_t c = 0; c < p.categories.size(); ++c) {
    dat += detail::gp_string(p.categories[c]);
    for (const auto& g : p.groups)
      dat += fmt::format(" {} {} {}", exact(g.value[c]), exact(g.low[c]), exact(g.high[c]));
    dat += "\n";
  }
  std::string plots;
  for (std::size_t i = 0; i < p.groups.size(); ++i) {
    const std::size_t col = 2 + 3 * i;
    plots += fmt::format("{}{} using {}:{}:{}{} title {} lt {}", i ? ", \\\n       " : "",
                         i ? std::string("\"\"") : detail::gp_string(f.stem + ".dat"), col,
                         col + 1, col + 2, i ? "" : ":xticlabels(1)", label(p.groups[i].label),
                         i + 1);
  }
  const std::string body = axes_body(p.text) +
                           "  set yrange [*<0:1<*]\n"
                           "  set style data histograms\n"
                           "  set style histogram errorbars gap 2 lw 1.5\n"
                           "  set style fill solid 0.6 border -1\n"
                           "  set boxwidth 0.9\n"
                           "  set key top right\n"
                           "  plot " + plots + "\n";
  const std::string script = script_head(f, p.text) + detail::gp_render_loop(f, width, height, body);
  detail::finish_figure(f, dat, script, render);
  return f;
}

}  // namespace

const figure_text& text_of(const plot_figure& p) {
  return std::visit([](const auto& x) -> const figure_text& { return x.text; }, p);
}

figure write_plot_figure(const plot_figure& p, const std::string& dir, bool render) {
  if (const auto* c = std::get_if<curve_plot>(&p)) return write_curves(*c, dir, render);
  if (const auto* m = std::get_if<map_plot>(&p)) return write_map(*m, dir, render);
  return write_bars(std::get<bar_plot>(p), dir, render);
}

std::string literal_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '_' || c == '^' || c == '{' || c == '}' || c == '&' || c == '~') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace stickslip::study
