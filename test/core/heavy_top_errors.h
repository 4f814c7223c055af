/* Error measures of heavy top runs against the reference, shared by the
 * convergence tests: centre-of-mass error, the least-squares order, and one
 * method run over a list of step sizes. */
#ifndef LGN_HEAVY_TOP_ERRORS_H
#define LGN_HEAVY_TOP_ERRORS_H

#include <math.h>
#include <stdio.h>

#include "lgn_reference.h"
#include "models/heavy_top.h"

/* |x - x_ref|_2 */
static inline double ComError(const HeavyTopResult *r, const LGNRefHeavyTop *ref)
{
  double e = 0.0;
  int k;
  for (k = 0; k < 3; k++) e += (r->x[k] - ref->x[k]) * (r->x[k] - ref->x[k]);
  return sqrt(e);
}

/* Least-squares slope of log(err) against log(h) over n runs. */
static inline double FittedOrder(const double *h, const double *err, int n)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int j;
  for (j = 0; j < n; j++) {
    double x = log(h[j]), y = log(err[j]);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/* One method over the nh step sizes h: prints a row per step size, fills
 * err, returns the fitted order (0 if a run failed) and, when max_phi is not
 * NULL, the max |Phi| over all runs. */
static inline double StudyOrder(HeavyTopOptions *opt, const LGNRefHeavyTop *ref,
                                const double *h, int nh, double *err,
                                double *max_phi)
{
  char name[96];
  int j;
  heavy_top_describe(opt, name, sizeof name);
  if (max_phi != NULL) *max_phi = 0.0;
  for (j = 0; j < nh; j++) {
    HeavyTopResult res;
    opt->h = h[j];
    if (heavy_top_run(opt, &res) != LGN_SUCCESS) {
      printf("%-30s h = %.4e  failed: %s at t = %.4f\n", name, h[j],
             LGNGetReturnFlagName(res.flag), res.t);
      return 0.0;
    }
    err[j] = ComError(&res, ref);
    printf("%-30s h = %.4e  err_com = %.4e  err_rot = %.4e  newton/step = %.2f",
           name, h[j], err[j], lgnref_rotation_error(ref->R, res.R),
           (double)res.nniters / (double)res.nsteps);
    if (max_phi != NULL) {
      *max_phi = fmax(*max_phi, res.max_phi);
      printf("  max|Phi| = %.2e", res.max_phi);
    }
    printf("\n");
  }
  return FittedOrder(h, err, nh);
}

#endif
