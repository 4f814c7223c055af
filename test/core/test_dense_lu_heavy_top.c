/* -----------------------------------------------------------------------------
 * The heavy top (models/heavy_top.c) with Lignum's dense LU
 * (LGNLinSol_Dense) gives SUNLinSol_Dense's trajectory to roundoff: 1000
 * fixed steps (h = 1e-3, t = 1) with every formulation (R^3 x SO(3),
 * SE(3), Euler parameters), method (Newmark, generalized-alpha), kinematics
 * (simplified, exact, sigma), constraint index (3, 2) and Newton mode (full,
 * modified), and error-controlled runs: final x, p, u, Omega, lambda within
 * 1e-12 relative, the same numbers of steps, iterations and setups; a
 * configuration that fails with one solver fails with the same flag with
 * the other. The largest difference found is printed.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>

#include "models/heavy_top.h"
#include "test_util.h"

/* max |a - b| / max(|b|, tiny) over n entries */
static double RelDiff(const double *a, const double *b, int n)
{
  double d = 0.0, s = 1e-300;
  int i;
  for (i = 0; i < n; i++) {
    d = fmax(d, fabs(a[i] - b[i]));
    s = fmax(s, fabs(b[i]));
  }
  return d / s;
}

static double worst = 0.0;
static int nruns = 0, nfailed = 0;

static void Pair(const HeavyTopOptions *base)
{
  HeavyTopOptions opt = *base;
  HeavyTopResult sun, lgn;
  char name[128];
  double d;
  heavy_top_describe(&opt, name, sizeof name);
  opt.make_ls = NULL; /* SUNLinSol_Dense */
  heavy_top_run(&opt, &sun);
  opt.make_ls = LGNLinSol_Dense;
  heavy_top_run(&opt, &lgn);
  nruns++;
  CHECK(sun.flag == lgn.flag, "%s (%s Newton%s): flags %d (SUNLinSol_Dense) and %d", name,
        opt.newton == LGN_NEWTON_FULL ? "full" : "modified", opt.adaptive ? ", adaptive" : "",
        sun.flag, lgn.flag);
  if (sun.flag != LGN_SUCCESS || lgn.flag != LGN_SUCCESS) {
    nfailed++;
    CHECK(sun.t == lgn.t, "%s: failed at the same time (%.17g, %.17g)", name, sun.t, lgn.t);
    printf("  %s (%s Newton%s): %s with both solvers\n", name,
           opt.newton == LGN_NEWTON_FULL ? "full" : "modified", opt.adaptive ? ", adaptive" : "",
           LGNGetReturnFlagName(sun.flag));
    return;
  }
  d = fmax(fmax(RelDiff(lgn.x, sun.x, 3), RelDiff(lgn.p, sun.p, 4)),
           fmax(fmax(RelDiff(lgn.u, sun.u, 3), RelDiff(lgn.Omega, sun.Omega, 3)),
                RelDiff(lgn.lambda, sun.lambda, 3)));
  worst = fmax(worst, d);
  CHECK(d <= 1e-12, "%s (%s Newton%s): relative difference %.3e", name,
        opt.newton == LGN_NEWTON_FULL ? "full" : "modified", opt.adaptive ? ", adaptive" : "", d);
  CHECK(sun.nsteps == lgn.nsteps && sun.nniters == lgn.nniters && sun.nlsetups == lgn.nlsetups &&
            sun.nlsolves == lgn.nlsolves,
        "%s: the same counts (steps %ld/%ld, iterations %ld/%ld, setups %ld/%ld)", name,
        sun.nsteps, lgn.nsteps, sun.nniters, lgn.nniters, sun.nlsetups, lgn.nlsetups);
  CHECK(fabs(lgn.t - 1.0) < 1e-12 && (opt.adaptive || lgn.nsteps == 1000),
        "%s: 1000 steps to t = 1 (%ld, t = %g)", name, lgn.nsteps, lgn.t);
}

int main(void)
{
  static const HeavyTopFormulation forms[] = {HT_LIE, HT_SE3, HT_EULER_PARAMETERS};
  static const int kins[] = {LGN_KINEMATICS_SIMPLIFIED, LGN_KINEMATICS_EXACT,
                             LGN_KINEMATICS_SIGMA};
  static const int idx[] = {LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2};
  static const int newton[] = {LGN_NEWTON_FULL, LGN_NEWTON_MODIFIED};
  HeavyTopOptions opt;
  int f, m, k, c, nw;
  for (f = 0; f < 3; f++)
    for (m = 0; m < 2; m++)
      for (k = 0; k < 3; k++)
        for (c = 0; c < 2; c++)
          for (nw = 0; nw < 2; nw++) {
            heavy_top_default_options(&opt);
            opt.formulation  = forms[f];
            opt.method       = m == 0 ? HT_NEWMARK : HT_GENALPHA;
            opt.kinematics   = kins[k];
            opt.constraints  = idx[c];
            opt.newton       = newton[nw];
            opt.h            = 1e-3;
            opt.t_end        = 1.0;
            opt.single_solve = 1;
            Pair(&opt);
          }
  /* error control (h the output interval) */
  for (f = 0; f < 3; f++)
    for (nw = 0; nw < 2; nw++) {
      heavy_top_default_options(&opt);
      opt.formulation  = forms[f];
      opt.newton       = newton[nw];
      opt.adaptive     = 1;
      opt.rtol         = 1e-6;
      opt.atol         = 1e-6;
      opt.h            = 0.1;
      opt.t_end        = 1.0;
      Pair(&opt);
    }
  printf("heavy top: %d configurations (%d refused or failed alike with both solvers); "
         "max relative difference of the final state, LGNLinSol_Dense vs SUNLinSol_Dense: "
         "%.3e\n",
         nruns, nfailed, worst);
  CHECK(nfailed <= nruns / 4, "most configurations run (%d of %d failed)", nfailed, nruns);
  return test_summary("test_dense_lu_heavy_top");
}
