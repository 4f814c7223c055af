/* -----------------------------------------------------------------------------
 * Lignum benchmarks: the N-body spherical pendulum chain of
 * models/chain.c (rods of 1 m, 1 kg, radius 0.02 m, spherical
 * joints, the top of rod 0 at the origin, gravity -9.81 z, at rest in the
 * bent, slightly twisted initial configuration) for SUNDIALS IDA, formulated
 * like the heavy top of ida_heavy_top.c: the stabilised index-2 (GGL) DAE in
 * Euler parameters, per body k q_k = (x_k, p_k) in R^7, v_k = q_k',
 *
 *   q' = v + B(q)^T mu                       (7 N)
 *   M(q) v' + g(q, v) + B(q)^T lambda = 0    (7 N)
 *   Phi(q) = 0                               (4 N: 3 N joints, N norms)
 *   B(q) v = 0                               (4 N)
 *
 * M_k = diag(m I, 4 G(p)^T J G(p)), g_k = [-m gravity ; 8 G(p')^T J G(p) p'],
 * joint j: Phi_j = x_{j-1} + R_{j-1} (0,0,-L/2) - x_j - R_j (0,0,L/2)
 * (the ground's point 0 for j = 0), Phi_{3N+k} = p_k.p_k - 1, B = dPhi/dq.
 * Unknowns y = (q, v, lambda, mu), 22 N; lambda and mu algebraic (IDASetId
 * 0, excluded from the error test by IDASetSuppressAlg).  Linear solvers as
 * for the heavy top: dense LU with IDA's difference-quotient Jacobian, dense
 * LU with the analytic Jacobian, KLU (CSC) with the analytic Jacobian.
 * Same initial values as Lignum's chain_create() (its q0,
 * v0 = 0); v'0 and lambda0 from the saddle-point system, mu0 = 0.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_IDA_CHAIN_H
#define LGN_IDA_CHAIN_H

#define IDACH_MAXN 8 /* largest number of bodies */

typedef enum {
  IDACH_DENSE_DQ = 0,  /* dense LU, IDA's difference-quotient Jacobian */
  IDACH_DENSE_JAC = 1, /* dense LU, analytic Jacobian                  */
  IDACH_KLU = 2        /* sparse KLU (CSC), analytic Jacobian          */
} IdaChainLinSol;

typedef struct {
  int n;             /* bodies (1..IDACH_MAXN)                           */
  IdaChainLinSol linsol;
  double rtol;
  double t_end;
  /* atol_i = rtol * scale: 1 for x and p, 5 for x' and p', 1e3 for
   * lambda and mu (as for the heavy top) */
  double h0;         /* > 0: IDASetInitStep                              */
  long int max_steps;/* 0: 1000000                                       */
  double scale_v;    /* > 0: atol of x' and p' = rtol * scale_v (0: 5)   */
} IdaChainOptions;

typedef struct {
  int flag;              /* IDA return flag (0: success)                  */
  double t;              /* time reached                                  */
  double tip[3];         /* free end of the last rod at t                 */
  double max_phi_end;    /* |Phi(q(t))|_inf                               */
  long int nsteps, nniters, nres, njevals;
  double cpu_seconds;    /* process CPU time of IDASolve only             */
} IdaChainResult;

void ida_chain_default_options(IdaChainOptions *opt);
int ida_chain_run(const IdaChainOptions *opt, IdaChainResult *res);

/* Consistent initial values (22 n each) and max|F(0, y0, y'0)|; 0 on success. */
int ida_chain_initial(int n, double *y0, double *yp0, double *res_norm);

/* max |B dq - (Phi(q + e dq) - Phi(q - e dq)) / (2 e)| / (1 + max|B|) at a
 * perturbed state: checks the constraint Jacobian the residual uses. */
double ida_chain_check_constraint_jacobian(int n);

/* Analytic Jacobian against central differences of the residual at a
 * perturbed, non-consistent state, for c_j = cj: max |J_an - J_dq| / (1 + max|J_an|). */
double ida_chain_check_jacobian(int n, double cj);

/* "dense-DQ", "dense-Jac", "KLU" */
const char *ida_chain_linsol_name(IdaChainLinSol ls);

/* Tip (free end of the last rod) of a state q (7 n: x, p per body). */
void ida_chain_tip(int n, const double *q, double tip[3]);

#endif
