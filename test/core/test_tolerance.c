/* -----------------------------------------------------------------------------
 * Lignum test: what a tolerance buys under error control (issue 30, item 2),
 * generalized-alpha (rho_inf 0.9, exact kinematics, index 3) with the error
 * per unit step, rtol = atol = tol:
 *
 *  (a) the band: on the heavy top (error of the centre of mass at t = 1
 *      against the ARKODE reference) and on the 3-rod chain (tip at t = 1
 *      against IDA at rtol 1e-12, bench/work_precision --chain-reference)
 *      the global error is at most BAND times the tolerance at tol 1e-5 ...
 *      1e-8 (measured 10 - 57; IDA's at the same tolerances, GGL index 2,
 *      rtol = atol = tol: 41 - 260 on the top, 5 - 49 on the chain,
 *      bench/tolerance_band), and at least a tenth of it (an estimate that
 *      overshoots by orders of magnitude wastes steps);
 *  (b) every decade of tolerance lowers the error;
 *  (c) the error follows tol^p with p >= 0.9 (least squares over the four
 *      tolerances; the error per step made it tol^0.6 ... 0.7);
 *  (d) the Newton mode changes the error by less than 20 % at equal steps:
 *      full and modified Newton at tol 1e-7 and 1e-8 take the same steps to
 *      within 2 % and agree in the error to 20 % (Newton stops at epcon of
 *      the error test's velocity tolerance, lgnNewtonTolerances).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_ls.h>

#include "lgn_reference.h"
#include "models/chain.h"
#include "models/heavy_top.h"
#include "test_util.h"

#define NTOL 4 /* tol = 1e-5 ... 1e-8 */
#define BAND 100.0
static const double CHAIN_TIP_REF[3] = {-1.855169400564356, -6.545653961586941e-03,
                                        -2.068593335280935};

typedef struct {
  int ok;
  double err;
  long int steps;
} Run;

static double Dist3(const double *a, const double *b)
{
  const double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

static Run HeavyTop(double tol, int newton, const double xref[3])
{
  HeavyTopOptions o;
  HeavyTopResult r;
  Run out;
  heavy_top_default_options(&o);
  o.method = HT_GENALPHA;
  o.rho_inf = 0.9;
  o.kinematics = LGN_KINEMATICS_EXACT;
  o.newton = newton;
  o.adaptive = 1;
  o.single_solve = 1;
  o.rtol = o.atol = tol;
  o.h = o.t_end = 1.0;
  o.make_ls = LGNLinSol_Dense;
  heavy_top_run(&o, &r);
  out.ok = r.flag == LGN_SUCCESS && r.t == 1.0;
  out.err = Dist3(r.x, xref);
  out.steps = r.nsteps;
  return out;
}

/* the free end of the last of n rods (x, p per body: centre + R (0, 0, -1/2)) */
static void Tip(int n, const double *q, double tip[3])
{
  const double *x = q + 7 * (n - 1), *p = x + 3;
  const double w = p[0], a = p[1], b = p[2], c = p[3];
  /* third column of R(p) (scalar first), times -L/2 */
  const double r02 = 2.0 * (a * c + w * b), r12 = 2.0 * (b * c - w * a),
               r22 = 1.0 - 2.0 * (a * a + b * b);
  tip[0] = x[0] - 0.5 * r02;
  tip[1] = x[1] - 0.5 * r12;
  tip[2] = x[2] - 0.5 * r22;
}

static Run Chain(double tol, int newton, SUNContext ctx)
{
  RigidSystem *sys = chain_create(3, RB_R3XSO3, ctx);
  RigidRunOptions o;
  RigidRunResult r;
  Run out = {0, NAN, 0};
  double tip[3];
  if (sys == NULL) return out;
  rigid_default_run_options(&o);
  o.method = 1;
  o.rho_inf = 0.9;
  o.kinematics = LGN_KINEMATICS_EXACT;
  o.newton = newton;
  o.analytic = 1;
  o.adaptive = 1;
  o.rtol = o.atol = tol;
  o.h = 1e-4;
  o.t_end = 1.0;
  o.outputs = 1;
  if (rigid_run(sys, &o, &r) == LGN_SUCCESS && r.q != NULL) {
    Tip(3, r.q, tip);
    out.ok = fabs(r.t - 1.0) < 1e-12;
    out.err = Dist3(tip, CHAIN_TIP_REF);
    out.steps = r.nsteps;
  }
  rigid_result_free(&r);
  rigid_free(&sys);
  return out;
}

static double Slope(const double *tol, const Run *r, int n)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int i;
  for (i = 0; i < n; i++) {
    const double x = log(tol[i]), y = log(r[i].err);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

int main(void)
{
  SUNContext ctx;
  LGNRefHeavyTop ref;
  const double t1 = 1.0;
  double tol[NTOL];
  Run run[2][NTOL];
  int prob, i;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  CHECK(lgnref_heavy_top(&t1, 1, &ref, LGNREF_FEHLBERG_8) == 0, "reference");
  for (i = 0; i < NTOL; i++) tol[i] = 1e-5 / pow(10.0, i);

  for (prob = 0; prob < 2; prob++) {
    const char *name = prob == 0 ? "heavy top" : "chain";
    double p;
    printf("(a) %s, generalized-alpha, error at t = 1 against tol\n", name);
    for (i = 0; i < NTOL; i++) {
      Run *r = &run[prob][i];
      *r = prob == 0 ? HeavyTop(tol[i], LGN_NEWTON_FULL, ref.x)
                     : Chain(tol[i], LGN_NEWTON_FULL, ctx);
      printf("  tol %.0e  steps %7ld  error %.3e  error / tol %.1f\n", tol[i], r->steps, r->err,
             r->err / tol[i]);
      CHECK(r->ok, "%s tol %g: the run failed", name, tol[i]);
      CHECK(r->err <= BAND * tol[i] && r->err >= 0.1 * tol[i],
            "(a) %s tol %g: error %.3e, error / tol %.1f outside [0.1, %g]", name, tol[i],
            r->err, r->err / tol[i], BAND);
      if (i > 0)
        CHECK(r->err < run[prob][i - 1].err, "(b) %s: error %.3e at tol %g, not below %.3e at %g",
              name, r->err, tol[i], run[prob][i - 1].err, tol[i - 1]);
    }
    p = Slope(tol, run[prob], NTOL);
    printf("(c) %s: error ~ tol^%.3f\n", name, p);
    CHECK(p >= 0.9 && p <= 1.2, "(c) %s: error ~ tol^%.3f, not in [0.9, 1.2]", name, p);

    /* (d) modified Newton at the tolerances where the runs of both modes
     * take the same steps (at 1e-5 and 1e-6 the modes' rejections differ) */
    for (i = 2; i < NTOL; i++) {
      const Run *f = &run[prob][i];
      const Run m = prob == 0 ? HeavyTop(tol[i], LGN_NEWTON_MODIFIED, ref.x)
                              : Chain(tol[i], LGN_NEWTON_MODIFIED, ctx);
      const double dsteps = fabs((double)(m.steps - f->steps)) / (double)f->steps;
      const double derr = fabs(m.err - f->err) / f->err;
      printf("(d) %s tol %.0e: modified Newton %ld steps, error %.3e (full: %ld, %.3e; "
             "%.1f %%)\n", name, tol[i], m.steps, m.err, f->steps, f->err, 100.0 * derr);
      CHECK(m.ok && dsteps <= 0.02, "(d) %s tol %g: steps %ld and %ld differ by %.1f %%", name,
            tol[i], m.steps, f->steps, 100.0 * dsteps);
      CHECK(derr < 0.2, "(d) %s tol %g: the Newton mode changes the error by %.1f %%", name,
            tol[i], 100.0 * derr);
    }
  }
  SUNContext_Free(&ctx);
  return test_summary("test_tolerance");
}
