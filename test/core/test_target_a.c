/* Reproduction target A (doc/accuracy-study.md): LGGalpha, rho_inf = 0.6,
 * h = 0.002, 10 steps, a_0 = 0, values at t = 0.02 s to all six printed
 * digits (OpenTurbine's pilot-code values), plus the a_0 = vdot_0 variant
 * and the consistent initial values. Analytic and difference-quotient
 * Jacobians must give the same solution (to the Newton tolerance). */
#include <lignum/lignum.h>

#include "models/heavy_top.h"
#include "test_util.h"

int main(void)
{
  HeavyTopOptions opt;
  HeavyTopResult res, res_dq;
  const double x_a[3] = {0.091943, 0.995745, -0.006167};
  const double p_a[4] = {0.070604, 0.045687, 0.996438, -0.006332};
  const double v_a[6] = {4.564702, -0.425498, -0.620310, 1.287734, 150.0, 4.522188};
  const double vd_a[6] = {-6.272347, -24.111949, -29.783310, -560.293932, 0.0, 244.069741};
  const double a_a[6] = {-4.850215, -21.808817, -30.587676, -616.404070, 0.0, 241.543883};
  /* six printed decimals: half a unit in the last place, plus roundoff */
  const double tol6 = 5.0e-7 + 1e-9;
  char what[64];
  int i;

  /* ---- consistent start (t = 0) ---- */
  heavy_top_default_options(&opt);
  opt.t_end = 0.0;
  heavy_top_run(&opt, &res);
  {
    const double vd0[6] = {0, -21.3017325444, -30.9608307692, 661.3461692308, 0, 0};
    const double l0[3] = {0, -319.525988166, -317.2624615385};
    for (i = 0; i < 6; i++) {
      snprintf(what, sizeof what, "vdot0[%d]", i);
      CHECK_CLOSE(res.vdot[i], vd0[i], 1e-9, what);
    }
    for (i = 0; i < 3; i++) {
      snprintf(what, sizeof what, "lambda0[%d]", i);
      CHECK_CLOSE(res.lambda[i], l0[i], 1e-9, what);
    }
  }

  /* ---- target A: a_0 = 0 ---- */
  heavy_top_default_options(&opt);
  opt.rho_inf = 0.6;
  opt.h = 0.002;
  opt.t_end = 0.02;
  opt.zero_a0 = 1;
  opt.rtol = opt.atol = 1e-12;
  CHECK(heavy_top_run(&opt, &res) == LGN_SUCCESS && res.nsteps == 10,
        "10 steps of LGGalpha(0.6) succeed (flag %d, %ld steps)", res.flag, res.nsteps);
  CHECK_CLOSE(res.t, 0.02, 1e-15, "t");
  printf("x = (%.7f, %.7f, %.7f)\n", res.x[0], res.x[1], res.x[2]);
  for (i = 0; i < 3; i++) {
    snprintf(what, sizeof what, "x[%d]", i);
    CHECK_CLOSE(res.x[i], x_a[i], tol6, what);
  }
  for (i = 0; i < 4; i++) {
    snprintf(what, sizeof what, "p[%d]", i);
    CHECK_CLOSE(res.p[i], p_a[i], tol6, what);
  }
  for (i = 0; i < 6; i++) {
    double vi = i < 3 ? res.u[i] : res.Omega[i - 3];
    snprintf(what, sizeof what, "v[%d]", i);
    CHECK_CLOSE(vi, v_a[i], tol6, what);
    snprintf(what, sizeof what, "vdot[%d]", i);
    CHECK_CLOSE(res.vdot[i], vd_a[i], tol6, what);
    snprintf(what, sizeof what, "a[%d]", i);
    CHECK_CLOSE(res.a[i], a_a[i], tol6, what);
  }

  /* ---- the same with difference-quotient Jacobians: same solution ---- */
  opt.analytic_jacobians = 0;
  CHECK(heavy_top_run(&opt, &res_dq) == LGN_SUCCESS, "DQ run succeeds");
  for (i = 0; i < 3; i++) {
    snprintf(what, sizeof what, "x[%d] DQ vs analytic", i);
    CHECK_CLOSE(res_dq.x[i], res.x[i], 1e-10, what);
    snprintf(what, sizeof what, "lambda[%d] DQ vs analytic", i);
    CHECK_CLOSE(res_dq.lambda[i], res.lambda[i], 1e-6, what);
  }
  CHECK(res_dq.ndq > 0 && res.ndq == 0, "DQ evaluations counted only when used (%ld, %ld)",
        res_dq.ndq, res.ndq);

  /* ---- a_0 = vdot_0 (published: x = (0.0919489, 0.9957440, -0.0062635),
   *      v_Omega = (1.2871406, 150, 4.5210325)), seven printed digits ---- */
  opt.analytic_jacobians = 1;
  opt.zero_a0 = 0;
  CHECK(heavy_top_run(&opt, &res) == LGN_SUCCESS, "a_0 = vdot_0 run succeeds");
  {
    const double x_b[3] = {0.0919489, 0.9957440, -0.0062635};
    const double w_b[3] = {1.2871406, 150.0, 4.5210325};
    for (i = 0; i < 3; i++) {
      snprintf(what, sizeof what, "x[%d] (a0 = vdot0)", i);
      CHECK_CLOSE(res.x[i], x_b[i], 5e-8 + 1e-10, what);
      snprintf(what, sizeof what, "Omega[%d] (a0 = vdot0)", i);
      CHECK_CLOSE(res.Omega[i], w_b[i], 5e-8 + 1e-10, what);
    }
  }
  return test_summary("test_target_a");
}
