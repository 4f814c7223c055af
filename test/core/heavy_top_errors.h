/* Error measures of a heavy top run against the reference, shared by the
 * convergence tests: centre-of-mass error and the least-squares order. */
#ifndef LGN_HEAVY_TOP_ERRORS_H
#define LGN_HEAVY_TOP_ERRORS_H

#include <math.h>

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

#endif
