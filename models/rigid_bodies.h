/* -----------------------------------------------------------------------------
 * Lignum study models: a system of rigid bodies joined by joints, under gravity.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Every body is a leaf R^3 x SO(3) (v = (u inertial, Omega body)) or SE(3)
 * (v = (U, Omega) body-fixed) of a product group; M is constant and
 * diagonal (mass, principal moments along the body axes), the forces are
 * gravity and the gyroscopic terms, and the joints come from lignum_joints.h.
 * The model gives every callback of Lignum, analytic (K_t, C_t, Z) or not,
 * for dense and sparse (CSC/CSR) matrices, so the tools on top of it
 * (chain.c, four_bar.c) only describe geometry.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_EXAMPLES_RIGID_BODIES_H
#define LGN_EXAMPLES_RIGID_BODIES_H

#include <stdio.h>

#include <lignum/lignum.h>
#include <lignum/lignum_joints.h>

typedef enum { RB_R3XSO3 = 0, RB_SE3 = 1 } RigidFormulation;
typedef enum {
  RB_DENSE = 0, RB_KLU_CSC = 1, RB_KLU_CSR = 2,
  RB_SPGMR = 3 /* matrix-free SPGMR (krylov_* options below) */
} RigidSolver;

typedef struct {
  int n;                    /* bodies                                       */
  RigidFormulation formulation;
  double *mass;             /* n                                            */
  double *inertia;          /* 3 n principal moments (body axes)            */
  double gravity[3];        /* acceleration of gravity                      */
  LGNGroup body, G;         /* the leaf and the product                     */
  LGNJoints joints;
  N_Vector q0, v0;          /* initial state (filled by the tool)           */
} RigidSystem;

/* A system of n bodies with unit masses and inertias, no joints yet. */
RigidSystem *rigid_create(int n, RigidFormulation formulation, SUNContext ctx);
void rigid_free(RigidSystem **sys);

/* Set body k: solid cylinder of length L, mass m, radius r, axis = body z. */
void rigid_set_cylinder(RigidSystem *sys, int k, double L, double m, double r);
/* Place body k: centre of mass x and rotation matrix R (row-major). */
void rigid_place(RigidSystem *sys, int k, const double x[3], const double R[9]);

/* Total energy: kinetic + gravitational potential (zero at the origin). */
double rigid_energy(const RigidSystem *sys, N_Vector q, N_Vector v);

/* The model's callbacks (user data: the system): M, g, K_t (the joints'
 * geometric stiffness plus gravity's term on SE(3)) and C_t, written by hand
 * here; for the tests that compare the body helpers (lignum_bodies.h) with
 * them. */
typedef struct {
  LGNMassFn mass;
  LGNForceFn force;
  LGNStiffnessFn stiffness;
  LGNDampingFn damping;
} RigidCallbacks;
void rigid_get_callbacks(RigidCallbacks *cb);

/* Run options and results shared by the multibody tools. */
typedef struct {
  RigidSolver solver;
  int method;               /* 0: Newmark, 1: generalized-alpha             */
  double rho_inf, beta, gamma;
  int kinematics;           /* LGN_KINEMATICS_*                             */
  int constraints;          /* LGN_CONSTR_INDEX3 / INDEX2                   */
  int analytic;             /* 1: K_t, C_t, Z from the model; 0: DQ         */
  double h, t_end;
  double rtol, atol;        /* Newton tolerances (0: defaults)              */
  int newton;               /* LGN_NEWTON_* (default full)                  */
  long int msbp;            /* modified Newton: steps between setups (0: default) */
  int predictor;            /* LGN_PREDICTOR_* (default zero)               */
  int klu_ordering;         /* KLU ordering: 0 AMD (default), 1 COLAMD, 2 natural */
  int klu_solve_sundials;   /* 1: solves by SUNLinSolSolve (KLU's own);
                               0 (default): Lignum's on a copy of the
                               factors (LGNSetOwnKLUSolves, opted in; KLU's
                               if the versions are not the copy's)      */
  int plain_residual;       /* 1: M evaluated every iteration and B^T lambda
                               from B (no LGNSetMassConstant,
                               LGNSetConstraintForceFn); 0 (default): both */
  int time_linear_algebra;  /* 1: time one solve and one setup after the run */
  int outputs;              /* energy samples over [0, t_end] (>= 1)        */
  FILE *csv;                /* t, energy, max |Phi| per sample (NULL: none) */
  int reject_stalls;        /* 1: LGNSetAcceptStalls(mem, SUNFALSE)          */
  LGNErrHandlerFn ehfun;    /* error handler (NULL: Lignum's default)        */
  void *eh_data;
  int adaptive;             /* 1: error control (LGN_STEP_ADAPTIVE) with
                               rtol, atol the error test's tolerances (0:
                               1e-6 each); h is then only the first step
                               tried (LGNSetInitStep), the samples are
                               interpolated, t_end is landed on exactly   */
  double hmax;              /* error control: largest step (0: none)       */
  int bdf_maxord;           /* > 0: the BDF family (LGNSetBDF) instead of method */
  long int max_steps;       /* > 0: LGNSetMaxNumSteps (steps per LGNSolve
                               call; 0: Lignum's default)                  */
  int own_dense_lu;         /* 1: LGNLinSol_Dense instead of SUNLinSol_Dense */
  FILE *step_log;           /* error control: "t,h,order" per accepted step
                               (LGN_ONE_STEP; NULL: none)                  */
  int krylov_blocks;        /* RB_SPGMR: block preconditioner with this many
                               equal blocks of bodies (0: none)            */
  int krylov_maxl;          /* RB_SPGMR: Krylov dimension (0: 30)          */
  int krylov_restarts;      /* RB_SPGMR: GMRES restarts (default 2)        */
  double krylov_eplifac;    /* RB_SPGMR: LGNSetEpsLin (0: Lignum's 0.05)  */
} RigidRunOptions;

typedef struct {
  int flag;
  double t;
  double energy0, energy, max_drift; /* E(0), E(t_end), max |E - E(0)|      */
  double max_phi;                    /* max |Phi| over the samples           */
  double phi_end;                    /* |Phi| at the last state reached (the
                                        integrator's own q with error control,
                                        whose samples are interpolated)     */
  long int nsteps, nni, nre, ndq, nje, nlsetups, nanalyses, ncolors;
  long int nreuse, nstall;
  long int netf, nncf;               /* error-test and Newton failures       */
  long int nnz, lenrw, leniw;
  double klu_peak_bytes;             /* KLU's peak memory (0 for dense)     */
  double cpu_seconds;                /* process CPU time in LGNSolve only    */
  double cpu_first_seconds;          /* ... of the first LGNSolve call (to the
                                        first output): set-up, KLU analysis,
                                        initial values and its steps        */
  long int nsteps_first;             /* steps of that first call             */
  long int nni_first;                /* Newton iterations of that first call */
  double solve_seconds;              /* one linear solve with the last matrix */
  double setup_seconds;              /* one factorisation of the last matrix  */
  long int nli, npe, nps, njtimes, nlcf; /* RB_SPGMR: Krylov counters      */
  double *q, *v;                     /* final state (nq, nv), malloc'ed      */
} RigidRunResult;

void rigid_default_run_options(RigidRunOptions *opt);
/* Integrate sys from its initial state; returns the Lignum flag. */
int rigid_run(RigidSystem *sys, const RigidRunOptions *opt, RigidRunResult *res);
void rigid_result_free(RigidRunResult *res);

/* Parse the options common to the tools (--solver, --method, ...);
 * returns 1 if argv[*i] was one of them (consuming its value; the flag
 * --adaptive has none), 0 if not,
 * -1 on a bad value. */
int rigid_parse_option(int argc, char **argv, int *i, RigidRunOptions *opt,
                       RigidFormulation *formulation);
void rigid_print_usage(FILE *out);
/* The step log of an error-controlled run needs LGN_ONE_STEP; the flag of
 * a run that stopped at t_end (LGN_TSTOP_RETURN) is reported as LGN_SUCCESS. */
const char *rigid_solver_name(RigidSolver s);
/* 1 if the solver is built (KLU needs LGN_ENABLE_KLU), 0 if not. */
int rigid_solver_available(RigidSolver s);

#endif
