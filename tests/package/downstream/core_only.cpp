// Uses only stickslip::core: a two-point lambda sweep, 100 realizations per
// point, seed 7, one thread. Prints the mean stick fraction R of each point
// with 17 significant digits, one line per point: "lambda R_mean".
#include <cstdio>
#include <exception>

#include <stickslip/sweep.hpp>
#include <stickslip/version.hpp>

int main() {
  try {
    stickslip::sweep_spec spec;
    spec.axes = {{"lambda", {1.0, 3.8}}};
    spec.realizations = 100;
    spec.seed = 7;
    stickslip::validate(spec);
    const stickslip::result_set rs = stickslip::run_sweep(spec, 1);
    std::printf("# stickslip %s\n", stickslip::version);
    for (const auto& point : rs.points) {
      std::printf("%.17g %.17g\n", point.parameters.switch_rate,
                  point.stats.stick_fraction.mean());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "core_only: %s\n", e.what());
    return 1;
  }
}
