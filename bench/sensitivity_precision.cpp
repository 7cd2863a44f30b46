// Time to precision of `stickslip sensitivity`, side by side in one run
// (docs/uncertainty.md): the design is run once for N rows; from the same
// merged moments, each estimator form gives its 95 % half-widths, and the
// rows (and seconds, at this run's rows per second) it would need for every
// index and share to reach a half-width H follow from the 1/sqrt(N) law:
//   default        OpenTURNS's centred Saltelli first order, Jansen total
//   saltelli_2010  the plain pick-freeze product mean(y_B (y_E - y_A))
// Usage: sensitivity_precision [rows] [threads] [H]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>

#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"
#include "stickslip/uncertainty/sobol.hpp"

using namespace stickslip;

int main(int argc, char** argv) {
  const std::uint64_t rows = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 20000;
  const unsigned threads = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 2;
  const double target = argc > 3 ? std::atof(argv[3]) : 0.02;
  struct study {
    const char* name;
    std::vector<std::pair<const char*, const char*>> laws;
  };
  const study studies[] = {
      {"sensitivity speed case", {{"mu", "uniform(2,7)"}, {"lambda", "loguniform(0.5,10)"}}},
      {"docs example",
       {{"mu", "gamma(mean=5,cv=0.2)"}, {"k", "lognormal(mean=40,cv=0.1)"},
        {"lambda", "loguniform(0.5,10)"}}},
  };
  for (const auto& st : studies) {
    sweep_spec s;
    s.base.stiffness = 40.0;
    s.sensitivity_statistic = std::string("R");
    for (const auto& [sym, law] : st.laws) s.uncertain.push_back({sym, parse_law(law, sym)});
    std::sort(s.uncertain.begin(), s.uncertain.end(),
              [](const auto& a, const auto& b) { return a.symbol < b.symbol; });
    s.realizations = rows;
    s.block_size = 64;
    const auto t0 = std::chrono::steady_clock::now();
    const auto rs = run_sweep(s, threads);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto& m = rs.points.front().stats.sensitivity;
    fmt::print("{}: {} rows ({} realizations) in {:.2f} s on {} threads\n", st.name, rows,
               rows * (s.uncertain.size() + 3), secs, threads);
    for (auto form : {first_order_form::openturns_saltelli, first_order_form::saltelli_2010}) {
      const auto e = sobol_indices(m, form);
      const double h = e.max_half_width();
      const double need = static_cast<double>(rows) * (h / target) * (h / target);
      fmt::print("  {:<14} max half-width {:.4f} (first order ", 
                 form == first_order_form::openturns_saltelli ? "default" : "saltelli_2010", h);
      for (const auto& f : e.first_order) fmt::print("{:.4f} ", f.half_width());
      fmt::print("); to {}: {:.0f} rows, {:.1f} s\n", target, need,
                 need * secs / static_cast<double>(rows));
    }
  }
}
