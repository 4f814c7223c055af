/* -----------------------------------------------------------------------------
 * Lignum benchmarks: the heavy top (doc/accuracy-study.md) for SUNDIALS IDA, as
 * the stabilised index-2 (GGL, Gear-Gupta-Leimkuhler) DAE in Euler parameters,
 * with the physics of Lignum's HT_EULER_PARAMETERS model
 * (models/heavy_top.c, doc/theory.md §1.1): q = (x, p) in R^7, v = qdot,
 *
 *   q' = v + B(q)^T mu                       (7, GGL: mu = 0 on the solution)
 *   M(q) v' + g(q, v) + B(q)^T lambda = 0    (7)
 *   Phi(q) = [X - R(p)^T x ; p.p - 1] = 0    (4, position level)
 *   B(q) v = 0                               (4, velocity level)
 *
 * with M = diag(m I, 4 G^T J G), g = [-m gamma_g ; 8 Gdot^T J G pdot],
 * B = dPhi/dq.  Unknowns y = (q, v, lambda, mu), 22 components; lambda and mu
 * are algebraic (IDASetId 0, excluded from the error test).  Consistent
 * initial values from the saddle-point system; the analytic Jacobian
 * dF/dy + c_j dF/dy' is written out in ida_heavy_top.c.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_IDA_HEAVY_TOP_H
#define LGN_IDA_HEAVY_TOP_H

/* Number of unknowns and their offsets in y. */
#define IDAHT_N  22
#define IDAHT_OQ 0  /* q = (x, p0, pbar)       7 */
#define IDAHT_OV 7  /* v = (xdot, pdot)        7 */
#define IDAHT_OL 14 /* lambda (joint 3, norm 1) */
#define IDAHT_OM 18 /* mu (GGL)                4 */

/* Linear solver set-ups. */
typedef enum {
  IDAHT_DENSE_DQ = 0,  /* dense LU, IDA's difference-quotient Jacobian */
  IDAHT_DENSE_JAC = 1, /* dense LU, analytic Jacobian                  */
  IDAHT_KLU = 2        /* sparse KLU (CSC), analytic Jacobian          */
} IdaHTLinSol;

typedef struct {
  IdaHTLinSol linsol;
  double rtol;
  double t_end;
  /* absolute tolerances atol_i = rtol * scale_i per block (<= 0: defaults
   * 1 for x and p, 5 for xdot, 75 for pdot, 1e3 for lambda, 1 for mu) */
  double scale_x, scale_p, scale_xd, scale_pd, scale_lambda, scale_mu;
  int maxord;        /* 0: IDA's default 5                         */
  double h0;         /* > 0: IDASetInitStep; 0: IDA's own estimate */
  double epcon;      /* > 0: IDASetNonlinConvCoef; 0: default 0.33  */
  double dcj;        /* > 0: IDASetDeltaCjLSetup; 0: default 0.25   */
  int maxcor;        /* > 0: IDASetMaxNonlinIters; 0: default 4     */
  int no_ls_scaling; /* 1: IDASetLinearSolutionScaling(SUNFALSE)     */
  long int max_steps;/* 0: 1000000                                 */
} IdaHTOptions;

typedef struct {
  int flag;              /* IDA return flag of the last call (0: success) */
  double t;              /* time reached                                  */
  double x[3];           /* centre of mass at t                           */
  double p[4];           /* Euler parameters at t (raw)                   */
  double max_phi_end;    /* |Phi(q(t))|_inf                               */
  long int nsteps, nniters, nres, njevals, netf, nncf;
  double cpu_seconds;    /* process CPU time of IDASolve only             */
} IdaHTResult;

void ida_heavy_top_default_options(IdaHTOptions *opt);

/* Run one configuration from the consistent initial values to t_end.
 * Returns the IDA flag (also in res->flag); -100 on set-up failure. */
int ida_heavy_top_run(const IdaHTOptions *opt, IdaHTResult *res);

/* Consistent initial values y0, yp0 (IDAHT_N each) and the residual norm
 * max|F(0, y0, yp0)|; returns 0 on success. */
int ida_heavy_top_initial(double *y0, double *yp0, double *res_norm);

/* Check the analytic Jacobian against central differences of the residual
 * at a perturbed, non-consistent state (all blocks nonzero), for c_j = cj.
 * Returns max |J_an - J_dq| / (1 + max |J_an|). */
double ida_heavy_top_check_jacobian(double cj);

/* "dense-DQ", "dense-Jac", "KLU" */
const char *ida_heavy_top_linsol_name(IdaHTLinSol ls);

#endif
