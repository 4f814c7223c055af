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

typedef struct LGNMemRec {
  SUNContext sunctx;

  /* ---- a run across MPI ranks (lgn_parallel.h; NULL: one process) ---- */
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

  /* ---- BDF (lgn_bdf.c): the history q_{n-j}, v_{n-j} at t_{n-j} ---- */
  int bdf_maxord;           /* LGNSetBDF: 1 ... 5                          */
  int bdf_form;             /* LGNSetBDFForm: LGN_BDF_VARIABLE_COEFF / ..._FIXED_LEADING */
  int bdf_ns;               /* FLC: consecutive steps at this h and order (IDA's ns) */
  sunrealtype bdf_hused;    /* FLC: the last step's size                   */
  sunrealtype bdf_sigck;    /* FLC: sigma_k / ck of the attempt (IDA)      */
  sunbooleantype bdf_step_flc; /* the attempt used the fixed leading coefficient */
  sunbooleantype lsetup_recoverable; /* a singular setup is retried with a
                                        smaller step: no message (BDF)     */
  int bdf_order;            /* the order of the next step                  */
  int bdf_last_order;       /* the order of the last step taken            */
  int bdf_nhist;            /* valid history points (0: start anew)        */
  int bdf_nsteps_order;     /* steps taken at the current order            */
  sunbooleantype bdf_phase0;/* start-up: the order rises every step        */
  sunrealtype bdf_chart_t;  /* t_n of the chart coordinates in bdf_x       */
  sunrealtype bdf_t[LGN_BDF_MAXHIST];
  sunrealtype bdf_vgain[LGN_BDF_MAXHIST]; /* v_{n-j}'s gain on position noise */
  sunrealtype bdf_vgain1;   /* ... of the attempt's v_{n+1}: sum_j |d_j|      */
  sunrealtype bdf_vpgain;   /* ... of its predictor: sum_j |p_j| vgain_j      */
  sunrealtype *bdf_q;       /* LGN_BDF_MAXHIST x nq: q_{n-j}               */
  sunrealtype *bdf_v;       /* LGN_BDF_MAXHIST x nv: v_{n-j}               */
  sunrealtype *bdf_l;       /* LGN_BDF_MAXHIST x m: lambda_{n-j}           */
  sunrealtype *bdf_x;       /* LGN_BDF_MAXHIST x nv: log(q_n^{-1} q_{n-j}) */
  sunrealtype *bdf_rx, *bdf_rv; /* the known parts of xdot, vdot (nv each) */
  sunrealtype *bdf_xpred, *bdf_vpred; /* the predictor (nv each)           */
  sunrealtype *bdf_dd;      /* divided differences, (LGN_BDF_MAXHIST + 1) nv */
  sunrealtype *bdf_ele_keep; /* nv: the step's estimate (ele) while the order estimates use ele */
  sunrealtype bdf_c0;       /* leading coefficient of the BDF derivative   */
  long int bdf_nord[LGN_BDF_MAXORD + 1]; /* steps taken at each order      */
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
  sunrealtype *out_keep;    /* the last output's vdot and lambda kept while
                               a setter dropped the work space (or NULL) */
  sunindextype out_keep_nv, out_keep_m;
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
  N_Vector dq_q, dq_v, dq_g, dq_r, dq_z;

  /* ---- diagonal blocks of T: the leaves of the group (lgn_tangent.c) ---- */
  int nblk;
  sunindextype *blk_voff;   /* nblk + 1 offsets in v                       */
  sunindextype *blk_qoff;   /* nblk + 1 offsets in q                       */
  sunindextype *blk_toff;   /* nblk + 1 offsets in the packed T storage    */
  sunindextype *blk_of;     /* block of each velocity component            */
  LGNGroup *blk_group;      /* the leaf group of each block                */
  sunindextype blk_max;     /* largest block                               */
  sunindextype tlen;        /* packed length (identity blocks store none)  */

  /* ---- matrices of the model (Lignum-owned, of the type of A) ---- */
  SUNMatrix Mmat;           /* nv x nv                                      */
  SUNMatrix Bmat;           /* m x nv (NULL when m = 0)                     */
  SUNMatrix Kmat;           /* nv x nv tangent stiffness                    */
  SUNMatrix Cmat;           /* nv x nv tangent damping                      */
  SUNMatrix Mdq;            /* nv x nv scratch for difference quotients     */
  SUNMatrix Bdq;            /* m x nv scratch for difference quotients      */

  /* ---- linear solver (not owned) ---- */
  SUNLinearSolver LS;
  SUNMatrix A;
  sunbooleantype sparse;    /* A is a SUNSparseMatrix (KLU)                 */
  int sparsetype;           /* CSC_MAT or CSR_MAT when sparse               */
  struct LGNSparseWorkRec *sp; /* sparse path work (lgn_sparse.h)           */
  sunbooleantype ls_initialized;
  sunbooleantype ls_restart; /* the next setup starts clean (lgn_ls.c): the
                                last one failed, or A's pattern was dropped */

  /* ---- Krylov solvers (lgn_krylov.c; allocated by lgn_mem.c) ---- */
  sunbooleantype krylov;    /* LS is a matrix-free iterative solver: A is
                               Lignum's own CSC matrix (own_A)             */
  sunbooleantype own_A;     /* A created by Lignum (lgnAllocKrylov)        */
  int kry_pretype;          /* LS's preconditioning side (PREC_*; -1: unknown) */
  LGNPrecSetupFn psetup;    /* LGNSetPreconditioner (NULL: none)           */
  LGNPrecSolveFn psolve;
  int bp_nblocks;           /* LGNSetBlockPreconditioner (0: off)          */
  long int *bp_bodies;      /* its partition of the bodies (NULL: equal)   */
  struct LGNBlockPrecRec *bp; /* the block preconditioner (lgn_blockprec.c) */
  N_Vector kry_w;           /* the solve's weights (nv + m)                */
  N_Vector kry_tmp;         /* scratch (nv + m)                            */
  sunrealtype eplifac;      /* LGNSetEpsLin: linear / Newton tolerance     */
  sunbooleantype kry_newton;/* the next solve is Newton's: kry_w holds its
                               correction weights (lgnKrylovNewtonWeights) */
  sunrealtype asm_t;        /* the time and scalings of the last assembly  */
  sunrealtype asm_cM, asm_cC, asm_cK; /* (handed to LGNPrecSetupFn)        */
  long int nli;             /* Krylov iterations                           */
  long int npe;             /* preconditioner setups                       */
  long int nps;             /* preconditioner solves                       */
  long int njtimes;         /* products with the iteration matrix          */
  long int nlcf;            /* linear solves that missed their tolerance   */
  int kry_pfail;            /* across ranks: a preconditioner solve's failure
                               in the current Krylov solve (0: none)      */

  /* ---- redundant constraints (lgn_redundancy.c) ---- */
  sunindextype m_user;      /* the user's constraint rows (LGNSetConstraints);
                               m counts those the integrator keeps         */
  int red_mode;             /* LGN_REDUNDANT_ELIMINATE or _REFUSE          */
  sunindextype red_nout;    /* rows left out (0: m = m_user, no mapping)   */
  sunindextype *red_rows;   /* 2 m_user: the kept rows (m of them, ascending),
                               then those left out; then scratch           */
  sunindextype *red_keep;   /* m_user: the kept index of a user row, or -1 */
  N_Vector red_full;        /* m_user: a callback's output, the user's rows */
  N_Vector red_lam;         /* m_user: lambda expanded (0 on rows left out) */
  SUNMatrix red_B;          /* m_user x nv: the user's B, of A's kind      */
  sunrealtype red_viol;     /* the last check: max |Phi| of the rows left out */
  long int red_nsel;        /* selections made (a change of the kept rows) */
  SUNMatrix red_A;          /* a direct solver for the kept rows, of the   */
  SUNLinearSolver red_LS;   /* user's kind (NULL: the user's fits)        */
  SUNMatrix red_Auser;      /* the user's, sized for m_user, while red_A   */
  SUNLinearSolver red_LSuser; /* and red_LS stand in for them              */

  /* ---- the diagnosis of the last singular matrix (lgn_diag.c) ---- */
  sunindextype *diag_red;   /* redundant constraints (m; work space)       */
  sunindextype diag_nred;   /* their number (0: none found)                */
  sunindextype diag_pivot;  /* the zero-pivot unknown (-1: none)           */
  long int last_lin_flag;

  /* ---- Lignum's solves with a copy of KLU's factors (lgn_klu_solve.c) ---- */
  sunbooleantype own_klu_solves; /* LGNSetOwnKLUSolves (default SUNFALSE)  */
  sunbooleantype klu_valid;      /* klu holds the factors now in LS         */
  long int klu_nsolve;           /* solves with LS's factors since its setup */
  struct LGNKluCopyRec *klu;     /* the copy (NULL: none)                   */
  long int klu_pattern;          /* A's pattern number when KLU last factored */
  /* its counters (lgn_ls.c, LGNGetNumKLU*, LGNGetNumOwnKLU*; restarted at
   * the first setup after LGNInit / LGNReInit) */
  long int nklu_fallback;        /* own refactorisations handed back to KLU:
                                    a pivot below the rcond threshold      */
  long int nklu_copy;            /* whole copies of KLU's factors           */
  long int nklu_values;          /* copies of their values only             */
  long int nklu_refactor;        /* Lignum's refactorisations, KLU's stead  */
  long int nklu_solve;           /* solves with the copy                    */
  long int nklu_newpattern;      /* KLU factored: a new pattern of A        */
  long int nklu_nocopy;          /* no copy possible (sizes, memory, A)     */

  /* ---- the factorised iteration matrix, for modified Newton (lgn_newmark_step.c) ---- */
  sunbooleantype lu_valid;  /* A holds a factorised iteration matrix of a step */
  sunrealtype lu_h;         /* the step size it was built with             */
  long int lu_nst;          /* nst when it was built                       */
  sunrealtype newton_rate;  /* last contraction rate seen with a reused A  */
  sunrealtype lambda_noise; /* multiplier part of the last stalled correction */
  sunrealtype lambda_noise_h; /* ... and its step size (0: none seen)      */

  /* ---- bookkeeping ---- */
  sunbooleantype malloc_done; /* LGNInit called                             */
  sunbooleantype work_done;   /* work space allocated for current nv, m     */
  sunbooleantype mat_done;    /* model matrices allocated for the type of A */
  sunrealtype hlast;

  /* ---- error control (LGN_STEP_ADAPTIVE; lgn_newmark_adapt.c, lgn_newmark_errtest.c) ---- */
  int step_control;         /* LGN_STEP_FIXED or LGN_STEP_ADAPTIVE         */
  sunbooleantype tols_set;  /* LGNSStolerances or LGNSVtolerances called  */
  sunrealtype *atol_vec;    /* per-component atol, nv (NULL: the scalar)   */
  sunrealtype epcon;        /* Newton tolerance / error-test tolerance     */
  sunrealtype h0_user;      /* LGNSetInitStep (0: estimated)               */
  sunrealtype hmin, hmax;   /* step size limits (hmax 0: none)             */
  int maxnef, maxncf;       /* failures per step                           */
  sunrealtype hnext;        /* the step size to try next (0: none yet)     */
  sunrealtype h0_actual;    /* the first step size tried                   */
  sunrealtype tstop;        /* LGNSetStopTime                              */
  sunbooleantype tstop_set;
  sunrealtype err_norm;     /* |e| of the last step attempted              */
  sunrealtype err_prev;     /* |e| of the last step accepted               */
  sunrealtype *ele;         /* its local error estimate (nv)               */
  sunrealtype *ewt;         /* ... and error weights (nv)                  */
  sunrealtype *a_scaled;    /* a_n rescaled to the step size (nv)          */
  const sunrealtype *a_step;/* a_n as the step uses it: a or a_scaled      */
  sunrealtype nls_rtol;     /* Newton's tolerances in this step            */
  sunrealtype nls_atol;
  const sunrealtype *nls_atolv; /* ... per component (NULL: nls_atol)     */
  sunrealtype nls_vfac;     /* ... nls_atolv's factor (fixed steps: 1)     */
  sunrealtype nls_lrtol;    /* ... of the multipliers' part               */
  sunrealtype nls_latol;
  long int netf;            /* error-test failures                         */

  /* ---- the last step, for dense output (lgn_dense_output.c) ---- */
  sunrealtype tprev;        /* its start t_n; it ends at tn                */
  sunbooleantype dense_valid; /* q1, v1, vdot1 hold its start, and the    */
                              /* increment its chart coordinate            */
  sunrealtype *incr;        /* sigma variant: log(q_n^-1 q1), tracked (nv) */
  sunrealtype *zero_nv;     /* zeros (nv), the algebra's origin            */
  sunrealtype *dense_work;  /* the dense output's scratch (4 nv)           */

  /* ---- what LGNSolve returns (lgn_output.c) ---- */
  sunbooleantype out_consistent; /* LGNSetConsistentOutputs (default on)  */
  int out_project;          /* LGNSetProjectOutputs: LGN_PROJECT_*        */
  sunbooleantype out_valid; /* out_vdot, out_lambda hold the last output's */
  sunrealtype out_t;        /* ... time                                    */
  sunrealtype *out_vdot;    /* consistent vdot at the last output (nv)     */
  sunrealtype *out_lambda;  /* ... and lambda (m; NULL when m = 0)         */
  sunrealtype *out_save;    /* q1, v1, vdot1, lambda1 kept while an output
                               is computed (nq + 3 nv + m)                 */
  N_Vector out_q, out_v;    /* LGNGetDky's q and v (clones; NULL until used) */
  N_Vector out_lq, out_lv;  /* the last projected output's q, v (clones)   */
  sunrealtype out_lt;       /* ... its time                                */
  sunbooleantype out_lvalid; /* ... kept (a failed LGNSolve at that time
                               returns them: lgn.c)                      */
  sunrealtype *out_lwork;   /* the iterate's consistent lambda (m)         */
  sunbooleantype lambda_errcon; /* LGNSetMultiplierErrorControl (default off) */
  sunrealtype lambda_atol;  /* ... its absolute tolerance of the multipliers */
  sunrealtype lambda_err;   /* |e_lambda| of the last attempt (0: off)     */
  long int nout;            /* outputs made consistent or projected        */

  /* ---- root finding (lgn_root.c; arrays allocated by lgn_mem.c) ---- */
  int nrtfn;                /* number of root functions (0: off)           */
  LGNRootFn gfun;           /* g(t, q, v, gout, user_data)                 */
  sunrealtype *glo;         /* g at tlo, the last point checked (nrtfn)    */
  sunrealtype *ghi;         /* g at the right end of the bracket (nrtfn)   */
  sunrealtype *grout;       /* g at the root returned / the trial point    */
  int *iroots;              /* +1 / -1: a root found, its direction (nrtfn)*/
  int *rootdir;             /* LGNSetRootDirection: +1, -1, 0 (nrtfn)      */
  sunbooleantype *gactive;  /* g_i not exactly zero at tlo (nrtfn)         */
  N_Vector rt_q, rt_v;      /* q, v handed to g (clones of the state)      */
  sunrealtype tlo;          /* roots are sought in (tlo, ...]              */
  sunbooleantype rt_started;/* glo holds g at tlo (dropped by STATE)       */
  sunbooleantype rt_pending;/* a root returned before tn (LGN_ONE_STEP:    */
                            /* tn itself is returned next, as IDA does)    */
  sunbooleantype rt_first;  /* the first check since the start is ahead   */
  sunbooleantype rt_nowarn; /* LGNSetNoInactiveRootWarn                    */
  long int nge;             /* root function evaluations                   */

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
  char diag_text[400];       /* the diagnosis of the last singular matrix  */
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

/* ---- lgn_newmark_errtest.c: the local error of a step -------------------- */

int lgnLocalError(LGNMem mem, const LGNStepCoeffs *c, sunrealtype *norm);
int lgnProjectEstimate(LGNMem mem, const LGNStepCoeffs *c);
int lgnErrorNorm(LGNMem mem, const LGNStepCoeffs *c, const sunrealtype *incr,
                 sunrealtype unit, sunrealtype *norm);
sunrealtype lgnWrmsNorm(LGNMem mem, const sunrealtype *x, const sunrealtype *w);
void lgnErrorWeights(LGNMem mem, const sunrealtype *incr, sunrealtype unit, sunrealtype *w);

/* ---- lgn_dense_output.c: output between steps ---------------------------- */

int lgnDenseOutput(LGNMem mem, sunrealtype t, int k, sunrealtype *out);

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

/* ---- lgn_bdf.c: the BDF family ------------------------------------------ */

int lgnBDFStep(LGNMem mem, sunrealtype h);
int lgnBDFAdaptiveStep(LGNMem mem, sunrealtype tout);

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
  return mem->blk_group[b]->kind == LGN_GROUP_RN;
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
  const int b = (int)mem->blk_of[j];
  const sunindextype o = mem->blk_voff[b];
  if (lgnBlockIsIdentity(mem, b) ||
      (mem->blk_group[b]->kind == LGN_GROUP_R3XSO3 && j < o + 3)) {
    *k0 = j;
    *k1 = j + 1;
  } else if (mem->blk_group[b]->kind == LGN_GROUP_R3XSO3) {
    *k0 = o + 3;
    *k1 = o + 6;
  } else {
    *k0 = o;
    *k1 = mem->blk_voff[b + 1];
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
  return mem->par == NULL ? flag : lgnAgreeRanks(mem, flag);
}

static inline void lgnSumAll(const struct LGNMemRec *mem, sunrealtype *x, int n)
{
  if (mem->par != NULL) lgnParallelSum(mem->par, x, n);
}

static inline sunrealtype lgnMaxAll(const struct LGNMemRec *mem, sunrealtype x)
{
  return mem->par == NULL ? x : lgnParallelMax(mem->par, x);
}

static inline sunrealtype *lgnData(N_Vector x)
{
  return lgnVecData(x);
}

#endif
