/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header: the integrator memory record, defaults, internal return
 * codes and message texts, and the functions shared between source files.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_IMPL_H
#define LGN_IMPL_H

#include <limits.h>
#include <stdarg.h>
#include <lignum/lignum.h>
#include <sundials/sundials_math.h>

#include "lgn_err.h"
#include "lgn_matops.h"
#include "lgn_parallel.h"

/* =============================================================================
 * Defaults
 * ===========================================================================*/

#define LGN_RHO_INF_DEFAULT   SUN_RCONST(0.9)
#define LGN_RTOL_DEFAULT      SUN_RCONST(1.0e-8)
#define LGN_ATOL_DEFAULT      SUN_RCONST(1.0e-8)
#define LGN_MAXCOR_DEFAULT    20
#define LGN_MSBP_DEFAULT      10L  /* modified Newton: steps between setups */
#define LGN_MXSTEP_DEFAULT    1000000L
#define LGN_MAX_CONSTRAINTS   ((sunindextype)1 << 31) /* sizes stay far from overflow */
#define LGN_MAX_ROOTS         (INT_MAX / 3) /* 3 nrtfn reals (lgnAllocRoots) */
#define LGN_EPCON_DEFAULT     SUN_RCONST(0.33) /* Newton / error-test tolerance */
#define LGN_MAXNEF_DEFAULT    10  /* error-test failures per step         */
#define LGN_MAXNCF_DEFAULT    10  /* Newton or callback failures per step */

/* =============================================================================
 * Internal return codes of the step (never returned to the user)
 * ===========================================================================*/

#define LGN_RECOVERABLE 100 /* a callback asked for a retry (error control) */

/* The method families (LGNSetNewmark ... / LGNSetBDF). */
#define LGN_FAMILY_NEWMARK 0
#define LGN_FAMILY_BDF     1
#define LGN_BDF_MAXORD     LGN_BDF_MAX_ORDER /* lignum.h */
#define LGN_BDF_MAXHIST    (LGN_BDF_MAXORD + 2) /* points kept: order k + 2 */

/* Which callback produced an error: used to pick the flag and message. */
typedef enum {
  LGN_CB_MASS = 0,
  LGN_CB_FORCE,
  LGN_CB_CONSTR,
  LGN_CB_CONSTR_JAC,
  LGN_CB_STIFFNESS,
  LGN_CB_DAMPING,
  LGN_CB_CURVATURE,
  LGN_CB_CONSTR_FORCE,
  LGN_CB_CONSTR_TIME,
  LGN_CB_GROUP,
  LGN_CB_COUNT
} LGNCallbackId;

/* =============================================================================
 * Message texts
 * ===========================================================================*/

#define MSG_NO_MEM      "lgn_mem = NULL illegal."
#define MSG_NO_MALLOC   "Attempt to call before LGNInit."
#define MSG_NO_GROUP    "No Lie group: call LGNSetGroup before LGNInit."
#define MSG_MEM_FAIL    "A memory request failed."
#define MSG_TIME        "t = %.17g: "

/* =============================================================================
 * The memory record
 * ===========================================================================*/

/* The record's sub-records, one per subsystem, as IDA keeps its linear
 * solver's state in IDALsMem: mem->sub.field. The files that may write a
 * sub-record's fields are listed with it and in doc/architecture.md's
 * owners table, which the test arch_check_owners enforces; every other file
 * reads them. The arrays of the step, the outputs and the BDF history are
 * cut from the work blocks (lgn_workspace.c). */

/* A run across MPI ranks and its ghost bodies (writers: lgn_mem.c, lgn_ghosts.c) */
struct LGNRanksRec {
  LGNParallel par;          /* the communicator of q0 and v0              */
  sunrealtype nv_all;       /* nv and m summed over the ranks: the sizes  */
  sunrealtype m_all;        /* of the weighted RMS norms                  */
  sunbooleantype any_constr_time; /* Phi_t set on some rank (on one process:
                                     on this one); set by LGNSolve         */
  /* ghost bodies (LGNSetHalo, lgn_ghosts.c; NULL: none): the local arrays
   * hold the owned bodies, then the ghosts; nv, nq count both */
  struct LGNHaloRec *halo;
  sunindextype nv_own, nq_own; /* the owned entries (nv, nq without halo) */
  N_Vector hx_b, hx_x;      /* a solve's owned right-hand side, solution:
                               nv_own + m, of the user's type            */
  sunrealtype *hx_ext;      /* nv + m scratch: Krylov products, preconditioner */
  sunrealtype *hx_ext2;     /* nv + m scratch                               */
};

/* The BDF family: settings, history q_{n-j}, v_{n-j} at t_{n-j}, order control (writers: lgn_bdf.c, lgn_mem.c, lgn_setget.c, lgn.c) */
struct LGNBDFRec {
  int maxord;           /* LGNSetBDF: 1 ... 5                          */
  int form;             /* LGNSetBDFForm: LGN_BDF_VARIABLE_COEFF / ..._FIXED_LEADING */
  int ns;               /* FLC: consecutive steps at this h and order (IDA's ns) */
  sunrealtype hused;    /* FLC: the last step's size                   */
  sunrealtype sigck;    /* FLC: sigma_k / ck of the attempt (IDA)      */
  sunbooleantype step_flc; /* the attempt used the fixed leading coefficient */
  int order;            /* the order of the next step                  */
  int last_order;       /* the order of the last step taken            */
  int nhist;            /* valid history points (0: start anew)        */
  int nsteps_order;     /* steps taken at the current order            */
  sunbooleantype phase0;/* start-up: the order rises every step        */
  sunrealtype chart_t;  /* t_n of the chart coordinates in bdf_x       */
  sunrealtype t[LGN_BDF_MAXHIST];
  sunrealtype vgain[LGN_BDF_MAXHIST]; /* v_{n-j}'s gain on position noise */
  sunrealtype vgain1;   /* ... of the attempt's v_{n+1}: sum_j |d_j|      */
  sunrealtype vpgain;   /* ... of its predictor: sum_j |p_j| vgain_j      */
  sunrealtype *q;       /* LGN_BDF_MAXHIST x nq: q_{n-j}               */
  sunrealtype *v;       /* LGN_BDF_MAXHIST x nv: v_{n-j}               */
  sunrealtype *l;       /* LGN_BDF_MAXHIST x m: lambda_{n-j}           */
  sunrealtype *x;       /* LGN_BDF_MAXHIST x nv: log(q_n^{-1} q_{n-j}) */
  sunrealtype *rx, *rv; /* the known parts of xdot, vdot (nv each) */
  sunrealtype *xpred, *vpred; /* the predictor (nv each)           */
  sunrealtype *dd;      /* divided differences, (LGN_BDF_MAXHIST + 1) nv */
  sunrealtype *ele_keep; /* nv: the step's estimate (ele) while the order estimates use ele */
  sunrealtype c0;       /* leading coefficient of the BDF derivative   */
  long int nord[LGN_BDF_MAXORD + 1]; /* steps taken at each order      */
};

/* The diagonal blocks of T: the leaves of the group (writers: lgn_mem.c) */
struct LGNBlocksRec {
  int n;
  sunindextype *voff;   /* nblk + 1 offsets in v                       */
  sunindextype *qoff;   /* nblk + 1 offsets in q                       */
  sunindextype *toff;   /* nblk + 1 offsets in the packed T storage    */
  sunindextype *of;     /* block of each velocity component            */
  LGNGroup *group;      /* the leaf group of each block                */
  sunindextype max;     /* largest block                               */
  sunindextype tlen;        /* packed length (identity blocks store none)  */
};

/* Difference-quotient scratch vectors (writers: lgn_mem.c) */
struct LGNDQRec {
  N_Vector q, v, g, r, z;
};

/* The linear solver (writers: lgn_ls.c, lgn_krylov.c, lgn_mem.c, lgn.c, lgn_newmark_adapt.c, lgn_bdf.c) */
struct LGNLinSolRec {
  SUNLinearSolver LS;
  SUNMatrix A;
  sunbooleantype sparse;    /* A is a SUNSparseMatrix (KLU)                 */
  int sparsetype;           /* CSC_MAT or CSR_MAT when sparse               */
  struct LGNSparseWorkRec *sp; /* sparse path work (lgn_sparse.h)           */
  sunbooleantype initialized;
  sunbooleantype restart; /* the next setup starts clean (lgn_ls.c): the
                                last one failed, or A's pattern was dropped */
  sunbooleantype setup_recoverable; /* a singular setup is retried with a
                                       smaller step: no message          */
  long int last_flag;       /* the last linear solver flag (lgn_diag.c)  */
};

/* Krylov solvers and preconditioners (writers: lgn_krylov.c, lgn_ls.c, lgn_matrix.c, lgn_mem.c, lgn.c) */
struct LGNKrylovRec {
  sunbooleantype on;    /* LS is a matrix-free iterative solver: A is
                               Lignum's own CSC matrix (own_A)             */
  sunbooleantype own_A;     /* A created by Lignum (lgnAllocKrylov)        */
  int pretype;          /* LS's preconditioning side (PREC_*; -1: unknown) */
  LGNPrecSetupFn psetup;    /* LGNSetPreconditioner (NULL: none)           */
  LGNPrecSolveFn psolve;
  int bp_nblocks;           /* LGNSetBlockPreconditioner (0: off)          */
  long int *bp_bodies;      /* its partition of the bodies (NULL: equal)   */
  struct LGNBlockPrecRec *bp; /* the block preconditioner (lgn_blockprec.c) */
  N_Vector w;           /* the solve's weights (nv + m)                */
  N_Vector tmp;         /* scratch (nv + m)                            */
  sunrealtype eplifac;      /* LGNSetEpsLin: linear / Newton tolerance     */
  sunbooleantype newton;/* the next solve is Newton's: kry_w holds its
                               correction weights (lgnKrylovNewtonWeights) */
  sunrealtype asm_t;        /* the time and scalings of the last assembly  */
  sunrealtype asm_cM, asm_cC, asm_cK; /* (handed to LGNPrecSetupFn)        */
  long int nli;             /* Krylov iterations                           */
  long int npe;             /* preconditioner setups                       */
  long int nps;             /* preconditioner solves                       */
  long int njtimes;         /* products with the iteration matrix          */
  long int nlcf;            /* linear solves that missed their tolerance   */
  int pfail;            /* across ranks: a preconditioner solve's failure
                               in the current Krylov solve (0: none)      */
};

/* Lignum's solves with a copy of KLU's factors (writers: lgn_ls.c, lgn_mem.c, lgn_restart.c, lgn.c) */
struct LGNKluRec {
  sunbooleantype own_solves; /* LGNSetOwnKLUSolves (default SUNFALSE)  */
  sunbooleantype valid;      /* klu holds the factors now in LS         */
  long int ls_nsolve;           /* solves with LS's factors since its setup */
  struct LGNKluCopyRec *copy;     /* the copy (NULL: none)                   */
  long int pattern;          /* A's pattern number when KLU last factored */
  /* its counters (lgn_ls.c, LGNGetNumKLU*, LGNGetNumOwnKLU*; restarted at
   * the first setup after LGNInit / LGNReInit) */
  long int nfallback;        /* own refactorisations handed back to KLU:
                                    a pivot below the rcond threshold      */
  long int ncopy;            /* whole copies of KLU's factors           */
  long int nvalues;          /* copies of their values only             */
  long int nrefactor;        /* Lignum's refactorisations, KLU's stead  */
  long int nsolve;           /* solves with the copy                    */
  long int nnewpattern;      /* KLU factored: a new pattern of A        */
  long int nnocopy;          /* no copy possible (sizes, memory, A)     */
};

/* Redundant constraints (writers: lgn_redundancy.c, lgn_mem.c, lgn_setget.c, lgn.c) */
struct LGNRedundancyRec {
  sunindextype m_user;      /* the user's constraint rows (LGNSetConstraints);
                               m counts those the integrator keeps         */
  int mode;             /* LGN_REDUNDANT_ELIMINATE or _REFUSE          */
  sunindextype nout;    /* rows left out (0: m = m_user, no mapping)   */
  sunindextype *rows;   /* 2 m_user: the kept rows (m of them, ascending),
                               then those left out; then scratch           */
  sunindextype *keep;   /* m_user: the kept index of a user row, or -1 */
  N_Vector full;        /* m_user: a callback's output, the user's rows */
  N_Vector lam;         /* m_user: lambda expanded (0 on rows left out) */
  SUNMatrix B;          /* m_user x nv: the user's B, of A's kind      */
  sunrealtype viol;     /* the last check: max |Phi| of the rows left out */
  long int nsel;        /* selections made (a change of the kept rows) */
  SUNMatrix A;          /* a direct solver for the kept rows, of the   */
  SUNLinearSolver LS;   /* user's kind (NULL: the user's fits)        */
  SUNMatrix Auser;      /* the user's, sized for m_user, while red_A   */
  SUNLinearSolver LSuser; /* and red_LS stand in for them              */
};

/* The diagnosis of the last singular matrix (writers: lgn_diag.c, lgn_krylov.c, lgn_mem.c) */
struct LGNDiagRec {
  sunindextype *red;   /* redundant constraints (m; work space)       */
  sunindextype nred;   /* their number (0: none found)                */
  sunindextype pivot;  /* the zero-pivot unknown (-1: none)           */
  char text[400];       /* the diagnosis of the last singular matrix  */
};

/* The Newton iteration: tolerances, the reused factorisation (writers: lgn_newton.c, lgn_krylov.c, lgn_mem.c, lgn_restart.c, lgn.c) */
struct LGNNewtonRec {
  sunbooleantype lu_valid;  /* A holds a factorised iteration matrix of a step */
  sunrealtype lu_h;         /* the step size it was built with             */
  long int lu_nst;          /* nst when it was built                       */
  sunrealtype rate;  /* last contraction rate seen with a reused A  */
  sunrealtype lambda_noise; /* multiplier part of the last stalled correction */
  sunrealtype lambda_noise_h; /* ... and its step size (0: none seen)      */
  sunrealtype rtol;     /* Newton's tolerances in this step            */
  sunrealtype atol;
  const sunrealtype *atolv; /* ... per component (NULL: nls_atol)     */
  sunrealtype vfac;     /* ... nls_atolv's factor (fixed steps: 1)     */
  sunrealtype lrtol;    /* ... of the multipliers' part               */
  sunrealtype latol;
};

/* Error control and step-size selection (writers: lgn_newmark_adapt.c, lgn_newmark_errtest.c, lgn_bdf.c, lgn_newmark_step.c, lgn_output.c, lgn_mem.c, lgn_setget.c, lgn.c) */
struct LGNErrConRec {
  int step_control;         /* LGN_STEP_FIXED or LGN_STEP_ADAPTIVE         */
  sunbooleantype tols_set;  /* LGNSStolerances or LGNSVtolerances called  */
  sunrealtype *atol_vec;    /* per-component atol, nv (NULL: the scalar)   */
  sunrealtype epcon;        /* Newton tolerance / error-test tolerance     */
  sunrealtype h0_user;      /* LGNSetInitStep (0: estimated)               */
  sunrealtype hmin, hmax;   /* step size limits (hmax 0: none)             */
  int maxnef, maxncf;       /* failures per step                           */
  sunrealtype hnext;        /* the step size to try next (0: none yet)     */
  sunrealtype h0_actual;    /* the first step size tried                   */
  sunrealtype err_norm;     /* |e| of the last step attempted              */
  sunrealtype err_prev;     /* |e| of the last step accepted               */
  sunrealtype *ele;         /* its local error estimate (nv)               */
  sunrealtype *ewt;         /* ... and error weights (nv)                  */
  sunrealtype *a_scaled;    /* a_n rescaled to the step size (nv)          */
  const sunrealtype *a_step;/* a_n as the step uses it: a or a_scaled      */
  long int netf;            /* error-test failures                         */
  sunbooleantype lambda_errcon; /* LGNSetMultiplierErrorControl (default off) */
  sunrealtype lambda_atol;  /* ... its absolute tolerance of the multipliers */
  sunrealtype lambda_err;   /* |e_lambda| of the last attempt (0: off)     */
};

/* The last step, for dense output (writers: lgn_newmark_step.c, lgn_bdf.c, lgn_kinematics.c, lgn_mem.c) */
struct LGNDenseRec {
  sunrealtype tprev;        /* its start t_n; it ends at tn                */
  sunbooleantype valid;     /* q1, v1, vdot1 hold its start, and incr
                               its chart coordinate                       */
  sunrealtype *incr;        /* sigma variant: log(q_n^-1 q1), tracked (nv) */
  sunrealtype *zero_nv;     /* zeros (nv), the algebra's origin            */
  sunrealtype *work;  /* the dense output's scratch (4 nv)           */
};

/* What LGNSolve and LGNGetDky return (writers: lgn_output.c, lgn_mem.c, lgn.c) */
struct LGNOutputRec {
  sunrealtype *keep;    /* the last output's vdot and lambda kept while
                               a setter dropped the work space (or NULL) */
  sunindextype keep_nv, keep_m;
  sunbooleantype consistent; /* LGNSetConsistentOutputs (default on)  */
  int project;          /* LGNSetProjectOutputs: LGN_PROJECT_*        */
  sunbooleantype valid; /* out_vdot, out_lambda hold the last output's */
  sunrealtype t;        /* ... time                                    */
  sunrealtype *vdot;    /* consistent vdot at the last output (nv)     */
  sunrealtype *lambda;  /* ... and lambda (m; NULL when m = 0)         */
  sunrealtype *save;    /* q1, v1, vdot1, lambda1 kept while an output
                               is computed (nq + 3 nv + m)                 */
  N_Vector q, v;    /* LGNGetDky's q and v (clones; NULL until used) */
  N_Vector lq, lv;  /* the last projected output's q, v (clones)   */
  sunrealtype lt;       /* ... its time                                */
  sunbooleantype lvalid; /* ... kept (a failed LGNSolve at that time
                               returns them: lgn.c)                      */
  sunrealtype *lwork;   /* the iterate's consistent lambda (m)         */
  long int n;            /* outputs made consistent or projected        */
};

/* Root finding (writers: lgn_root.c, lgn_mem.c, lgn.c) */
struct LGNRootRec {
  int nrtfn;                /* number of root functions (0: off)           */
  LGNRootFn gfun;           /* g(t, q, v, gout, user_data)                 */
  sunrealtype *glo;         /* g at tlo, the last point checked (nrtfn)    */
  sunrealtype *ghi;         /* g at the right end of the bracket (nrtfn)   */
  sunrealtype *grout;       /* g at the root returned / the trial point    */
  int *iroots;              /* +1 / -1: a root found, its direction (nrtfn)*/
  int *rootdir;             /* LGNSetRootDirection: +1, -1, 0 (nrtfn)      */
  sunbooleantype *gactive;  /* g_i not exactly zero at tlo (nrtfn)         */
  N_Vector q, v;      /* q, v handed to g (clones of the state)      */
  sunrealtype tlo;          /* roots are sought in (tlo, ...]              */
  sunbooleantype started;/* glo holds g at tlo (dropped by STATE)       */
  sunbooleantype pending;   /* a root returned before tn (LGN_ONE_STEP:
                               tn itself is returned next, as IDA does)   */
  sunbooleantype first;  /* the first check since the start is ahead   */
  sunbooleantype nowarn; /* LGNSetNoInactiveRootWarn                    */
  long int nge;             /* root function evaluations                   */
};

typedef struct LGNMemRec {
  SUNContext sunctx;

  /* ---- a run across MPI ranks (lgn_parallel.h; NULL: one process) ---- */
  struct LGNRanksRec ranks; /* a run across MPI ranks and its ghost bodies */

  /* ---- model ---- */
  LGNGroup G;               /* configuration space (not owned)            */
  sunindextype nq;          /* reals per group element                    */
  sunindextype nv;          /* Lie algebra dimension                      */
  sunindextype m;           /* number of constraints                      */
  sunindextype nalg;        /* the algebraic unknowns of the Newton system
                               after the nv velocities: m, or 2 m under
                               LGN_CONSTR_GGL (lambda and mu; set with the
                               work space, lgnAllocWork)                  */
  void *user_data;
  LGNMassFn mass;
  LGNForceFn force;
  LGNConstrFn constr;
  LGNConstrJacFn constr_jac;
  LGNStiffnessFn stiffness; /* NULL: difference quotients                 */
  LGNDampingFn damping;     /* NULL: difference quotients                 */
  LGNCurvatureFn curvature; /* NULL: difference quotients                 */
  LGNConstrTimeFn constr_time; /* Phi_t; NULL: Phi(q) scleronomic          */
  LGNConstrForceFn constr_force; /* NULL: B^T lambda from B                */
  sunbooleantype mass_constant;  /* LGNSetMassConstant                     */
  sunbooleantype mass_current;   /* Mmat holds the constant M              */
  sunbooleantype mass_diagonal;  /* ... and it is diagonal, in mass_diag    */

  /* ---- method ---- */
  sunrealtype alpha_m, alpha_f, beta, gamma; /* Chung-Hulbert convention  */
  int constr_index;         /* LGN_CONSTR_INDEX3, _INDEX2 or LGN_CONSTR_GGL */
  sunrealtype *ggl_mu;      /* GGL: the kinematic multiplier mu of the
                               iterate (m; NULL otherwise)                */
  sunrealtype ggl_t1;       /* GGL: the time of the Newton iterate         */
  sunrealtype *ggl_Bn;      /* GGL, Newmark family: B(q_n, t_n), m x nv
                               column-major (NULL otherwise)              */
  sunbooleantype ggl_Bn_valid; /* ggl_Bn holds B at the current t_n, q_n  */
  int kinematics;           /* LGN_KINEMATICS_*                            */
  const struct LGNKinematicsOps *kin; /* its operations (lgn_kinematics.c) */
  sunrealtype h;            /* fixed step size (0 = not set)               */
  int family;               /* LGN_FAMILY_NEWMARK or LGN_FAMILY_BDF        */
  const struct LGNFamilyOps *fam; /* its operations (lgn_family.c)         */

  /* ---- BDF (lgn_bdf.c): the history q_{n-j}, v_{n-j} at t_{n-j} ---- */
  struct LGNBDFRec bdf; /* the BDF family: settings, history, order control */
  sunrealtype rtol, atol;   /* Newton stop test                            */
  int maxcor;               /* max Newton iterations per step              */
  int newton_mode;          /* LGN_NEWTON_FULL or LGN_NEWTON_MODIFIED      */
  long int msbp;            /* modified Newton: max steps between setups   */
  long int mxstep;          /* max steps per LGNSolve (< 0: no limit)       */

  /* ---- state at t_n ---- */
  sunrealtype tn;
  N_Vector q, v, vdot, a;   /* configuration, velocity, acceleration, aux  */
  N_Vector lambda;          /* multipliers (NULL when m = 0)               */
  sunbooleantype lambda_valid; /* lambda holds multipliers computed (or
                                  given) at t_n, not the work space's zeros */
  sunrealtype *lambda_keep; /* the last valid multipliers while the work
                               space is dropped (a setter changed sizes):
                               restored when it is made again with this m */
  sunindextype lambda_keep_len;
  sunbooleantype ic_done;   /* vdot, lambda, a consistent at t_n           */
  sunbooleantype user_vdot0;/* vdot0/lambda0 given by the user             */
  sunbooleantype user_a0;   /* a0 given by the user                        */
  sunbooleantype pstart_on; /* LGNSetPerturbedStart (default off)        */
  sunbooleantype pstart_done; /* applied (or not due) since the IC         */
  sunbooleantype pstart_pending; /* applied in an attempt not yet completed */

  /* ---- step work space (iterates at t_{n+1}) ---- */
  N_Vector q1, v1, vdot1;   /* configuration, velocity, acceleration       */
  N_Vector lambda1;         /* multipliers (NULL when m = 0)               */
  sunrealtype *sigma;       /* local coordinate: q1 = q_n o exp(sigma)     */
  sunrealtype *sigma_dot;   /* its first derivative                        */
  sunrealtype *sigma_ddot;  /* its second derivative                       */
  sunrealtype *a_pred;      /* a+ = (alpha_f vdot_n - alpha_m a_n)/(1-am)  */
  sunrealtype *Tm;          /* T(sigma), block diagonal (lgn_tangent.c)    */
  sunrealtype *Tv;          /* exact kinematics: (dv/dsigma)/gamma'        */
  sunrealtype *Ta;          /* exact kinematics: (dvdot/dsigma)/beta'      */
  sunrealtype *blk_work;    /* 3 blk_max scratch for the block routines    */
  sunrealtype *Bvq;         /* dense index 2: D_q(B(q) v).(q w~), m x nv    */
  sunrealtype *work_nv;     /* scratch of length nv                        */
  sunrealtype *work2_nv;    /* second scratch of length nv                 */
  sunrealtype *work_m;      /* scratch of length m                         */
  sunrealtype *vdot_prev;   /* vdot_{n-1}, for the extrapolating predictor */
  sunrealtype *mass_diag;   /* diagonal of a constant diagonal M (nv)      */
  sunrealtype *lambda_prev; /* lambda_{n-1} (NULL when m = 0)              */
  sunrealtype h_prev;       /* step size that produced vdot_n (0: none)    */
  int predictor;            /* LGN_PREDICTOR_*                             */
  N_Vector g;               /* forces g(q1, v1, t)                         */
  N_Vector rdyn;            /* unscaled dynamic residual M vdot + g + B^T l*/
  N_Vector phi;             /* Phi(q1) or B v (NULL when m = 0)            */
  N_Vector phit;            /* Phi_t(q, t) (NULL when m = 0)               */
  N_Vector rhs;             /* Newton right-hand side, length nv + nalg    */
  N_Vector sol;             /* Newton correction, length nv + nalg         */

  /* ---- difference quotient scratch ---- */
  struct LGNDQRec dq; /* difference-quotient scratch vectors */

  /* ---- diagonal blocks of T: the leaves of the group (lgn_tangent.c) ---- */
  struct LGNBlocksRec blk; /* the diagonal blocks of T: the leaves of the group */

  /* ---- matrices of the model (Lignum-owned, of the type of A) ---- */
  SUNMatrix Mmat;           /* nv x nv                                      */
  SUNMatrix Bmat;           /* m x nv (NULL when m = 0)                     */
  SUNMatrix Kmat;           /* nv x nv tangent stiffness                    */
  SUNMatrix Cmat;           /* nv x nv tangent damping                      */
  SUNMatrix Mdq;            /* nv x nv scratch for difference quotients     */
  SUNMatrix Bdq;            /* m x nv scratch for difference quotients      */

  /* ---- linear solver (not owned) ---- */
  struct LGNLinSolRec ls; /* the linear solver (LS and A not owned) */

  /* ---- Krylov solvers (lgn_krylov.c; allocated by lgn_mem.c) ---- */
  struct LGNKrylovRec kry; /* Krylov solvers and preconditioners */

  /* ---- redundant constraints (lgn_redundancy.c) ---- */
  struct LGNRedundancyRec red; /* redundant constraints */

  /* ---- the diagnosis of the last singular matrix (lgn_diag.c) ---- */
  struct LGNDiagRec diag; /* the diagnosis of the last singular matrix */

  /* ---- Lignum's solves with a copy of KLU's factors (lgn_klu_solve.c) ---- */
  struct LGNKluRec klu; /* Lignum's solves with a copy of KLU's factors */

  /* ---- the factorised iteration matrix, for modified Newton (lgn_newmark_step.c) ---- */
  struct LGNNewtonRec nls; /* the Newton iteration: tolerances, the reused factorisation */

  /* ---- bookkeeping ---- */
  sunbooleantype malloc_done; /* LGNInit called                             */
  sunbooleantype work_done;   /* work space allocated for current nv, m     */
  sunbooleantype mat_done;    /* model matrices allocated for the type of A */
  sunrealtype hlast;

  /* ---- error control (LGN_STEP_ADAPTIVE; lgn_newmark_adapt.c, lgn_newmark_errtest.c) ---- */
  struct LGNErrConRec ec; /* error control and step-size selection (LGN_STEP_ADAPTIVE) */
  sunrealtype tstop;        /* LGNSetStopTime                              */
  sunbooleantype tstop_set;

  /* ---- the last step, for dense output (lgn_dense_output.c) ---- */
  struct LGNDenseRec dense; /* the last step, for dense output */

  /* ---- what LGNSolve returns (lgn_output.c) ---- */
  struct LGNOutputRec out; /* what LGNSolve and LGNGetDky return */

  /* ---- root finding (lgn_root.c; arrays allocated by lgn_mem.c) ---- */
  struct LGNRootRec rt; /* root finding (events) */

  /* ---- counters ---- */
  long int nst;      /* steps                                              */
  long int nni;      /* Newton iterations                                  */
  long int nncf;     /* Newton convergence failures                        */
  long int nstall;   /* steps accepted with multipliers at roundoff level  */
  sunbooleantype accept_stalls; /* LGNSetAcceptStalls (default SUNTRUE)  */
  sunbooleantype stall_warned;  /* the warning of LGNSolve given         */
  long int nfails;   /* failed step attempts                               */
  long int nre;      /* residual evaluations in Newton                     */
  long int ndq;      /* residual-type evaluations in difference quotients  */
  long int nje;      /* iteration matrix evaluations                       */
  long int nlsetup;  /* linear solver setups                               */
  long int nlsolve;  /* linear solves                                      */
  long int nreuse;   /* Newton iterations solved with a reused matrix      */
  long int nrestart; /* steps whose Newton iteration restarted with a fresh
                        matrix after failing with a reused one             */

  /* ---- error reporting ---- */
  LGNErrSink err;            /* where messages go (lgn_err.h)              */
  const char *api_func;      /* the public function running (its name in
                                messages; set by lgnAccessMem)             */
} *LGNMem;

/* =============================================================================
 * Shared internal functions, by file from the bottom layer up
 * (doc/architecture.md; calls go downward only, checked by the test
 * check_layers). The pure helpers below this record have headers of their
 * own: lgn_err.h, lgn_matops.h, lgn_sparse.h, lgn_klu_solve.h,
 * groups/lgn_group_impl.h.
 * ===========================================================================*/

/* ---- lgn_mem.c: the record's owner -------------------------------------- */

/* What a setter changed, for lgnInvalidate (bits, or-ed). */
#define LGN_CHANGE_GROUP   0x001u /* the Lie group (its blocks, maybe sizes)  */
#define LGN_CHANGE_SIZES   0x002u /* the number of constraints m              */
#define LGN_CHANGE_LINSOL  0x004u /* the linear solver or its matrix A        */
#define LGN_CHANGE_PATTERN 0x008u /* the sparsity of the model's matrices     */
#define LGN_CHANGE_MASS    0x010u /* the mass function or its constancy       */
#define LGN_CHANGE_MODEL   0x020u /* another model callback                   */
#define LGN_CHANGE_METHOD  0x040u /* coefficients, variant, index, Newton     */
#define LGN_CHANGE_STATE   0x080u /* the state at t_n (LGNInit, LGNReInit...) */
#define LGN_CHANGE_MATRIX  0x100u /* A overwritten (internal: not a setting)  */

void lgnInvalidate(LGNMem mem, unsigned int what);
int lgnAccessMem(void *lgn_mem, const char *func, LGNMem *mem);
int lgnCheckVector(LGNMem mem, N_Vector x, sunindextype len, const char *name,
                   const char *func);
void lgnProcessError(LGNMem mem, int error_code, int line, const char *func,
                     const char *file, const char *msgfmt, ...);
int lgnCallbackFlag(LGNMem mem, LGNCallbackId cb, int retval,
                    const char *func);
int lgnCallbackVector(LGNMem mem, LGNCallbackId cb, int retval, N_Vector x,
                      const char *func);
int lgnCallbackMatrix(LGNMem mem, LGNCallbackId cb, int retval, SUNMatrix A,
                      const char *func);
int lgnAgreeRanks(LGNMem mem, int flag);
int lgnAllocState(LGNMem mem, N_Vector q0, N_Vector v0);
void lgnFreeState(LGNMem mem);
void lgnSetAlgebraicSize(LGNMem mem);
int lgnAllocWork(LGNMem mem);
int lgnEnsureWork(LGNMem mem);
int lgnAllocBDF(LGNMem mem);
void lgnFreeWork(LGNMem mem);
int lgnAllocMatrices(LGNMem mem);
void lgnFreeMatrices(LGNMem mem);
void lgnFreeAll(LGNMem mem);
int lgnAllocRedundancy(LGNMem mem);
void lgnFreeRedundancy(LGNMem mem);
int lgnAllocRedundancySolver(LGNMem mem, sunindextype n);
void lgnFreeRedundancySolver(LGNMem mem);
int lgnSparseWorkCreate(LGNMem mem);
void lgnSparseWorkFree(LGNMem mem);
void lgnSparseWorkSpace(const LGNMem mem, long int *rw, long int *iw);
long int lgnIterationMatrixNnz(LGNMem mem);
void lgnWorkSpace(LGNMem mem, long int *lenrw, long int *leniw);

int lgnAllocKrylov(LGNMem mem);
void lgnFreeKrylov(LGNMem mem, sunbooleantype settings);
int lgnAllocRoots(LGNMem mem, int nrtfn);
int lgnAllocRootVectors(LGNMem mem);
void lgnFreeRoots(LGNMem mem);

/* ---- lgn_workspace.c: the work blocks, one table of slices each -------- */

/* The blocks: the step's arrays (sigma ... ggl_Bn), T's packed blocks, the
 * outputs, the BDF history. Each is one allocation; the table that points
 * its slices also counts it (lgnWorkSpace), so the two cannot drift. */
#define LGN_WORK_STEP    0
#define LGN_WORK_TANGENT 1
#define LGN_WORK_OUTPUT  2
#define LGN_WORK_BDF     3
#define LGN_WORK_NBLOCKS 4

int lgnWorkBlockAlloc(LGNMem mem, int block);      /* LGN_MEM_FAIL, no message */
void lgnWorkBlockFree(LGNMem mem, int block);      /* and its slices NULL      */
size_t lgnWorkBlockLength(const struct LGNMemRec *mem, int block); /* reals */
sunbooleantype lgnWorkBlockAllocated(const struct LGNMemRec *mem, int block);

/* Report an error from inside a function: fills in line, function and file. */
#define LGN_ERROR(mem, code, ...) \
  lgnProcessError((mem), (code), __LINE__, __func__, __FILE__, __VA_ARGS__)

/* ---- lgn_ghosts.c: ghost bodies of a run across ranks (LGNSetHalo) ----- */

/* The solve's unknowns of the owned bodies and the multipliers (nv_own + m)
 * from a right-hand side of nv + m local rows: the ghosts' rows added to
 * their owners' (fold), or the owned entries only (restrict). */
void lgnGhostsFold(LGNMem mem, const sunrealtype *ext, sunrealtype *owned);
void lgnGhostsRestrict(LGNMem mem, const sunrealtype *ext, sunrealtype *owned);
/* ... and back: the ghosts' entries from their owners (collective). */
void lgnGhostsExpand(LGNMem mem, const sunrealtype *owned, sunrealtype *ext);
/* The ghosts' entries of the state (q, v, vdot, a) from their owners. */
void lgnGhostsRefreshState(LGNMem mem);
/* The owned bodies (leaves of the group): all of them without a halo,
 * else those before the ghosts (the work space must exist: nv_own). */
int lgnGhostsOwnedBodies(const LGNMem mem);
/* LGN_ILL_INPUT (reported) when the halo was made for another group than
 * the integrator's (LGNSetGroup after LGNSetHalo). */
int lgnGhostsCheck(LGNMem mem);
/* LGN_ILL_INPUT (reported) when the mass matrix M has an entry in a
 * ghost's rows or columns: a ghost's mass is its owner's (the sum over the
 * ranks would count it twice). */
int lgnGhostsCheckMass(LGNMem mem, SUNMatrix M);
/* The entries of q (nq) and v (nv) of the rank's own bodies: all of them
 * without a halo. */
void lgnGhostsOwnedLengths(const LGNMem mem, sunindextype *nq, sunindextype *nv);
/* The ghosts' entries of q <- identity, of v <- 0 (placeholders until the
 * owners' values arrive; either may be NULL). */
void lgnGhostsClear(const LGNMem mem, sunrealtype *q, sunrealtype *v);

/* ---- lgn_model.c: M, g, B and the residuals ----------------------------- */

sunbooleantype lgnNeedsConstraintJacobian(LGNMem mem, sunbooleantype for_matrix);
int lgnEvalModelAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v,
                   SUNMatrix M, N_Vector g, SUNMatrix B, sunbooleantype with_B);
int lgnEvalModel(LGNMem mem, sunrealtype t, sunbooleantype with_B);
int lgnEvalConstraintJacobian(LGNMem mem, sunrealtype t, N_Vector q, SUNMatrix B);
int lgnConstraintVelocity(LGNMem mem, sunrealtype t, N_Vector q, SUNMatrix B,
                          const sunrealtype *v, sunrealtype *out);
int lgnDynamicResidual(LGNMem mem, sunrealtype t, N_Vector q, SUNMatrix M,
                       N_Vector g, SUNMatrix B, N_Vector r);
int lgnNewtonResidual(LGNMem mem, sunrealtype t, sunrealtype scale,
                      sunrealtype cv, sunbooleantype for_matrix);

/* ---- lgn_tangent.c: T(sigma) and the exact kinematics' derivatives ------ */

int lgnTangentMatrices(LGNMem mem);
int lgnExactKinematicsMap(LGNMem mem, sunbooleantype with_tangent);
int lgnExactKinematicsDerivatives(LGNMem mem, sunrealtype gamma_p,
                                  sunrealtype beta_p);
void lgnDenseTimesTangent(LGNMem mem, const sunrealtype *X, sunindextype ldx,
                          sunindextype nrow, const sunrealtype *T,
                          sunrealtype *Y, sunindextype ldy);

/* ---- lgn_dq.c: K_t, C_t, D_q(B v), curvature: callbacks or quotients ---- */

int lgnEvalTangents(LGNMem mem, sunrealtype t, sunrealtype cC, sunrealtype cK);
int lgnCurvatureDQ(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v,
                   N_Vector z);
int lgnConstraintVelocityDQ(LGNMem mem, sunrealtype t);
int lgnBuildDQPatterns(LGNMem mem);
int lgnConstraintVelocityDQColored(LGNMem mem, sunrealtype t);

/* ---- lgn_kinematics.c: the kinematics variants -------------------------- */

/* Per-step constants (lgn_newmark_step.c sets them). */
typedef struct {
  sunrealtype h, t1;
  sunrealtype beta_p;  /* beta'  = (1-am)/(h^2 beta (1-af)): d sigma_ddot / d sigma */
  sunrealtype gamma_p; /* gamma' = gamma/(h beta):           d sigma_dot  / d sigma */
  sunrealtype scale;   /* beta h^2: scaling of the dynamic rows              */
  sunrealtype qscale;  /* max(1, |q_n|_max): size of the configuration       */
  sunrealtype hmat;    /* the step the iteration matrix depends on: h (Newmark),
                        * 1/c0 (BDF), compared for its reuse                */
  sunrealtype beta_n;  /* Newton's beta: scale = beta_n h^2 (the multipliers'
                        * roundoff floor): beta (Newmark), 1/(c0 h)^2 (BDF) */
} LGNStepCoeffs;

/* The scaled iteration matrix as a sum of terms (lgn_matrix.c):
 *   [[ cM M TM + cC C TC + cK K TK ,  B^T ],  [ B TB + cBv D_q(B v) TK , 0 ]]
 * with TM ... TB block diagonal in packed storage, NULL standing for I. */
typedef struct {
  sunrealtype cM, cC, cK, cBv;
  const sunrealtype *TM, *TC, *TK, *TB;
  sunbooleantype ggl; /* the GGL step matrix (lgn_matrix.c): rows Phi and
                         (B v + Phi_t) / gamma', columns lambda and nu */
  /* GGL only: TP the T-like factor of the Phi rows; the column of nu is
   * gsign (cM M UA + cC C UV) GB^T in the dynamic rows and gsign B UV GB^T
   * in the velocity rows, GB = B(q1) (NULL; BDF) or B(q_n) (Newmark) */
  const sunrealtype *TP, *UA, *UV, *GB;
  sunrealtype gsign;
} LGNMatrixTerms;

/* A kinematics variant: how the Newmark increments (sigma, sigma_dot,
 * sigma_ddot) of the step map to the iterate (q1, v1, vdot1), and what that
 * means for the predictor, the corrections and the iteration matrix. Adding
 * a variant is adding one of these tables. */
typedef struct LGNKinematicsOps {
  const char *name;
  sunbooleantype needs_tangent_dot;     /* group ops beyond compose_exp,    */
  sunbooleantype needs_tangent_inverse; /* tangent_apply and tangent_matrix */
  sunbooleantype extrapolates; /* LGN_PREDICTOR_EXTRAPOLATE applies        */
  /* where sigma_dot and sigma_ddot live (at the start of every attempt) */
  void (*bind)(LGNMem mem);
  /* after the Newmark predictor: map the guess acc of vdot_{n+1} into the
   * chart (extrapolate), or scale the increment (sigma variant) */
  int (*predict)(LGNMem mem, const LGNStepCoeffs *c, sunrealtype *acc,
                 sunbooleantype extrapolate);
  /* (q1, v1, vdot1) from the increments; with_tangent: also T(sigma) */
  int (*iterate)(LGNMem mem, sunbooleantype with_tangent);
  /* the terms of the iteration matrix at the current iterate */
  int (*matrix)(LGNMem mem, const LGNStepCoeffs *c, LGNMatrixTerms *terms);
  /* after sigma += delta: anything else the variant carries (NULL: none) */
  int (*correct)(LGNMem mem, const sunrealtype *delta);
  /* the chart coordinate of the iterate, log(q_n^{-1} q1) */
  const sunrealtype *(*increment)(LGNMem mem);
} LGNKinematicsOps;

const LGNKinematicsOps *lgnKinematicsOps(int kinematics);
const LGNKinematicsOps *lgnBDFOps(void);
void lgnFormIncrement(LGNMem mem, const LGNStepCoeffs *c);
void lgnSaddlePointTerms(LGNMatrixTerms *terms);

/* ---- lgn_family_settings.c: settings of one method family only ---- */
int lgnRefuseOtherFamily(LGNMem mem, int family, sunbooleantype is_default, const char *func);
int lgnCheckFamilySettings(LGNMem mem, const char *func);

/* ---- lgn_matrix_sparse.c, lgn_matrix.c: the iteration matrix ------------ */

int lgnAssembleSparse(LGNMem mem, sunrealtype t, const LGNMatrixTerms *terms);
int lgnAssembleIterationMatrix(LGNMem mem, sunrealtype t,
                               const LGNMatrixTerms *terms);

/* ---- lgn_redundancy.c: redundant constraints ---------------------------- */

int lgnRankRevealingRows(SUNMatrix B, sunindextype m, sunindextype nv, sunrealtype rank_floor,
                         sunindextype *rank, sunindextype *rows);
int lgnRedundancyAnalyse(LGNMem mem, const char *func);
int lgnRedundancyCheck(LGNMem mem, sunrealtype t, N_Vector q, const char *func);
void lgnRedundancyExpand(const LGNMem mem, const sunrealtype *lambda, sunrealtype *full);
sunindextype lgnUserRow(const LGNMem mem, sunindextype k);
int lgnUserConstr(LGNMem mem, sunrealtype t, N_Vector q, N_Vector phi);
int lgnUserConstrJac(LGNMem mem, sunrealtype t, N_Vector q, SUNMatrix B);
int lgnUserConstrTime(LGNMem mem, sunrealtype t, N_Vector q, N_Vector phit);
int lgnUserCurvature(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v, N_Vector z);
int lgnUserConstrForce(LGNMem mem, sunrealtype t, N_Vector q, N_Vector lambda, N_Vector f);
int lgnUserStiffness(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                     N_Vector lambda, SUNMatrix K);

/* ---- lgn_diag.c: diagnostics of a singular matrix ----------------------- */

void lgnDiagnoseSingular(LGNMem mem, int ret, char *buf, size_t len);

/* ---- lgn_ls.c: the linear solver bridge --------------------------------- */

int lgnLsCheck(LGNMem mem);
int lgnLsSetup(LGNMem mem);
int lgnLsSolve(LGNMem mem, N_Vector x, N_Vector b);

/* ---- lgn_krylov.c: Krylov solvers, preconditioners ---------------------- */

#define LGN_EPLIFAC_DEFAULT SUN_RCONST(0.05) /* as IDA's epslin factor */

int lgnKrylovAttach(LGNMem mem, SUNLinearSolver LS);
int lgnKrylovCheck(LGNMem mem);
int lgnKrylovCheckPreconditioner(LGNMem mem);
int lgnKrylovSetup(LGNMem mem);
int lgnKrylovSolve(LGNMem mem, N_Vector x, N_Vector b);
void lgnKrylovNewtonWeights(LGNMem mem, const LGNStepCoeffs *c);

/* ---- lgn_consistent_ic.c: consistent initial values ---------------------- */

int lgnInitialConditions(LGNMem mem); /* LGNSolve: the check, then lgnComputeIC */
int lgnComputeIC(LGNMem mem);         /* vdot_0, lambda_0, a_0 at (q_n, v_n)    */
int lgnProjectIC(LGNMem mem, int icopt);
int lgnPerturbedStart(LGNMem mem, sunrealtype h);

/* The saddle-point system [[M, B^T], [B, 0]] at (t, q, v), through the
 * iterate slots q1, v1 (vdot1, lambda1 zeroed): lgnEvalAt evaluates M, g,
 * B there, lgnSaddlePointFactor factorises, lgnSaddlePointBackSolve solves
 * for mem->rhs into mem->sol, lgnIndex1Rhs writes (-g, -z) into mem->rhs. */
int lgnEvalAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v);
int lgnSaddlePointFactor(LGNMem mem, sunrealtype t);
int lgnSaddlePointBackSolve(LGNMem mem);
int lgnIndex1Rhs(LGNMem mem, sunrealtype t);
int lgnProjectQAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v,
                  sunrealtype tol_stall, int min_it, const char *what);

/* ---- lgn_newton.c: the Newton iteration of a step ----------------------- */

void lgnNewtonTolerances(LGNMem mem, const LGNStepCoeffs *c);
void lgnNewtonTolerancesPerStep(LGNMem mem, sunrealtype h, sunrealtype share);
void lgnFixedNewtonTolerances(LGNMem mem);
int lgnNewton(LGNMem mem, const LGNStepCoeffs *c, sunbooleantype force_setup,
              sunbooleantype *used_old);

/* ---- lgn_failure.c: the step-failure policy of the error-controlled loops */

/* The cut of h after a Newton, singular-matrix or recoverable callback
 * failure (every family; IDA's IDAHandleNFlag cuts by 1/4 as well). */
#define LGN_CUT_NFAIL SUN_RCONST(0.25)

/* The flag of a failed attempt (LGN_CONV_FAILURE or LGN_RECOVERABLE) at
 * step size h, the ncf-th of the step: LGN_RECOVERABLE (retry with
 * h * LGN_CUT_NFAIL) or the final flag, reported, after maxncf failures or
 * at hmin: LGN_CONV_FAILURE, LGN_LSETUP_FAIL or LGN_REPTD_CALLBACK_ERR. */
int lgnHandleNFlag(LGNMem mem, int flag, sunrealtype h, int *ncf);

/* ---- lgn_newmark_errtest.c: the local error of a step --------------------------- */

int lgnLocalError(LGNMem mem, const LGNStepCoeffs *c, sunrealtype *norm);
int lgnProjectEstimate(LGNMem mem, const LGNStepCoeffs *c);
int lgnErrorNorm(LGNMem mem, const LGNStepCoeffs *c, const sunrealtype *incr,
                 sunrealtype unit, sunrealtype *norm);
sunrealtype lgnWrmsNorm(LGNMem mem, const sunrealtype *x, const sunrealtype *w);
void lgnErrorWeights(LGNMem mem, const sunrealtype *incr, sunrealtype unit, sunrealtype *w);

/* ---- lgn_dense_output.c: output between steps ---------------------------- */

int lgnDenseOutput(LGNMem mem, sunrealtype t, int k, sunrealtype *out);
/* The BDF family's interpolating polynomials (its table's dense output,
 * used once its history holds two points). */
int lgnBDFDenseOutput(LGNMem mem, sunrealtype t, int k, sunrealtype *out);

/* ---- lgn_output.c: the outputs LGNSolve and LGNGetDky return ------------- */

int lgnOutputAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v);
int lgnOutputDky(LGNMem mem, sunrealtype t, int k, N_Vector dky);
/* The multipliers in the error test (LGNSetMultiplierErrorControl): the
 * weighted RMS norm of lambda1 - lambda_c at the iterate (t1, q1, v1), 0
 * when off; the slots are kept. */
int lgnMultiplierError(LGNMem mem, sunrealtype t1, sunrealtype *norm);

/* ---- lgn_newmark_step.c: one step ---------------------------------------- */

LGNStepCoeffs lgnStepCoeffs(LGNMem mem, sunrealtype h);
int lgnCheckProgress(LGNMem mem, sunrealtype h);
int lgnStepAttempt(LGNMem mem, const LGNStepCoeffs *c);
void lgnStepRejected(LGNMem mem);
void lgnStepComplete(LGNMem mem, const LGNStepCoeffs *c);
void lgnCommitStep(LGNMem mem, const LGNStepCoeffs *c);
int lgnStep(LGNMem mem, sunrealtype h);

/* ---- lgn_newmark_adapt.c: one error-controlled step ---------------------- */

int lgnAdaptiveStep(LGNMem mem, sunrealtype tout);
sunrealtype lgnLimitStep(LGNMem mem, sunrealtype h);
sunrealtype lgnInitialStep(LGNMem mem, sunrealtype tout);
sunrealtype lgnFirstStep(LGNMem mem, sunrealtype tout);
/* LGN_ILL_INPUT with a message when error control meets index 3 with a
 * method that does not damp the constraint mode (rho_inf = 1) */
int lgnCheckIndex3Damping(LGNMem mem);

/* ---- lgn_bdf.c: the BDF family ------------------------------------------ */

int lgnBDFStep(LGNMem mem, sunrealtype h);
int lgnBDFAdaptiveStep(LGNMem mem, sunrealtype tout);

/* ---- lgn_family.c: the method families, one table each ----------------- */

/* A method family: what the driver, the getters, the dense output, the
 * error norm and Newton ask of it. Adding a family is adding its files and
 * one of these tables (lgnFamilyOps). */
typedef struct LGNFamilyOps {
  const char *name;
  int id;                      /* LGN_FAMILY_*                              */
  sunbooleantype error_per_step; /* the error test in the units of the step
                                  (else per unit step, lgnErrorNorm)       */
  sunbooleantype keeps_grid;   /* fixed steps: step past tout and interpolate
                                  rather than shorten the last step        */
  sunbooleantype ggl_at_tn;    /* GGL corrects with B(q_n) (Newton's GGL
                                  correction, the Jacobian at t_n)         */
  int (*prepare)(LGNMem mem);  /* its work space before the first step
                                  (NULL: none beyond lgnAllocWork)         */
  int (*step)(LGNMem mem, sunrealtype h);               /* a fixed step      */
  int (*adaptive_step)(LGNMem mem, sunrealtype tout);   /* error-controlled  */
  int (*dense_output)(LGNMem mem, sunrealtype t, int k, sunrealtype *out);
                               /* between t_n and t_{n+1} (NULL, or the BDF
                                  history short of two points: the Hermite
                                  interpolant of lgn_dense_output.c)              */
  int (*order)(const struct LGNMemRec *mem, sunbooleantype last);
} LGNFamilyOps;

const LGNFamilyOps *lgnFamilyOps(int family);

/* ---- lgn_root.c: events (root finding on the dense output) ------------- */

int lgnRootSolveStart(LGNMem mem, sunrealtype tout, int itask,
                      sunrealtype *tret, N_Vector q, N_Vector v,
                      sunbooleantype *done);
int lgnRootAfterStep(LGNMem mem, sunrealtype tout, int itask,
                     sunrealtype *tret, N_Vector q, N_Vector v);

/* helpers */
/* T = I on this block (an R^n leaf): nothing stored, nothing to apply. */
static inline sunbooleantype lgnBlockIsIdentity(const struct LGNMemRec *mem, int b)
{
  return mem->blk.group[b]->kind == LGN_GROUP_RN;
}

/* The columns k0 <= k < k1 of X whose entries column j of X T combines,
 * for T (and Tv, Ta) block diagonal by leaves (lgn_tangent.c): j alone in
 * an R^n leaf, where T = I, and in the translation part of an R^3 x SO(3)
 * leaf, where T = diag(I3, T_SO3); the rotation part of that leaf; the
 * whole leaf otherwise. */
static inline void lgnTangentColumnRange(const struct LGNMemRec *mem,
                                         sunindextype j, sunindextype *k0,
                                         sunindextype *k1)
{
  const int b = (int)mem->blk.of[j];
  const sunindextype o = mem->blk.voff[b];
  if (lgnBlockIsIdentity(mem, b) ||
      (mem->blk.group[b]->kind == LGN_GROUP_R3XSO3 && j < o + 3)) {
    *k0 = j;
    *k1 = j + 1;
  } else if (mem->blk.group[b]->kind == LGN_GROUP_R3XSO3) {
    *k0 = o + 3;
    *k1 = o + 6;
  } else {
    *k0 = o;
    *k1 = mem->blk.voff[b + 1];
  }
}

/* Is the perturbed start due at a step attempt: on, and the first attempt
 * since the initial values were computed at a start (nst = 0)? */
static inline sunbooleantype lgnPerturbedStartDue(const struct LGNMemRec *mem)
{
  return mem->pstart_on && !mem->pstart_done && mem->nst == 0;
}

/* A run across ranks (lgn_parallel.h): the flag every rank goes on with
 * (lgnAgreeRanks reports another rank's failure), sums and maxima over the
 * ranks. Inline, so that a run on one process pays one test each. */
static inline int lgnAgree(struct LGNMemRec *mem, int flag)
{
  return mem->ranks.par == NULL ? flag : lgnAgreeRanks(mem, flag);
}

static inline void lgnSumAll(const struct LGNMemRec *mem, sunrealtype *x, int n)
{
  if (mem->ranks.par != NULL) lgnParallelSum(mem->ranks.par, x, n);
}

static inline sunrealtype lgnMaxAll(const struct LGNMemRec *mem, sunrealtype x)
{
  return mem->ranks.par == NULL ? x : lgnParallelMax(mem->ranks.par, x);
}

static inline sunrealtype *lgnData(N_Vector x)
{
  return lgnVecData(x);
}

#endif
