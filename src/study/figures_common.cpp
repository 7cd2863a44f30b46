#include "figures_common.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "stickslip/io/atomic_file.hpp"

namespace stickslip::study {

namespace {
std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}
}  // namespace

bool gnuplot_available() {
  static const bool ok =
      std::system("gnuplot -e \"set terminal pngcairo; set terminal svg\" >/dev/null 2>&1") == 0;
  return ok;
}

bool run_gnuplot(const std::string& dir, const std::string& script) {
  const std::string cmd = "cd " + shell_quote(dir) + " && gnuplot " + shell_quote(script) +
                          " > " + shell_quote(script + ".log") + " 2>&1";
  const bool ok = std::system(cmd.c_str()) == 0;
  // Keep the log only when gnuplot said something.
  std::error_code ec;
  const auto log = std::filesystem::path(dir) / (script + ".log");
  if (ok && std::filesystem::file_size(log, ec) == 0 && !ec) std::filesystem::remove(log, ec);
  return ok;
}

namespace detail {

void write_text_file(const std::string& path, const std::string& text) {
  io::detail::write_text_atomically(path, [&](io::detail::text_sink& out) { out.write(text); });
}

std::string num(double x) {
  if (std::isnan(x)) return "NaN";
  return fmt::format("{:.9g}", x);
}

std::string gp_string(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '\\' || c == '"') q += '\\';
    if (c == '@') {  // enhanced text: '@' is an operator
      q += "\\\\@";
      continue;
    }
    q += c;
  }
  return q + "\"";
}

std::string gp_preamble(const figure& f, int width, int height) {
  return fmt::format(
      "# {title}\n"
      "# Written by `stickslip reproduce`. Edit and rerun in this folder:\n"
      "#   gnuplot {stem}.gp     (renders {stem}.png and {stem}.svg, {w}x{h} px)\n"
      "# Data: {stem}.dat (columns described in its header).\n"
      "set encoding utf8\n"
      "set datafile missing \"NaN\"\n"
      "set grid lc rgb \"#dddddd\"\n"
      "set key box opaque\n"
      "set style fill transparent solid 0.25 noborder\n"
      "set linetype 1 lc rgb \"#0072b2\" lw 2\n"
      "set linetype 2 lc rgb \"#d55e00\" lw 2\n"
      "set linetype 3 lc rgb \"#009e73\" lw 2\n"
      "set linetype 4 lc rgb \"#cc79a7\" lw 2\n"
      "set linetype 5 lc rgb \"#e69f00\" lw 2\n"
      "set linetype 6 lc rgb \"#56b4e9\" lw 2\n"
      "set linetype 7 lc rgb \"#000000\" lw 2\n"
      "set linetype 8 lc rgb \"#999999\" lw 2\n"
      "set linetype cycle 8\n",
      fmt::arg("title", f.title), fmt::arg("stem", f.stem), fmt::arg("w", width),
      fmt::arg("h", height));
}

std::string gp_render_loop(const figure& f, int width, int height, const std::string& body) {
  return fmt::format(
      "do for [fmt in \"png svg\"] {{\n"
      "  if (fmt eq \"png\") {{\n"
      "    set terminal pngcairo enhanced size {w},{h} font \"DejaVu Sans,11\"\n"
      "  }} else {{\n"
      "    set terminal svg enhanced size {w},{h} font \"DejaVu Sans,11\" background rgb \"white\"\n"
      "  }}\n"
      "  set output \"{stem}.\".fmt\n"
      "{body}"
      "  unset output\n"
      "}}\n",
      fmt::arg("w", width), fmt::arg("h", height), fmt::arg("stem", f.stem),
      fmt::arg("body", body));
}

void finish_figure(figure& f, const std::string& dat, const std::string& script, bool render) {
  if (!dat.empty()) write_text_file(f.dir + "/" + f.stem + ".dat", dat);
  write_text_file(f.script(), script);
  f.rendered = render && run_gnuplot(f.dir, f.stem + ".gp");
  if (!f.rendered) {  // no stale images from an earlier run beside new data
    std::error_code ec;
    std::filesystem::remove(f.png(), ec);
    std::filesystem::remove(f.svg(), ec);
  }
}

double nearest_mu(const result_set& rs, double mu) {
  double best = rs.points.front().parameters.friction_coefficient;
  for (const auto& p : rs.points)
    if (std::abs(p.parameters.friction_coefficient - mu) < std::abs(best - mu))
      best = p.parameters.friction_coefficient;
  return best;
}

std::vector<double> nearest_lambdas(const result_set& rs, const std::vector<double>& wanted) {
  std::set<double> out;
  for (double w : wanted) {
    double best = rs.points.front().parameters.switch_rate;
    for (const auto& p : rs.points)
      if (std::abs(std::log(p.parameters.switch_rate / w)) < std::abs(std::log(best / w)))
        best = p.parameters.switch_rate;
    out.insert(best);
  }
  return {out.begin(), out.end()};
}

std::string parameter_line(const model_parameters& p) {
  return fmt::format("m={} kg, k={} N/m, g={} m/s^2, V={} m/s, t_a={} s", p.mass, p.stiffness,
                     p.gravity, p.belt_speed, p.window);
}

}  // namespace detail
}  // namespace stickslip::study
