/* Convergence of the heavy top (spec numerics.md §5) in the centre-of-mass
 * position at t = 1 s, against the independent reference (ARKODE Fehlberg
 * 7(8) at tol 1e-13 on the equivalent ODE, test/reference): Lie group
 * generalized-alpha (rho_inf 0.9) and Euler-parameter generalized-alpha must
 * show an observed order 2.0 +- 0.1 (least-squares fit over four step sizes).
 * The table also lists the other methods for information. */
#include <lignum/lignum.h>

#include "lgn_reference.h"
#include "models/heavy_top.h"
#include "heavy_top_errors.h"
#include "test_util.h"

#define NH 4

/* Run one method over the step sizes; returns the fitted order (0 if a run
 * failed) and prints a table row per step size. */
static double Study(HeavyTopOptions *opt, const LGNRefHeavyTop *ref, const double *h,
                    double *err)
{
  char name[96];
  int j;
  heavy_top_describe(opt, name, sizeof name);
  for (j = 0; j < NH; j++) {
    HeavyTopResult res;
    opt->h = h[j];
    if (heavy_top_run(opt, &res) != LGN_SUCCESS) {
      printf("%-28s h = %.4e  failed: %s at t = %.4f\n", name, h[j],
             LGNGetReturnFlagName(res.flag), res.t);
      return 0.0;
    }
    err[j] = ComError(&res, ref);
    printf("%-28s h = %.4e  err_com = %.4e  err_rot = %.4e  newton/step = %.2f\n",
           name, h[j], err[j], lgnref_rotation_error(ref->R, res.R),
           (double)res.nniters / (double)res.nsteps);
  }
  return FittedOrder(h, err, NH);
}

int main(void)
{
  const double t_end = 1.0;
  const double h[NH] = {1e-3, 5e-4, 2.5e-4, 1.25e-4};
  double err[NH], order;
  LGNRefHeavyTop ref;
  HeavyTopOptions opt;

  CHECK(lgnref_heavy_top(&t_end, 1, &ref, 1) == 0, "reference solution computed");

  /* required: Lie group generalized-alpha, rho_inf 0.9, index 3 */
  heavy_top_default_options(&opt);
  order = Study(&opt, &ref, h, err);
  printf("  fitted order %.3f\n", order);
  CHECK(fabs(order - 2.0) <= 0.1, "LGGalpha(0.9) order %.3f = 2.0 +- 0.1", order);
  CHECK(err[NH - 1] < 1e-3, "LGGalpha(0.9) error %.3e < 1e-3 at h = 1.25e-4", err[NH - 1]);

  /* required: Euler-parameter (conventional) generalized-alpha, rho_inf 0.9 */
  heavy_top_default_options(&opt);
  opt.formulation = HT_EULER_PARAMETERS;
  order = Study(&opt, &ref, h, err);
  printf("  fitted order %.3f\n", order);
  CHECK(fabs(order - 2.0) <= 0.1, "EP gen-alpha(0.9) order %.3f = 2.0 +- 0.1", order);

  /* the exact-kinematics variant (mod. LGGalpha) and index-2 Newmark */
  heavy_top_default_options(&opt);
  opt.kinematics = LGN_KINEMATICS_EXACT;
  order = Study(&opt, &ref, h, err);
  printf("  fitted order %.3f\n", order);
  CHECK(fabs(order - 2.0) <= 0.1, "mod. LGGalpha(0.9) order %.3f = 2.0 +- 0.1", order);

  heavy_top_default_options(&opt);
  opt.method = HT_NEWMARK;
  opt.constraints = LGN_CONSTR_INDEX2;
  order = Study(&opt, &ref, h, err);
  printf("  fitted order %.3f\n", order);
  CHECK(fabs(order - 2.0) <= 0.1, "LGNM index 2 order %.3f = 2.0 +- 0.1", order);

  return test_summary("test_convergence");
}
