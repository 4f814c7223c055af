/* -----------------------------------------------------------------------------
 * Lignum study models: the heavy top benchmark (Brüls and Cardona 2010), as a model
 * (callbacks for R^3 x SO(3), for SE(3) and for Euler parameters on R^7) and as a driver
 * that runs one configuration and reports the final state and statistics.
 * Shared by the heavy_top tool, the demo, the tests and the benchmarks.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_HEAVY_TOP_H
#define LGN_HEAVY_TOP_H

#include <stdio.h>
#include <lignum/lignum.h>

/* Data of the benchmark (Brüls and Cardona 2010). */
#define HT_MASS     15.0
#define HT_J1       0.234375
#define HT_J2       0.46875
#define HT_J3       0.234375
#define HT_GRAVITY  (-9.81)     /* gamma_g = (0, 0, HT_GRAVITY) */
#define HT_OMEGA0_Y 150.0
#define HT_OMEGA0_Z (-4.61538)  /* Omega0 = (0, 150, -4.61538), body frame */

/* HT_LIE: R^3 x SO(3); HT_EULER_PARAMETERS: R^7; HT_SE3: SE(3) (doc/theory.md). */
typedef enum { HT_LIE = 0, HT_EULER_PARAMETERS = 1, HT_SE3 = 2 } HeavyTopFormulation;
typedef enum { HT_NEWMARK = 0, HT_GENALPHA = 1 } HeavyTopMethod;

/* One run of the heavy top. */
typedef struct {
  HeavyTopFormulation formulation;
  HeavyTopMethod method;
  double rho_inf;          /* generalized-alpha                          */
  double beta, gamma;      /* Newmark                                    */
  int constraints;         /* LGN_CONSTR_INDEX3, _INDEX2 or _GGL (BDF)   */
  int kinematics;          /* LGN_KINEMATICS_*                           */
  double h, t_end;
  double rtol, atol;       /* Newton tolerances (0: Lignum's defaults)   */
  int analytic_jacobians;  /* 1: K_t, C_t, Z from the model; 0: DQ      */
  int zero_a0;             /* 1: start with a_0 = 0 (reproduction target A) */
  int predictor;           /* LGN_PREDICTOR_* (default LGN_PREDICTOR_ZERO) */
  int newton;              /* LGN_NEWTON_* (default LGN_NEWTON_FULL)   */
  long int msbp;           /* modified Newton: steps between setups (0: default) */
  FILE *csv;               /* time history (NULL: none)                 */
  double *com_history;     /* if not NULL: x at t_k = k h, 3*(nsteps+1)  */
  long int history_len;    /* capacity of com_history in points          */
  int single_solve;        /* 1: one LGNSolve call to t_end (no per-step
                              output: csv, com_history, max_phi unused)  */
  int adaptive;            /* 1: error control (LGN_STEP_ADAPTIVE) with
                              rtol, atol as the error test's tolerances;
                              h is then the output interval and the run
                              stops at t_end exactly (LGNSetStopTime)    */
  long int max_steps;      /* > 0: LGNSetMaxNumSteps (steps per LGNSolve
                              call; 0: Lignum's default)                 */
  int bdf_maxord;          /* > 0: the BDF family of this highest order
                              (LGNSetBDF) instead of method             */
  SUNLinearSolver (*make_ls)(N_Vector y, SUNMatrix A, SUNContext ctx);
                           /* the dense linear solver's constructor
                              (NULL: SUNLinSol_Dense)                    */
} HeavyTopOptions;

/* Result of a run: state at the time reached, in the R^3 x SO(3) variables
 * (x, R, u, Omega and the spherical-joint multiplier for Phi = X - R^T x),
 * whatever the formulation: for HT_SE3, u = R U is the inertial centre-of-mass
 * velocity and vdot[0..2] = udot = R (Udot + Omega x U) (a[0..2] likewise). */
typedef struct {
  int flag;                /* LGN_SUCCESS or the failure flag           */
  double t;                /* time reached                              */
  double x[3], p[4], R[9]; /* centre of mass, rotation (p: w >= 0)      */
  double u[3], Omega[3];   /* velocities                                */
  double vdot[6], a[6];    /* (udot | Omegadot) and algorithmic accel.  */
  double lambda[3];        /* joint multiplier                          */
  long int nsteps, nniters, nres, ndq, njevals, nlsolves, nlsetups;
  long int netfails, nncfails; /* error-test and Newton failures         */
  long int nstall;         /* steps accepted with stalled multipliers      */
  long int history_points; /* points written to com_history             */
  double max_phi;          /* max over the output grid of |X - R^T x|_inf,
                              evaluated on the integrator's raw q        */
  double cpu_seconds;      /* process CPU time (clock()) of the LGNSolve
                              calls (with single_solve: the integration
                              only; otherwise incl. per-step output)    */
} HeavyTopResult;

/* Default options: Lie group, generalized-alpha rho_inf = 0.9, index 3,
 * simplified kinematics, h = 1e-3, t_end = 1, analytic Jacobians. */
void heavy_top_default_options(HeavyTopOptions *opt);

/* Run one configuration; returns the Lignum flag (also in res->flag).
 * Setup failures (e.g. illegal options) are returned the same way. */
int heavy_top_run(const HeavyTopOptions *opt, HeavyTopResult *res);

/* Relative differences max|analytic - DQ| / max(|analytic|, |DQ|) between a
 * formulation's analytic B, K_t, C_t, Z and central differences of its
 * constraint, residual and force callbacks along the group:
 *   B w        = d/de Phi(q o exp(e w)),
 *   K_t w      = d/de [M vdot + g + B^T lambda](q o exp(e w)),
 *   C_t w      = d/de g(q, v + e w),
 *   Z(q)(v, v) = d/de B(q o exp(e v)) v.  */
typedef struct {
  double B, K, C, Z;
} HeavyTopJacobianErrors;

/* The check at a random state from seed: unit quaternion p, x, v, vdot,
 * lambda of unit size (x = R X on the Lie groups, see heavy_top.c).
 * Returns 0, or -1 if an allocation or a callback failed. */
int heavy_top_check_jacobians(HeavyTopFormulation formulation, unsigned int seed,
                              HeavyTopJacobianErrors *err);

/* Human-readable name of a configuration, e.g. "LGGalpha(0.9) idx3". */
void heavy_top_describe(const HeavyTopOptions *opt, char *buf, size_t len);

#endif
