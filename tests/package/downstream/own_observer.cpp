// A user's own observer on the header templates (simulate_realization, and
// with it the event-driven integrator and poisson_switches' refill), compiled
// in the user's translation unit with the user's flags. install_and_consume.sh
// builds it with -march=haswell -ffp-contract=fast, GCC's default contraction
// on a CPU with fused multiply-adds, where the CPU has them. The stick
// fraction R of every realization must be the same bits as the library's
// records (the lane engine, compiled inside stickslip_core): the package
// passes -ffp-contract=off to every target that links stickslip::core, so
// that no fused multiply-add the source does not write changes a result.
// Prints "realizations N equal" and exits 0, or names the first that differs.
#include <cstdio>
#include <exception>

#include <stickslip/observer.hpp>
#include <stickslip/sweep.hpp>

namespace {

struct stick_time : stickslip::observer_base {
  double total = 0.0;
  void on_episode(const stickslip::episode& e) noexcept {
    if (e.kind == stickslip::mode::stick) total += e.duration();
  }
};

}  // namespace

int main() {
  try {
    stickslip::sweep_spec spec;
    spec.axes = {{"lambda", {3.8}}};
    spec.realizations = 400;
    spec.seed = 7;
    spec.keep_records = true;
    stickslip::validate(spec);
    const stickslip::result_set rs = stickslip::run_sweep(spec, 1);
    const auto& point = rs.points.at(0);
    const auto& records = rs.records.at(0);
    for (std::uint64_t r = 0; r < spec.realizations; ++r) {
      stick_time obs;
      (void)stickslip::simulate_realization(spec, point.parameters, r, obs);
      const double mine = obs.total / point.parameters.window;
      if (mine != records.at(r).stick_fraction) {
        std::printf("realization %llu: R %.17g here, %.17g in the library\n",
                    static_cast<unsigned long long>(r), mine, records.at(r).stick_fraction);
        return 1;
      }
    }
    std::printf("realizations %llu equal\n", static_cast<unsigned long long>(spec.realizations));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "own_observer: %s\n", e.what());
    return 1;
  }
}
