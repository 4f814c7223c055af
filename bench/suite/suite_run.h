/* -----------------------------------------------------------------------------
 * Lignum benchmarks, the standard multibody suite: one run of a problem of
 * suite_problem.h with Lignum (suite_lignum.c) or with IDA (suite_ida.c),
 * rtol = atol = tol, and what the tables report.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_SUITE_RUN_H
#define LGN_SUITE_RUN_H

#include "suite_problem.h"

/* Lignum's method for a run. */
typedef struct {
  int bdf_maxord;  /* 1 ... 5: the BDF family; 0: generalized-alpha        */
  double rho_inf;  /* generalized-alpha's spectral radius at infinity       */
  int constraints; /* LGN_CONSTR_INDEX3 (default), _INDEX2 or _GGL          */
  int newton;      /* LGN_NEWTON_FULL or LGN_NEWTON_MODIFIED                */
} SuiteLignumMethod;

typedef struct {
  int flag;          /* 0: success (t_end reached), else the solver's flag   */
  double t;          /* time reached                                         */
  double q[SUITE_MAXN], v[SUITE_MAXN], lambda[SUITE_MAXN]; /* at t          */
  double err;        /* the suite's error (suite_problem.h); NaN on failure  */
  double err_v;      /* the same over the velocities (NaN if no reference)   */
  double mescd;      /* -log10(err), the Test Set's mixed significant digits */
  double energy_drift; /* max |E - E(0)| over the outputs (NaN: no energy)  */
  double phi_end;    /* max |Phi(q(t))| at the end                            */
  long int nsteps, nrejected; /* steps, rejected steps (error test + Newton) */
  long int nniters, nlu;      /* Newton iterations, LU factorisations       */
  double cpu;        /* process CPU time of the solver calls (s)             */
} SuiteResult;

/* Lignum: the problem on LGNGroup_Rn(n), dense matrix with Lignum's dense
 * LU (LGNLinSol_Dense), error control at rtol = atol = tol, landing on
 * t_end (LGNSetStopTime) or on every output (problems with exact).
 * Returns res->flag. */
int suite_lignum_run(const SuiteProblem *p, const SuiteLignumMethod *method, double tol,
                     SuiteResult *res);

/* IDA's formulations:
 *   SUITE_IDA_INDEX2 (the suite's): y = (q, v, lambda),
 *     q' = v,  M v' + g + B^T lambda = 0,  B v + Phi_t = 0;
 *   SUITE_IDA_GGL (stabilised index 2): y = (q, v, lambda, mu),
 *     q' = v + B^T mu,  M v' + g + B^T lambda = 0,  Phi = 0,  B v + Phi_t = 0.
 * Index 2 is IDA's best form here at rtol = atol = tol: GGL's Newton
 * iteration fails on Andrews' first step from tol 1e-6 on (IDA_CONV_FAIL
 * at h ~ 1e-15; it runs with a given first step and the multipliers'
 * atol scaled up by 1e6, a tuning a user would not find). */
enum { SUITE_IDA_INDEX2 = 0, SUITE_IDA_GGL = 1 };

/* IDA (SUNDIALS 6.4) in its best form: the formulation form, lambda (and
 * mu) algebraic (IDASetId 0, out of the error test by IDASetSuppressAlg),
 * dense LU with IDA's difference-quotient Jacobian, rtol = atol = tol
 * (IDASStolerances), maxord (0: 5), IDASetStopTime(t_end), IDA's own
 * first step; consistent y'(0) from the saddle-point system.
 * Returns res->flag. */
int suite_ida_run(const SuiteProblem *p, double tol, int maxord, int form, SuiteResult *res);

/* The consistent accelerations and multipliers at (t, q, v): the
 * saddle-point system [M B^T; B 0] [v'; lambda] = [-g; -z], z the
 * curvature d/dt(B v + Phi_t) - B v' by central differences of
 * B v + Phi_t along the motion. Returns 0, or -1 if singular. */
int suite_consistent_acceleration(const SuiteProblem *p, double t, const double *q,
                                  const double *v, double *vdot, double *lambda);

/* Fill err, err_v, mescd, phi_end of res from its q, v at t_end (end-value
 * problems; runs with exact track err themselves). */
void suite_finish_result(const SuiteProblem *p, SuiteResult *res);

#endif
