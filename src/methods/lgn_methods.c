/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Method parameters as pure functions (doc/theory.md §2): the Chung-Hulbert
 * map rho_inf -> (alpha_m, alpha_f, beta, gamma), and the admissibility check
 * of a parameter set.
 *
 * Convention (Chung-Hulbert, Arnold-Brüls): alpha_m and alpha_f weight the OLD
 * values, (1-am) a_{n+1} + am a_n = (1-af) vdot_{n+1} + af vdot_n, and the
 * equations of motion are imposed at t_{n+1}. PETSc's TSALPHA2 uses
 * alpha_PETSc = 1 - alpha_CH.
 * ---------------------------------------------------------------------------*/

#include <math.h>

#include "lgn_err.h"
#include "lgn_methods.h"

int LGNGenAlphaFromRhoInf(sunrealtype rho_inf, sunrealtype *alpha_m,
                          sunrealtype *alpha_f, sunrealtype *beta,
                          sunrealtype *gamma)
{
  sunrealtype gp;
  if (alpha_m == NULL || alpha_f == NULL || beta == NULL || gamma == NULL) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__, "An output argument is NULL.");
    return LGN_ILL_INPUT;
  }
  if (!(rho_inf >= SUN_RCONST(0.0) && rho_inf <= SUN_RCONST(1.0))) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__,
              "rho_inf = %g illegal: it must lie in [0, 1].", (double)rho_inf);
    return LGN_ILL_INPUT;
  }
  *alpha_m = (SUN_RCONST(2.0) * rho_inf - SUN_RCONST(1.0)) /
             (rho_inf + SUN_RCONST(1.0));
  *alpha_f = rho_inf / (rho_inf + SUN_RCONST(1.0));
  *gamma   = SUN_RCONST(0.5) + *alpha_f - *alpha_m;
  gp       = *gamma + SUN_RCONST(0.5);
  *beta    = SUN_RCONST(0.25) * gp * gp;
  return LGN_SUCCESS;
}

/* A parameter set is usable when the step is well defined: alpha_m, alpha_f
 * < 1 (they divide), beta > 0 (it divides) and gamma > 0. Stability or order
 * are the user's choice; LGNGetMethodParams reports what is used. */
int lgnCheckMethodParams(sunrealtype alpha_m, sunrealtype alpha_f,
                         sunrealtype beta, sunrealtype gamma, const char **why)
{
  if (!isfinite(alpha_m) || !isfinite(alpha_f) || !isfinite(beta) || !isfinite(gamma)) {
    *why = "every parameter must be finite";
    return LGN_ILL_INPUT;
  }
  if (!(alpha_m < SUN_RCONST(1.0))) {
    *why = "alpha_m must be < 1";
    return LGN_ILL_INPUT;
  }
  if (!(alpha_f < SUN_RCONST(1.0))) {
    *why = "alpha_f must be < 1";
    return LGN_ILL_INPUT;
  }
  if (!(beta > SUN_RCONST(0.0) && beta <= SUN_RCONST(1.0))) {
    *why = "beta must lie in (0, 1]";
    return LGN_ILL_INPUT;
  }
  if (!(gamma > SUN_RCONST(0.0) && gamma <= SUN_RCONST(1.5))) {
    *why = "gamma must lie in (0, 1.5]";
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

/* l_j(t) = prod_{m != j} (t - tau_m)/(tau_j - tau_m) and
 * l_j'(t) = sum_{m != j} 1/(tau_j - tau_m) prod_{r != j, m} (t - tau_r)/(tau_j - tau_r). */
void lgnLagrangeBasis(const sunrealtype *tau, int n, sunrealtype t, sunrealtype *l,
                      sunrealtype *dl)
{
  int j, m, r;
  for (j = 0; j <= n; j++) {
    l[j] = SUN_RCONST(1.0);
    for (m = 0; m <= n; m++)
      if (m != j) l[j] *= (t - tau[m]) / (tau[j] - tau[m]);
    if (dl == NULL) continue;
    dl[j] = SUN_RCONST(0.0);
    for (m = 0; m <= n; m++) {
      sunrealtype p;
      if (m == j) continue;
      p = SUN_RCONST(1.0) / (tau[j] - tau[m]);
      for (r = 0; r <= n; r++)
        if (r != j && r != m) p *= (t - tau[r]) / (tau[j] - tau[r]);
      dl[j] += p;
    }
  }
}
