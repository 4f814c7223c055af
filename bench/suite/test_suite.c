/* -----------------------------------------------------------------------------
 * Lignum benchmarks, the standard multibody suite: checks of every problem
 * (bench/suite/README.md), none timed.
 *
 *  (a) the models: B against central differences of Phi, Phi_t against a
 *      central difference in t, consistent initial values;
 *  (b) the pendulum's exact solution (IFToMM A01's reference): K(1/sqrt 2)
 *      against its published value, q' = v by differences, |q| = 1 and
 *      the energy along 2000 s, the mass at the bottom after a quarter
 *      period;
 *  (c) IDA (index 2, Debian's SUNDIALS) against the published references
 *      of Andrews and the car axis at tol 1e-10, and at tol 1e-12 on
 *      Andrews (the published positions hold to ~1e-9);
 *  (d) Lignum's BDF (maxord 5) and generalized-alpha against the same
 *      references at tight tolerances, and the error / tol band and its
 *      monotonicity at tol 1e-4, 1e-6, 1e-8, 1e-10 against IDA: issue 30
 *      item 2's band for generalized-alpha (error <= 100 tol and <= 3 x
 *      IDA's at the same tol, 1e-4 ... 1e-8), BDF's generous one (its error
 *      test is unchanged, user guide 8.8);
 *  (e) the pendulum over [0, 20] s (40 outputs): the IFToMM high-precision
 *      criterion (position error <= 1e-3 m) and the energy drift, both
 *      codes at tol 1e-8.
 * Exit status 1 if a check fails.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>

#include "suite_run.h"

static int fails = 0;

static void Check(int ok, const char *what, double value, double bound)
{
  printf("  %-4s %-66s %10.3e  (bound %.1e)\n", ok ? "ok" : "FAIL", what, value, bound);
  if (!ok) fails++;
}

static void CheckLe(const char *what, double value, double bound)
{
  Check(value <= bound, what, value, bound); /* NaN fails */
}

/* ---- (a) the models ----------------------------------------------------- */

static void CheckModel(const SuiteProblem *p)
{
  double q[SUITE_MAXN], B[SUITE_MAXN * SUITE_MAXN], pp[SUITE_MAXN], pm[SUITE_MAXN];
  double phi[SUITE_MAXN], w[SUITE_MAXN], dB = 0.0, dT = 0.0, c0 = 0.0, v0 = 0.0;
  const double t = 0.37 * p->t_end, eps = 1e-6;
  char what[128];
  int i, j;
  for (i = 0; i < p->n; i++) q[i] = p->q0[i] + 0.01 * (double)(i + 1); /* off the manifold */
  p->jacobian(t, q, B);
  for (i = 0; i < p->n; i++) { /* column i of B against (Phi(q + e_i eps) - Phi(q - e_i eps)) / 2 eps */
    const double qi = q[i];
    q[i] = qi + eps;
    p->constraints(t, q, pp);
    q[i] = qi - eps;
    p->constraints(t, q, pm);
    q[i] = qi;
    for (j = 0; j < p->m; j++)
      dB = fmax(dB, fabs(B[j * p->n + i] - (pp[j] - pm[j]) / (2 * eps)) / (1.0 + fabs(B[j * p->n + i])));
  }
  snprintf(what, sizeof what, "%s: B against differences of Phi", p->name);
  CheckLe(what, dB, 1e-7);
  if (p->phi_t != NULL) {
    double phit[SUITE_MAXN];
    p->phi_t(t, q, phit);
    p->constraints(t + eps, q, pp);
    p->constraints(t - eps, q, pm);
    for (j = 0; j < p->m; j++) dT = fmax(dT, fabs(phit[j] - (pp[j] - pm[j]) / (2 * eps)));
    snprintf(what, sizeof what, "%s: Phi_t against differences of Phi in t", p->name);
    CheckLe(what, dT, 1e-7);
  }
  p->constraints(0.0, p->q0, phi);
  p->jacobian(0.0, p->q0, B);
  if (p->phi_t != NULL) p->phi_t(0.0, p->q0, w);
  for (j = 0; j < p->m; j++) {
    double bv = p->phi_t != NULL ? w[j] : 0.0;
    for (i = 0; i < p->n; i++) bv += B[j * p->n + i] * p->v0[i];
    c0 = fmax(c0, fabs(phi[j]));
    v0 = fmax(v0, fabs(bv));
  }
  snprintf(what, sizeof what, "%s: |Phi(q0)|", p->name);
  CheckLe(what, c0, 1e-14);
  snprintf(what, sizeof what, "%s: |B v0 + Phi_t|", p->name);
  CheckLe(what, v0, 1e-14);
}

/* ---- (b) the pendulum's exact solution ---------------------------------- */

static void CheckPendulumExact(void)
{
  const SuiteProblem *p = &SUITE_PENDULUM;
  const double K = suite_elliptic_k(sqrt(0.5)), w0 = sqrt(9.81);
  const double times[] = {0.3, 17.1, 555.5, 1999.7};
  double q[2], v[2], qp[2], qm[2], vv[2], dq = 0.0, dl = 0.0, de = 0.0;
  const double e0 = p->energy(p->q0, p->v0), h = 1e-5;
  int k, i;
  /* K(1/sqrt 2) = Gamma(1/4)^2 / (4 sqrt(pi)) = 1.8540746773013719... */
  CheckLe("pendulum: |K(1/sqrt 2) - 1.8540746773013719|", fabs(K - 1.8540746773013719), 1e-15);
  p->exact(0.0, q, v);
  CheckLe("pendulum: exact(0) = (1, 0) at rest", fmax(fmax(fabs(q[0] - 1), fabs(q[1])),
                                                      fmax(fabs(v[0]), fabs(v[1]))), 1e-15);
  p->exact(K / w0, q, v); /* a quarter period: at the bottom, fastest */
  CheckLe("pendulum: exact(T/4) = (0, -1)", fmax(fabs(q[0]), fabs(q[1] + 1)), 1e-14);
  for (k = 0; k < 4; k++) {
    p->exact(times[k] + h, qp, vv);
    p->exact(times[k] - h, qm, vv);
    p->exact(times[k], q, v);
    for (i = 0; i < 2; i++) dq = fmax(dq, fabs((qp[i] - qm[i]) / (2 * h) - v[i]));
    dl = fmax(dl, fabs(hypot(q[0], q[1]) - 1.0));
    de = fmax(de, fabs(p->energy(q, v) - e0));
  }
  CheckLe("pendulum: exact q' = v (central differences, up to t = 2000)", dq, 1e-7);
  CheckLe("pendulum: exact |q| = 1", dl, 1e-14);
  CheckLe("pendulum: exact energy constant", de, 1e-12);
}

/* ---- (c), (d) the Test Set problems ------------------------------------- */

static double RelMax(const double *a, const double *b, int n)
{
  double e = 0.0;
  int i;
  for (i = 0; i < n; i++) e = fmax(e, fabs(a[i] - b[i]) / (1.0 + fabs(b[i])));
  return e;
}

static void CheckIda(const SuiteProblem *p, double tol, double bound_q, double bound_v)
{
  SuiteResult r;
  char what[128];
  suite_ida_run(p, tol, 5, SUITE_IDA_INDEX2, &r);
  snprintf(what, sizeof what, "%s: IDA index 2, tol %.0e: flag", p->name, tol);
  Check(r.flag == 0, what, (double)r.flag, 0.0);
  snprintf(what, sizeof what, "%s: IDA index 2, tol %.0e: position error", p->name, tol);
  CheckLe(what, r.err, bound_q);
  snprintf(what, sizeof what, "%s: IDA index 2, tol %.0e: velocity error", p->name, tol);
  CheckLe(what, r.err_v, bound_v);
}

static void CheckLignum(const SuiteProblem *p, const SuiteLignumMethod *me, const char *name,
                        double tol, double bound_q, double bound_v, double bound_lambda)
{
  SuiteResult r;
  char what[128];
  suite_lignum_run(p, me, tol, &r);
  snprintf(what, sizeof what, "%s: Lignum %s, tol %.0e: flag", p->name, name, tol);
  Check(r.flag == 0, what, (double)r.flag, 0.0);
  snprintf(what, sizeof what, "%s: Lignum %s, tol %.0e: position error", p->name, name, tol);
  CheckLe(what, r.err, bound_q);
  snprintf(what, sizeof what, "%s: Lignum %s, tol %.0e: velocity error", p->name, name, tol);
  CheckLe(what, r.err_v, bound_v);
  snprintf(what, sizeof what, "%s: Lignum %s, tol %.0e: multiplier error", p->name, name, tol);
  CheckLe(what, RelMax(r.lambda, p->lambda_ref, p->m), bound_lambda);
  snprintf(what, sizeof what, "%s: Lignum %s, tol %.0e: |Phi(q(t_end))|", p->name, name, tol);
  CheckLe(what, r.phi_end, 1e-12);
}

/* ===== Issue 30 item 2: the band. ===========================================
 * Asserted: error / tol <= BAND_* at tol 1e-4 ... 1e-10 (generalized-alpha:
 * 1e-4 ... 1e-8, its steps grow like tol^(-1/2)), error <= BAND_VS_IDA_*
 * times IDA's at the same tol, and the error falling by a factor of at
 * least 3 from one tolerance to the next (two decades apart), for BDF
 * maxord 5 and generalized-alpha with full Newton. Measured before item 2
 * (Andrews, car axis): BDF5 error/tol 110-1400, generalized-alpha
 * 150-30,000; IDA 3-31. Generalized-alpha with the error per unit step
 * (item 2): 5.7 - 17, 0.6 - 1.7 times IDA's at these tolerances. BDF is
 * unchanged by item 2 (user guide 8.8): its band stays today's. */
#define BAND_BDF             5e3   /* error / tol, BDF maxord 5            */
#define BAND_GENALPHA        1e2   /* error / tol, generalized-alpha       */
#define BAND_VS_IDA_BDF      1e4   /* error / IDA's error, BDF (open)      */
#define BAND_VS_IDA_GENALPHA 3.0   /* error / IDA's error, generalized-alpha */
/* ========================================================================= */

static void CheckBand(const SuiteProblem *p, const SuiteLignumMethod *me, const char *name,
                      double band, double band_vs_ida, int ntols)
{
  static const double TOLS[] = {1e-4, 1e-6, 1e-8, 1e-10};
  double prev = INFINITY;
  char what[128];
  int k;
  for (k = 0; k < ntols; k++) {
    SuiteResult r, ida;
    suite_lignum_run(p, me, TOLS[k], &r);
    suite_ida_run(p, TOLS[k], 5, SUITE_IDA_INDEX2, &ida);
    snprintf(what, sizeof what, "%s: %s, tol %.0e: error / tol", p->name, name, TOLS[k]);
    CheckLe(what, r.err / TOLS[k], band);
    snprintf(what, sizeof what, "%s: %s, tol %.0e: error / IDA's error", p->name, name, TOLS[k]);
    CheckLe(what, r.err / ida.err, band_vs_ida);
    if (k > 0) {
      snprintf(what, sizeof what, "%s: %s, tol %.0e: error / error at 100 tol", p->name, name,
               TOLS[k]);
      CheckLe(what, r.err / prev, 1.0 / 3.0);
    }
    prev = r.err;
  }
}

/* ---- (e) the pendulum, 20 s ---------------------------------------------- */

static void CheckPendulumRun(void)
{
  SuiteProblem p = SUITE_PENDULUM;
  const SuiteLignumMethod bdf5 = {5, 0.9, LGN_CONSTR_INDEX3, LGN_NEWTON_FULL};
  SuiteResult r;
  p.t_end = 20.0;
  p.noutputs = 40; /* every 0.5 s, as the benchmark's 4000 outputs over 2000 s */
  suite_ida_run(&p, 1e-8, 5, SUITE_IDA_INDEX2, &r);
  Check(r.flag == 0, "pendulum, 20 s: IDA tol 1e-8: flag", (double)r.flag, 0.0);
  CheckLe("pendulum, 20 s: IDA tol 1e-8: max position error (IFToMM: 1e-3)", r.err, 1e-3);
  CheckLe("pendulum, 20 s: IDA tol 1e-8: max energy drift (J)", r.energy_drift, 1e-4);
  suite_lignum_run(&p, &bdf5, 1e-8, &r);
  Check(r.flag == 0, "pendulum, 20 s: Lignum BDF5 tol 1e-8: flag", (double)r.flag, 0.0);
  CheckLe("pendulum, 20 s: Lignum BDF5 tol 1e-8: max position error (IFToMM: 1e-3)", r.err,
          1e-3);
  CheckLe("pendulum, 20 s: Lignum BDF5 tol 1e-8: max energy drift (J)", r.energy_drift, 1e-4);
  CheckLe("pendulum, 20 s: Lignum BDF5 tol 1e-8: |Phi(q(t_end))|", r.phi_end, 1e-12);
}

/* ---- (f) modified Newton's matrix policy (issue 33 item 1) --------------- */

/* BDF reuses the factorised matrix while c0 stays within 0.75 ... 1/0.75 of
 * the one it was built with (lgn_newton.c, MatrixReusable). On the car
 * axis (BDF5, tol 1e-8) that is 318 factorisations in 1,828 steps; the
 * 10 % rule on h before it took 714 in 1,827. Asserted: at most one per
 * four steps, and the error within a factor 2 of full Newton's at the
 * same tol (measured 2.34e-6 and 2.35e-6). */
static void CheckMatrixPolicy(void)
{
  const SuiteLignumMethod full = {5, 0.9, LGN_CONSTR_INDEX3, LGN_NEWTON_FULL};
  const SuiteLignumMethod modified = {5, 0.9, LGN_CONSTR_INDEX3, LGN_NEWTON_MODIFIED};
  SuiteResult f, m;
  suite_lignum_run(&SUITE_CAR_AXIS, &full, 1e-8, &f);
  suite_lignum_run(&SUITE_CAR_AXIS, &modified, 1e-8, &m);
  Check(f.flag == 0 && m.flag == 0, "caraxis: BDF5 full and modified Newton, tol 1e-8: flags",
        (double)(f.flag != 0 ? f.flag : m.flag), 0.0);
  CheckLe("caraxis: BDF5 modified Newton, tol 1e-8: factorisations / steps",
          (double)m.nlu / (double)m.nsteps, 0.25);
  CheckLe("caraxis: BDF5, tol 1e-8: error modified / full Newton",
          fmax(m.err / f.err, f.err / m.err), 2.0);
}

int main(void)
{
  const SuiteLignumMethod bdf5 = {5, 0.9, LGN_CONSTR_INDEX3, LGN_NEWTON_FULL};
  const SuiteLignumMethod genalpha = {0, 0.9, LGN_CONSTR_INDEX3, LGN_NEWTON_FULL};

  printf("(a) the models\n");
  CheckModel(&SUITE_ANDREWS);
  CheckModel(&SUITE_CAR_AXIS);
  CheckModel(&SUITE_PENDULUM);
  printf("(b) the pendulum's exact solution\n");
  CheckPendulumExact();
  printf("(c) IDA against the published references\n");
  CheckIda(&SUITE_ANDREWS, 1e-10, 3e-9, 1e-6);
  CheckIda(&SUITE_ANDREWS, 1e-12, 3e-10, 1e-7);
  CheckIda(&SUITE_CAR_AXIS, 1e-10, 2e-8, 1e-6);
  printf("(d) Lignum against the published references, and the band\n");
  CheckLignum(&SUITE_ANDREWS, &bdf5, "BDF5", 1e-12, 3e-8, 1e-5, 1e-4);
  CheckLignum(&SUITE_CAR_AXIS, &bdf5, "BDF5", 1e-12, 3e-9, 1e-7, 1e-5);
  CheckLignum(&SUITE_ANDREWS, &genalpha, "gen-alpha", 1e-8, 3e-6, 1e-3, 1e-2);
  CheckLignum(&SUITE_CAR_AXIS, &genalpha, "gen-alpha", 1e-8, 3e-5, 1e-3, 1e-2);
  CheckBand(&SUITE_ANDREWS, &bdf5, "BDF5", BAND_BDF, BAND_VS_IDA_BDF, 4);
  CheckBand(&SUITE_CAR_AXIS, &bdf5, "BDF5", BAND_BDF, BAND_VS_IDA_BDF, 4);
  CheckBand(&SUITE_ANDREWS, &genalpha, "gen-alpha", BAND_GENALPHA, BAND_VS_IDA_GENALPHA, 3);
  CheckBand(&SUITE_CAR_AXIS, &genalpha, "gen-alpha", BAND_GENALPHA, BAND_VS_IDA_GENALPHA, 3);
  printf("(e) the pendulum over 20 s\n");
  CheckPendulumRun();
  printf("(f) modified Newton's matrix policy\n");
  CheckMatrixPolicy();
  printf("%s: %d check(s) failed\n", fails ? "FAIL" : "PASS", fails);
  return fails ? 1 : 0;
}
