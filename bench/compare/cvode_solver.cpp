#include "cvode_solver.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <stdexcept>
#include <string>

namespace stickslip::bench {
namespace {

int cvode_rhs(sunrealtype, N_Vector y, N_Vector dy, void* user) {
  const auto* self = static_cast<cvode_adams*>(user);
  self->problem->rhs(N_VGetArrayPointer(y), N_VGetArrayPointer(dy));
  return 0;
}

int cvode_root(sunrealtype, N_Vector y, sunrealtype* g, void* user) {
  const auto* self = static_cast<cvode_adams*>(user);
  g[0] = self->problem->event(N_VGetArrayPointer(y));
  return 0;
}

void check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(std::string("CVODE: ") + what + " failed, flag " + std::to_string(flag));
}

}  // namespace

cvode_adams::cvode_adams(double abs_tol, double rel_tol) {
  SUNContext ctx = nullptr;
  check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
  context_ = ctx;
  N_Vector y = N_VNew_Serial(2, ctx);
  vector_ = y;
  N_VConst(0.0, y);
  memory_ = CVodeCreate(CV_ADAMS, ctx);
  check(CVodeInit(memory_, cvode_rhs, 0.0, y), "CVodeInit");
  check(CVodeSStolerances(memory_, rel_tol, abs_tol), "CVodeSStolerances");
  SUNNonlinearSolver nls = SUNNonlinSol_FixedPoint(y, 0, ctx);
  nonlinear_ = nls;
  check(CVodeSetNonlinearSolver(memory_, nls), "CVodeSetNonlinearSolver");
  check(CVodeSetUserData(memory_, this), "CVodeSetUserData");
  check(CVodeRootInit(memory_, 1, cvode_root), "CVodeRootInit");
  check(CVodeSetMaxNumSteps(memory_, 100'000'000), "CVodeSetMaxNumSteps");
}

cvode_adams::~cvode_adams() {
  CVodeFree(&memory_);
  SUNNonlinSolFree(static_cast<SUNNonlinearSolver>(nonlinear_));
  N_VDestroy(static_cast<N_Vector>(vector_));
  SUNContext ctx = static_cast<SUNContext>(context_);
  SUNContext_Free(&ctx);
}

segment_outcome cvode_adams::advance(const segment_problem& prob, double t0, const double y0[2],
                                     double t_stop) {
  problem = &prob;
  auto y = static_cast<N_Vector>(vector_);
  double* yd = N_VGetArrayPointer(y);
  yd[0] = y0[0];
  yd[1] = y0[1];
  check(CVodeReInit(memory_, t0, y), "CVodeReInit");
  check(CVodeSetStopTime(memory_, t_stop), "CVodeSetStopTime");
  int direction = prob.direction() > 0 ? 1 : -1;
  check(CVodeSetRootDirection(memory_, &direction), "CVodeSetRootDirection");
  segment_outcome out;
  double t = t0;
  int flag = CV_SUCCESS;
  do {
    flag = CVode(memory_, t_stop, y, &t, CV_NORMAL);
    check(flag, "CVode");
  } while (flag != CV_ROOT_RETURN && flag != CV_TSTOP_RETURN && t < t_stop);
  out.t = flag == CV_ROOT_RETURN ? t : t_stop;
  out.y[0] = yd[0];
  out.y[1] = yd[1];
  out.event = flag == CV_ROOT_RETURN;
  long n = 0;
  CVodeGetNumSteps(memory_, &n);
  steps_ += static_cast<std::uint64_t>(n);
  CVodeGetNumRhsEvals(memory_, &n);
  rhs_evaluations_ += static_cast<std::uint64_t>(n);
  return out;
}

}  // namespace stickslip::bench
