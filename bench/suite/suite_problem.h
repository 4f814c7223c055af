/* -----------------------------------------------------------------------------
 * Lignum benchmarks, the standard multibody suite: a problem as a
 * second-order DAE on R^n, written once and shared by the Lignum driver
 * (suite_lignum.c, the group LGNGroup_Rn), the IDA driver (suite_ida.c),
 * the benchmark (suite.c) and the tests (test_suite.c):
 *
 *   q' = v,   M(q, t) v' + g(q, v, t) + B(q, t)^T lambda = 0,   Phi(q, t) = 0,
 *
 * B = dPhi/dq, and the velocity constraint B v + Phi_t = 0. The signs are
 * Lignum's (lignum.h): a model written as M v' = f - G^T lambda has
 * g = -f and the same lambda.
 *
 * Problems (suite_problems.c):
 *   Andrews' squeezing mechanism and the car axis of the Test Set for IVP
 *   Solvers (Mazzia et al.), index 3, with the Test Set's reference values
 *   at t_end (published in andrews.f / caraxis.f, subroutine solut);
 *   the IFToMM benchmark A01 (planar simple pendulum over 2000 s), whose
 *   reference is the exact solution in Jacobi elliptic functions.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_SUITE_PROBLEM_H
#define LGN_SUITE_PROBLEM_H

#define SUITE_MAXN 8 /* largest n (positions) and m (constraints) */

typedef struct SuiteProblem {
  const char *name;  /* short name: "andrews", "caraxis", "pendulum"        */
  const char *title; /* one line for the tables                              */
  int n, m;          /* positions (= velocities) and constraints              */
  double t_end;      /* t in [0, t_end]                                       */

  /* the model (row-major matrices: M is n x n, B is m x n) */
  void (*mass)(double t, const double *q, double *M);
  void (*force)(double t, const double *q, const double *v, double *g);
  void (*constraints)(double t, const double *q, double *phi);
  void (*jacobian)(double t, const double *q, double *B);
  void (*phi_t)(double t, const double *q, double *phit); /* NULL: Phi(q) */
  int mass_constant; /* 1: M depends on neither q nor t                      */

  const double *q0, *v0; /* consistent initial values at t = 0              */

  /* Reference at t_end (end-value problems): q, v and lambda (Lignum's
   * sign); NULL when not published (q_ref NULL: the problem has exact). */
  const double *q_ref, *v_ref, *lambda_ref;
  /* Reference along the motion (IFToMM A01): the exact q(t), v(t); the
   * error is then the largest position error over noutputs equally spaced
   * output times (the benchmark's definition), NULL for end-value problems. */
  void (*exact)(double t, double *q, double *v);
  int noutputs;
  /* Mechanical energy (NULL: none): its largest drift over the outputs. */
  double (*energy)(const double *q, const double *v);

  double ref_accuracy; /* the reference's own error in the error measure     */
  const char *reference; /* where the reference comes from                   */
} SuiteProblem;

/* The problems of the suite: "andrews", "caraxis", "pendulum" (NULL if
 * unknown). */
const SuiteProblem *suite_problem(const char *name);
extern const SuiteProblem SUITE_ANDREWS, SUITE_CAR_AXIS, SUITE_PENDULUM;

/* The error measure of the suite at the end of a run (end-value problems):
 * the Test Set's mixed error over the positions,
 *   max_i |q_i - q_ref,i| / (1 + |q_ref,i|)       (atol / rtol = 1),
 * whose -log10 is the Test Set's mescd. */
double suite_mixed_error(const SuiteProblem *p, const double *q);
/* The same over the velocities (NaN when no v_ref is published). */
double suite_mixed_error_v(const SuiteProblem *p, const double *v);

/* Jacobi elliptic functions sn, cn, dn of (u | k^2) by the arithmetic-
 * geometric mean (Abramowitz and Stegun 16.4), u reduced modulo the period
 * 4K first, and K(k) = pi / (2 AGM(1, sqrt(1 - k^2))) (A&S 17.6): the
 * pendulum's exact solution, exported for its test. */
void suite_jacobi(double u, double k, double *sn, double *cn, double *dn);
double suite_elliptic_k(double k);

#endif
