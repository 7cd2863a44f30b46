// The oracle of the damped-slip regressions: classical fixed-step RK4 on
// y'' + 2 gamma y' + omega_0^2 y = 0 (y = x - sigma a_k, z = x'), written
// without the closed forms of damped_slip.hpp.
#pragma once

namespace stickslip::regression {

struct slip_rk4 {
  double w2, gamma;  // omega_0^2, c / 2m
  double y, z;       // the state, advanced in place

  void step(double h) {
    auto f = [&](double yy, double zz) { return -w2 * yy - 2.0 * gamma * zz; };
    const double k1y = z, k1z = f(y, z);
    const double k2y = z + 0.5 * h * k1z, k2z = f(y + 0.5 * h * k1y, z + 0.5 * h * k1z);
    const double k3y = z + 0.5 * h * k2z, k3z = f(y + 0.5 * h * k2y, z + 0.5 * h * k2z);
    const double k4y = z + h * k3z, k4z = f(y + h * k3y, z + h * k3z);
    y += h / 6.0 * (k1y + 2.0 * k2y + 2.0 * k3y + k4y);
    z += h / 6.0 * (k1z + 2.0 * k2z + 2.0 * k3z + k4z);
  }
};

}  // namespace stickslip::regression
