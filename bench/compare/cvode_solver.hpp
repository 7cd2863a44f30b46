// SUNDIALS CVODE (Adams-Moulton, variable order, fixed-point iteration: the
// non-stiff setting) with its built-in root finding. One CVODE instance per
// solver; every segment is a CVodeReInit with the segment's stop time.
#pragma once
#include <cstdint>

#include "hybrid_driver.hpp"

namespace stickslip::bench {

class cvode_adams {
 public:
  cvode_adams(double abs_tol, double rel_tol);
  ~cvode_adams();
  cvode_adams(const cvode_adams&) = delete;
  cvode_adams& operator=(const cvode_adams&) = delete;

  segment_outcome advance(const segment_problem& prob, double t0, const double y0[2],
                          double t_stop);
  [[nodiscard]] std::uint64_t steps() const noexcept { return steps_; }
  [[nodiscard]] std::uint64_t rhs_evaluations() const noexcept { return rhs_evaluations_; }

  // Called by CVODE through user data.
  const segment_problem* problem = nullptr;

 private:
  void* context_ = nullptr;  // SUNContext
  void* memory_ = nullptr;   // CVODE memory
  void* vector_ = nullptr;   // N_Vector
  void* nonlinear_ = nullptr;  // SUNNonlinearSolver
  std::uint64_t steps_ = 0, rhs_evaluations_ = 0;
};

}  // namespace stickslip::bench
