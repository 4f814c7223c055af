/* Convergence of the heavy top (doc/accuracy-study.md) in the centre-of-mass
 * position at t = 1 s, against the independent reference (ARKODE Fehlberg
 * 7(8) at tol 1e-13 on the equivalent ODE, models/lgn_reference.c): Lie group
 * generalized-alpha (rho_inf 0.9) and Euler-parameter generalized-alpha must
 * show an observed order 2.0 +- 0.1 (least-squares fit over four step sizes).
 * The table also lists the other methods for information. */
#include <lignum/lignum.h>

#include "lgn_reference.h"
#include "models/heavy_top.h"
#include "heavy_top_errors.h"
#include "test_util.h"

#define NH 4

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
  order = StudyOrder(&opt, &ref, h, NH, err, NULL);
  printf("  fitted order %.3f\n", order);
  CHECK(fabs(order - 2.0) <= 0.1, "LGGalpha(0.9) order %.3f = 2.0 +- 0.1", order);
  CHECK(err[NH - 1] < 1e-3, "LGGalpha(0.9) error %.3e < 1e-3 at h = 1.25e-4", err[NH - 1]);

  /* required: Euler-parameter (conventional) generalized-alpha, rho_inf 0.9 */
  heavy_top_default_options(&opt);
  opt.formulation = HT_EULER_PARAMETERS;
  order = StudyOrder(&opt, &ref, h, NH, err, NULL);
  printf("  fitted order %.3f\n", order);
  CHECK(fabs(order - 2.0) <= 0.1, "EP gen-alpha(0.9) order %.3f = 2.0 +- 0.1", order);

  /* the exact-kinematics variant (mod. LGGalpha) and index-2 Newmark */
  heavy_top_default_options(&opt);
  opt.kinematics = LGN_KINEMATICS_EXACT;
  order = StudyOrder(&opt, &ref, h, NH, err, NULL);
  printf("  fitted order %.3f\n", order);
  CHECK(fabs(order - 2.0) <= 0.1, "mod. LGGalpha(0.9) order %.3f = 2.0 +- 0.1", order);

  heavy_top_default_options(&opt);
  opt.method = HT_NEWMARK;
  opt.constraints = LGN_CONSTR_INDEX2;
  order = StudyOrder(&opt, &ref, h, NH, err, NULL);
  printf("  fitted order %.3f\n", order);
  CHECK(fabs(order - 2.0) <= 0.1, "LGNM index 2 order %.3f = 2.0 +- 0.1", order);

  return test_summary("test_convergence");
}
