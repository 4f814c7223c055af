/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Main user interface. The model is the DAE on a Lie group G (spec numerics.md §1)
 *
 *     qdot = q v~ ,   M(q) vdot + g(q, v, t) + B(q)^T lambda = 0 ,   Phi(q, t) = 0,
 *
 * integrated with Newmark / generalized-alpha steppers (Chung-Hulbert
 * convention: alpha_m, alpha_f weight the OLD values, equations at t_{n+1}).
 *
 * Skeleton of a user program (compare IDA):
 *   1. SUNContext_Create(NULL, &ctx);
 *   2. G = LGNGroup_R3xSO3();  q0, v0 = N_VNew_Serial(...)
 *   3. mem = LGNCreate(ctx);
 *   4. LGNSetGroup, LGNSetMassFn, LGNSetForceFn, LGNSetConstraints, ...
 *   5. LGNInit(mem, t0, q0, v0);
 *   6. A = SUNDenseMatrix(nv+m, nv+m, ctx); LS = SUNLinSol_Dense(tmp, A, ctx);
 *      LGNSetLinearSolver(mem, LS, A);
 *   7. LGNSetGenAlpha(mem, 0.9); LGNSetStepSize(mem, 1e-3);
 *   8. loop: LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
 *   9. LGNPrintAllStats(mem, stdout, SUN_OUTPUTFORMAT_TABLE);
 *  10. LGNFree(&mem); SUNLinSolFree(LS); SUNMatDestroy(A); N_VDestroy(...);
 *      LGNGroup_Destroy(G); SUNContext_Free(&ctx);
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_H
#define LIGNUM_H

#include <stdio.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>
#include <sundials/sundials_types.h>

#include <lignum/lignum_config.h>
#include <lignum/lignum_group.h>

#ifdef __cplusplus
extern "C" {
#endif

/* =============================================================================
 * Return flags: one flat, non-overlapping space (names via LGNGetReturnFlagName)
 * ===========================================================================*/

#define LGN_SUCCESS             0   /**< success                                  */
#define LGN_TSTOP_RETURN        1   /**< LGNSolve stopped at the stop time         */

/* solver failures -1 .. -19 */
#define LGN_TOO_MUCH_WORK      -1   /**< max number of steps reached before tout  */
#define LGN_CONV_FAILURE       -2   /**< Newton iteration did not converge        */
#define LGN_MASS_FAIL          -3   /**< mass matrix callback failed              */
#define LGN_FORCE_FAIL         -4   /**< force callback failed                    */
#define LGN_CONSTR_FAIL        -5   /**< constraint callback failed               */
#define LGN_CONSTR_JAC_FAIL    -6   /**< constraint Jacobian callback failed      */
#define LGN_TANGENT_FAIL       -7   /**< stiffness / damping / curvature failed   */
#define LGN_GROUP_FAIL         -8   /**< a Lie group operation failed             */
#define LGN_NONFINITE          -9   /**< a callback produced NaN or Inf           */
#define LGN_REPTD_CALLBACK_ERR -10  /**< a recoverable callback error persisted   */
#define LGN_IC_FAIL            -11  /**< consistent initial values not computable */
#define LGN_ERR_FAILURE        -12  /**< the error test failed repeatedly or at hmin */

/* usage errors -20 .. -29 */
#define LGN_MEM_NULL           -20  /**< the memory argument is NULL              */
#define LGN_MEM_FAIL           -21  /**< a memory allocation failed               */
#define LGN_ILL_INPUT          -22  /**< an argument is illegal                   */
#define LGN_NO_MALLOC          -23  /**< LGNInit has not been called              */
#define LGN_NO_LINSOL          -24  /**< no linear solver attached                */
#define LGN_MISSING_FN         -25  /**< a required callback is not set           */
#define LGN_BAD_TOUT           -26  /**< tout lies behind the current time        */
#define LGN_BAD_T              -27  /**< LGNGetDky: t outside the last step       */
#define LGN_BAD_K              -28  /**< LGNGetDky: k not 0, 1 or 2               */

/* linear solver interface -30 .. -39 */
#define LGN_LINIT_FAIL         -30  /**< SUNLinSolInitialize failed               */
#define LGN_LSETUP_FAIL        -31  /**< SUNLinSolSetup failed (e.g. singular)     */
#define LGN_LSOLVE_FAIL        -32  /**< SUNLinSolSolve failed                    */
#define LGN_LS_MISMATCH        -33  /**< matrix / linear solver do not fit        */

#define LGN_UNRECOGNIZED_ERR   -99  /**< unknown failure                          */

/* =============================================================================
 * Other constants
 * ===========================================================================*/

/** itask of LGNSolve: advance to tout (last step shortened to hit tout). */
#define LGN_NORMAL   1
/** itask of LGNSolve: take a single step and return. */
#define LGN_ONE_STEP 2

/** Step size control (LGNSetStepControl): the fixed step of LGNSetStepSize
 *  (default). */
#define LGN_STEP_FIXED    40
/** Step size control: error control with the tolerances of LGNSStolerances
 *  or LGNSVtolerances (adaptive steps, retries, output between steps). */
#define LGN_STEP_ADAPTIVE 41

/** Constraint formulation: position level Phi(q) = 0 (index 3, scaled). */
#define LGN_CONSTR_INDEX3 3
/** Constraint formulation: velocity level B(q) v = 0 (index 2). */
#define LGN_CONSTR_INDEX2 2

/** Kinematics: v = xdot, vdot = xddot in each step (LGNM, LGGalpha). */
#define LGN_KINEMATICS_SIMPLIFIED 0
/** Kinematics: v = T(x) xdot, vdot = T xddot + Tdot xdot (mod. LGNM / LGGalpha). */
#define LGN_KINEMATICS_EXACT      1
/** Kinematics of the sigma variant (Holzinger-Arnold-Gerstmayr 2025):
 *  predictor increment scaled by Xi = I - (h beta/(2 gamma)) ad(v_pred),
 *  Newton corrections composed on the right, no tangent operator. Linearly
 *  unstable at index 3 for rho_inf >~ 0.7 unless h |Omega| is small. */
#define LGN_KINEMATICS_SIGMA      2

/** Newton predictor (default): sigma_ddot = 0 and lambda = lambda_n (spec §2). */
#define LGN_PREDICTOR_ZERO        0
/** Newton predictor: vdot and lambda extrapolated linearly from
 *  the last two steps (constant on the first step), mapped into the chart of
 *  the step for exact kinematics. */
#define LGN_PREDICTOR_EXTRAPOLATE 1

/** Newton iteration (default): the iteration matrix is evaluated and
 *  factorised at every iterate (quadratic convergence). */
#define LGN_NEWTON_FULL     0
/** Modified Newton iteration: the factorised iteration matrix is reused over
 *  iterations and steps while the iteration contracts fast, as in IDA. It is
 *  rebuilt at the first iterate of a step when the step size differs by more
 *  than 10% from the one it was built with, after LGNSetLSetupFrequency steps,
 *  or after a change of the model or method; within a step when the
 *  contraction rate exceeds 0.9; and a step whose iteration fails with a
 *  reused matrix is retried once with a fresh one. */
#define LGN_NEWTON_MODIFIED 1

/* =============================================================================
 * User callbacks. Return 0 on success, > 0 for a recoverable failure, < 0 for
 * an unrecoverable one. Matrices passed to the user are zeroed beforehand.
 * ===========================================================================*/

/** Mass matrix: M = M(q, t), nv x nv. */
typedef int (*LGNMassFn)(sunrealtype t, N_Vector q, SUNMatrix M,
                         void *user_data);

/** Forces: g = g(q, v, t), so that M vdot + g + B^T lambda = 0. */
typedef int (*LGNForceFn)(sunrealtype t, N_Vector q, N_Vector v, N_Vector g,
                          void *user_data);

/** Constraints: phi = Phi(q, t), length m. */
typedef int (*LGNConstrFn)(sunrealtype t, N_Vector q, N_Vector phi,
                           void *user_data);

/** Constraint Jacobian in Lie algebra directions: B(q) with
 *  DPhi(q).(q w~) = B(q) w, an m x nv matrix. */
typedef int (*LGNConstrJacFn)(sunrealtype t, N_Vector q, SUNMatrix B,
                              void *user_data);

/** Tangent stiffness K_t: D_q[M vdot + g + B^T lambda].(q w~) = K_t w (nv x nv). */
typedef int (*LGNStiffnessFn)(sunrealtype t, N_Vector q, N_Vector v,
                              N_Vector vdot, N_Vector lambda, SUNMatrix K,
                              void *user_data);

/** Tangent damping C_t = dg/dv (nv x nv). */
typedef int (*LGNDampingFn)(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C,
                            void *user_data);

/** Constraint forces f = B(q)^T lambda (length nv), without forming B: an
 *  optional shortcut for the residual (LGNSetConstraintForceFn). */
typedef int (*LGNConstrForceFn)(sunrealtype t, N_Vector q, N_Vector lambda,
                                N_Vector f, void *user_data);

/** Constraint curvature z = Z(q)(v, v), with d/dt(B v) = B vdot + Z(q)(v, v). */
typedef int (*LGNCurvatureFn)(sunrealtype t, N_Vector q, N_Vector v,
                              N_Vector z, void *user_data);

/** Error handler (replaceable); the default prints to stderr. */
typedef void (*LGNErrHandlerFn)(int error_code, const char *module,
                                const char *function, const char *msg,
                                void *eh_data);

/* =============================================================================
 * Lifecycle
 * ===========================================================================*/

/** Create an integrator memory block.
 *  @param sunctx the SUNDIALS context (must not be NULL)
 *  @return the memory block, or NULL on failure (message on stderr). */
void *LGNCreate(SUNContext sunctx);

/** Provide the initial state and allocate the state vectors.
 *  The Lie group must have been set with LGNSetGroup.
 *  @param lgn_mem memory from LGNCreate
 *  @param t0 initial time
 *  @param q0 initial configuration (length nq of the group; serial N_Vector)
 *  @param v0 initial velocity (length nv of the group)
 *  @return LGN_SUCCESS, LGN_MEM_NULL, LGN_ILL_INPUT, LGN_MEM_FAIL. */
int LGNInit(void *lgn_mem, sunrealtype t0, N_Vector q0, N_Vector v0);

/** Restart from a new initial state, keeping all settings. Counters are reset
 *  and the consistent initial values recomputed at the next LGNSolve.
 *  @return as LGNInit; LGN_NO_MALLOC if LGNInit was never called. */
int LGNReInit(void *lgn_mem, sunrealtype t0, N_Vector q0, N_Vector v0);

/** Advance the solution.
 *  @param lgn_mem memory block
 *  @param tout    the output time (LGN_NORMAL) or a direction hint (LGN_ONE_STEP)
 *  @param tret    on return, the time reached
 *  @param q       on return, the configuration at tret (length nq)
 *  @param v       on return, the velocity at tret (length nv)
 *  @param itask   LGN_NORMAL: steps of the fixed size h until tout, the last
 *                 one shortened to land on tout; LGN_ONE_STEP: one step
 *  @return LGN_SUCCESS or a negative flag. On failure the integrator keeps the
 *          last accepted state (tret, q, v are that state), so it can continue
 *          after the cause has been fixed (e.g. a smaller step size). */
int LGNSolve(void *lgn_mem, sunrealtype tout, sunrealtype *tret, N_Vector q,
             N_Vector v, int itask);

/** Free the memory block and everything Lignum allocated; sets *lgn_mem = NULL.
 *  Objects the user created (group, vectors, matrix, linear solver) are not freed. */
void LGNFree(void **lgn_mem);

/* =============================================================================
 * Model description
 * ===========================================================================*/

/** Set the Lie group (configuration space). Required before LGNInit.
 *  The group is referenced, not copied; it must outlive the memory block. */
int LGNSetGroup(void *lgn_mem, LGNGroup G);

/** Set the pointer passed to every callback. */
int LGNSetUserData(void *lgn_mem, void *user_data);

/** Set the mass matrix callback (required). */
int LGNSetMassFn(void *lgn_mem, LGNMassFn mass);

/** Set the force callback (required). */
int LGNSetForceFn(void *lgn_mem, LGNForceFn force);

/** Set the number of constraints and their callbacks.
 *  @param m   number of constraints (0 for an unconstrained system)
 *  @param phi Phi(q, t) (required if m > 0)
 *  @param B   its Jacobian in Lie algebra directions (required if m > 0) */
int LGNSetConstraints(void *lgn_mem, sunindextype m, LGNConstrFn phi,
                      LGNConstrJacFn B);

/** Set the tangent stiffness callback. NULL (default): difference quotients
 *  along the group. */
int LGNSetStiffnessFn(void *lgn_mem, LGNStiffnessFn K);

/** Set the tangent damping callback. NULL (default): difference quotients. */
int LGNSetDampingFn(void *lgn_mem, LGNDampingFn C);

/** Set the constraint curvature callback Z(q)(v,v). NULL (default):
 *  difference quotients of B(q exp(eps v)) v. */
int LGNSetCurvatureFn(void *lgn_mem, LGNCurvatureFn Z);

/** Set a callback for the constraint forces f = B(q)^T lambda. With it, the
 *  Newton residual at index 3 needs no B: the constraint Jacobian is then
 *  evaluated only when the iteration matrix is built (every iteration with
 *  full Newton, at the setups of modified Newton) and for the initial
 *  values. It must equal B(q)^T lambda of the LGNConstrJacFn to round-off
 *  (LGNJoints_ConstraintForce does). NULL (default): f from B. A failure
 *  is reported as LGN_CONSTR_JAC_FAIL. */
int LGNSetConstraintForceFn(void *lgn_mem, LGNConstrForceFn F);

/** Declare the mass matrix constant: M depends on neither q nor t, as for
 *  rigid bodies on R^3 x SO(3) or SE(3) with body-fixed angular velocities
 *  (and a body-fixed reference point at the centre of mass for SE(3)).
 *  The LGNMassFn is then called once after each LGNInit / LGNReInit (or a
 *  change of the linear solver) and M is kept. Default: SUNFALSE. */
int LGNSetMassConstant(void *lgn_mem, sunbooleantype constant);

/* =============================================================================
 * Method and solver settings (zero restores a default where stated)
 * ===========================================================================*/

/** Attach a linear solver and the iteration matrix A ((nv+m) x (nv+m)).
 *  Supported now: SUNDenseMatrix with SUNLinSol_Dense (or any direct solver
 *  on a dense matrix). Lignum does not take ownership. */
int LGNSetLinearSolver(void *lgn_mem, SUNLinearSolver LS, SUNMatrix A);

/** Solve with Lignum's own triangular solves on a copy of KLU's factors
 *  (SUNLinSol_KLU only). Off by default: opt in with own = SUNTRUE.
 *  Lignum copies L, U, the off-diagonal BTF blocks, the permutations and
 *  the row scaling out of KLU (klu_l_extract) with 32-bit indices and
 *  solves with the copy instead of calling SUNLinSolSolve: 12 instead of
 *  16 bytes per entry to read and a shorter chain of dependences make a
 *  solve about twice as fast.
 *  - CSC matrix: the copy holds L and U by rows and is made at the first
 *    solve after KLU's factorisation. From then on Lignum also refactors
 *    in its place: each row of Rs^{-1} A(P, Q) is eliminated against the
 *    rows of U with KLU's pivots, blocks, pattern and row scaling
 *    (klu_common.scale), which gives KLU's factors up to roundoff without
 *    klu_l_refactor and without copying them out again. As SUNLinSolSetup
 *    does, it checks KLU's cheap rcond, min |U(i,i)| / max |U(i,i)|: below
 *    eps^(2/3), and after a change of A's pattern, KLU factors (and may
 *    pivot anew) and its factors are copied again.
 *  - CSR matrix: the copy holds the columns of KLU's factors and is made
 *    at the second solve with a factorisation (so never with full Newton);
 *    after klu_l_refactor only the new values are taken.
 *  By columns (CSR) the solves do KLU's operations in KLU's order: the
 *  results agree with SUNLinSolSolve to the last bit without fused
 *  multiply-add. By rows (CSC) U's rows are kept divided by U's diagonal,
 *  which takes the division off the solve's chain of dependences, and
 *  Lignum refactors: the results agree with SUNLinSolSolve to roundoff
 *  (backward errors within a small factor of KLU's: at most 2.5 times in
 *  the tests, which allow 10). The copy takes 12 bytes per
 *  entry of L + U, 56 per row, 8 per entry of A for the refactorisation's
 *  maps, and 8 per entry of the larger factor for the extraction (counted
 *  in LGNGetWorkSpace; doc/user-guide.md, section 7). Factors beyond 32-bit
 *  indices, or memory refused, make Lignum fall back to SUNLinSolSetup and
 *  SUNLinSolSolve (LGNGetNumKLUFallbacks).
 *  What it buys (bench/chain_scaling, the 1000- and 10000-body chains,
 *  KLU CSC, CPU ms per step, copy off -> on): full Newton 3.16 -> 2.60
 *  and 33.2 -> 20.8, modified Newton 0.608 -> 0.397 and 8.49 -> 4.61
 *  (1.2 to 1.8 times faster; doc/user-guide.md, section 7), for 3.2 kB
 *  more memory per body (16.8 instead of 13.6 kB with KLU's).
 *  Why it is off by default: it reads KLU's Numeric and Symbolic objects
 *  and packed columns and SUNLinSol_KLU's private content, layouts that
 *  neither library publishes. So it accepts only the versions it was
 *  written and tested against: KLU 1.3 (SuiteSparse 5; the version
 *  compiled against) with SUNDIALS 6.4 (the version found at run time and
 *  the one compiled against).
 *  @param lgn_mem memory block
 *  @param own     SUNTRUE: Lignum's solves (and, CSC, its
 *                 refactorisations); SUNFALSE (default): SUNLinSolSetup and
 *                 SUNLinSolSolve, a copy is freed and the next step sets
 *                 the matrix up anew. With a dense solver the setting is
 *                 only recorded.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT for own = SUNTRUE
 *          when the copy is not available: other versions of KLU or
 *          SUNDIALS (the message names those found and those supported),
 *          SUNDIALS with 32-bit indices, or Lignum built without KLU
 *          (LGN_ENABLE_KLU=OFF); the setting then stays off. */
int LGNSetOwnKLUSolves(void *lgn_mem, sunbooleantype own);

/** Number of whole copies of KLU's factors (klu_l_extract) made for
 *  Lignum's solves (LGNSetOwnKLUSolves): after each factorisation by KLU
 *  with new pivots or a new pattern. Counted from LGNInit / LGNReInit, as
 *  all counters; 0 with the copy off.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (ncopies = NULL). */
int LGNGetNumKLUFactorCopies(void *lgn_mem, long int *ncopies);

/** Number of copies of the values only of KLU's factors, after
 *  klu_l_refactor kept the pattern (CSR matrices: KLU refactors).
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (nvalues = NULL). */
int LGNGetNumKLUValueCopies(void *lgn_mem, long int *nvalues);

/** Number of Lignum's refactorisations into the copy that took the place
 *  of SUNLinSolSetup (CSC matrices). LGNGetNumLinSolvSetups counts these
 *  and KLU's factorisations together.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (nrefactors = NULL). */
int LGNGetNumOwnKLURefactors(void *lgn_mem, long int *nrefactors);

/** Number of linear solves with the copy instead of SUNLinSolSolve (of
 *  LGNGetNumLinSolves, which counts both).
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (nsolves = NULL). */
int LGNGetNumOwnKLUSolves(void *lgn_mem, long int *nsolves);

/** Number of times KLU factored where Lignum would have refactored into the
 *  copy, or its factors could not be copied, by cause:
 *  @param npivot   Lignum's refactorisation left a pivot below SUNDIALS'
 *                  rcond threshold (its work is spent; KLU may pivot anew)
 *  @param npattern A's sparsity pattern changed (a new symbolic analysis)
 *  @param nnocopy  the factors could not be copied or A did not fit the
 *                  copy (sizes beyond 32-bit indices, memory refused):
 *                  KLU's setups and solves until the next factorisation
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT (an output NULL,
 *          named in the message). */
int LGNGetNumKLUFallbacks(void *lgn_mem, long int *npivot, long int *npattern,
                          long int *nnocopy);

/** Fixed step size h > 0 (required). */
int LGNSetStepSize(void *lgn_mem, sunrealtype h);

/** Newmark method (alpha_m = alpha_f = 0) with parameters beta, gamma.
 *  Requires 0 < beta <= 1/2 and 0 < gamma <= 1. Second order iff gamma = 1/2. */
int LGNSetNewmark(void *lgn_mem, sunrealtype beta, sunrealtype gamma);

/** Generalized-alpha with the Chung-Hulbert parameters for spectral radius
 *  at infinity rho_inf in [0, 1] (see LGNGenAlphaFromRhoInf). This is the
 *  default with rho_inf = 0.9. */
int LGNSetGenAlpha(void *lgn_mem, sunrealtype rho_inf);

/** Generalized-alpha with all four parameters (Chung-Hulbert convention).
 *  Requires alpha_m < 1, alpha_f < 1, beta > 0, gamma > 0. */
int LGNSetGenAlphaParams(void *lgn_mem, sunrealtype alpha_m,
                         sunrealtype alpha_f, sunrealtype beta,
                         sunrealtype gamma);

/** Constraint formulation: LGN_CONSTR_INDEX3 (default) or LGN_CONSTR_INDEX2. */
int LGNSetConstraintIndex(void *lgn_mem, int index);

/** Kinematic relations used in each step: LGN_KINEMATICS_SIMPLIFIED (default),
 *  LGN_KINEMATICS_EXACT or LGN_KINEMATICS_SIGMA (see the constants). */
int LGNSetKinematics(void *lgn_mem, int kinematics);

/** Newton predictor: LGN_PREDICTOR_ZERO (default) or LGN_PREDICTOR_EXTRAPOLATE.
 *  The converged solution does not depend on it (to the Newton tolerance),
 *  the number of Newton iterations does. Extrapolation saves about one
 *  iteration per step on damped methods but amplifies the parasitic
 *  multiplier oscillation of undamped index-3 Newmark (which then may fail). */
int LGNSetPredictor(void *lgn_mem, int predictor);

/** Newton stop test tolerances: stop when the WRMS norm of the increment
 *  (weights 1/(atol + rtol |xi|)) is <= 1. Defaults 1e-8, 1e-8; 0 restores. */
int LGNSStolerances(void *lgn_mem, sunrealtype rtol, sunrealtype atol);

/** Maximum number of Newton iterations per step (0: default 20). */
int LGNSetMaxNewtonIters(void *lgn_mem, int maxiters);

/** Newton variant: LGN_NEWTON_FULL (default) or LGN_NEWTON_MODIFIED (see the
 *  constants). The converged solution is the same to the Newton tolerance;
 *  the modified iteration needs more, but much cheaper, iterations. */
int LGNSetNewtonMode(void *lgn_mem, int mode);

/** Modified Newton: maximum number of steps between two evaluations and
 *  factorisations of the iteration matrix (0: default 10; < 0: no limit,
 *  the matrix is then rebuilt only when the convergence requires it).
 *  Like CVODE's CVodeSetLSetupFrequency. */
int LGNSetLSetupFrequency(void *lgn_mem, long int msbp);

/** Maximum number of steps per LGNSolve call (0: default 1000000, < 0: no limit). */
int LGNSetMaxNumSteps(void *lgn_mem, long int mxsteps);

/** Give consistent initial values vdot0 (length nv) and lambda0 (length m,
 *  may be NULL when m = 0) instead of letting Lignum compute them. Must be
 *  called after LGNInit/LGNReInit. */
int LGNSetInitialAcceleration(void *lgn_mem, N_Vector vdot0, N_Vector lambda0);

/** Set the initial algorithmic acceleration a_0 (default a_0 = vdot_0).
 *  Must be called after LGNInit/LGNReInit. */
int LGNSetInitialAux(void *lgn_mem, N_Vector a0);

/** Tell Lignum that the sparsity pattern of M, B, K_t or C_t has changed:
 *  at the next assembly the pattern of the iteration matrix and the column
 *  colouring of the difference quotients are rebuilt, and KLU analyses the
 *  new pattern. Without this call the pattern found at the first assembly is
 *  kept (KLU only refactors); entries outside it extend it automatically.
 *  A no-op for dense matrices. */
int LGNResetSparsityPattern(void *lgn_mem);

/** Replace the error handler (NULL restores the default). */
int LGNSetErrHandlerFn(void *lgn_mem, LGNErrHandlerFn ehfun, void *eh_data);

/** Set the stream of the default error handler (NULL silences it). */
int LGNSetErrFile(void *lgn_mem, FILE *errfp);

/* =============================================================================
 * Parameter maps (pure functions, no memory block)
 * ===========================================================================*/

/** Chung-Hulbert generalized-alpha parameters from rho_inf in [0, 1]:
 *  alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1),
 *  gamma = 1/2 + alpha_f - alpha_m, beta = (gamma + 1/2)^2 / 4.
 *  @return LGN_SUCCESS, or LGN_ILL_INPUT if rho_inf is outside [0, 1] or
 *          an output pointer is NULL. */
int LGNGenAlphaFromRhoInf(sunrealtype rho_inf, sunrealtype *alpha_m,
                          sunrealtype *alpha_f, sunrealtype *beta,
                          sunrealtype *gamma);

/* =============================================================================
 * Outputs
 * ===========================================================================*/

/** Acceleration vdot at the current time (length nv). */
int LGNGetAcceleration(void *lgn_mem, N_Vector vdot);
/** Multipliers lambda at the current time (length m). */
int LGNGetMultipliers(void *lgn_mem, N_Vector lambda);
/** Algorithmic acceleration a at the current time (length nv). */
int LGNGetAuxAcceleration(void *lgn_mem, N_Vector a);
/** Current time. */
int LGNGetCurrentTime(void *lgn_mem, sunrealtype *tcur);
/** Size of the last step taken. */
int LGNGetLastStep(void *lgn_mem, sunrealtype *hlast);
/** Method parameters in use. */
int LGNGetMethodParams(void *lgn_mem, sunrealtype *alpha_m,
                       sunrealtype *alpha_f, sunrealtype *beta,
                       sunrealtype *gamma);
/** Number of steps taken. */
int LGNGetNumSteps(void *lgn_mem, long int *nsteps);
/** Number of Newton iterations. */
int LGNGetNumNewtonIters(void *lgn_mem, long int *nniters);
/** Number of Newton convergence failures. */
int LGNGetNumNewtonConvFails(void *lgn_mem, long int *nncfails);
/** Number of failed step attempts (any cause). */
int LGNGetNumStepFails(void *lgn_mem, long int *nfails);
/** Number of residual evaluations (M, g, B, Phi at one point) in Newton. */
int LGNGetNumResEvals(void *lgn_mem, long int *nres);
/** Number of residual-type evaluations spent in difference quotients. */
int LGNGetNumDQEvals(void *lgn_mem, long int *ndq);
/** Number of iteration matrix evaluations (Jacobian builds). */
int LGNGetNumJacEvals(void *lgn_mem, long int *njevals);
/** Number of steps whose Newton iteration was accepted with the
 *  configuration converged and the multiplier corrections stalled at
 *  roundoff level (no longer contracting, or within the level of the last
 *  such stall at this step size; see doc/user-guide.md). */
int LGNGetNumNewtonStalls(void *lgn_mem, long int *nstalls);
/** Number of patterns of the sparse iteration matrix built (each followed
 *  by a symbolic analysis in KLU); 0 for dense matrices. */
int LGNGetNumSparsityAnalyses(void *lgn_mem, long int *nanalyses);
/** Number of stored entries of the iteration matrix: its pattern's size for
 *  sparse matrices (0 before the first assembly), (nv + m)^2 for dense ones. */
int LGNGetIterationMatrixNnz(void *lgn_mem, long int *nnz);
/** Number of displaced evaluations per difference-quotient stiffness matrix:
 *  the number of column colours (sparse) or nv (dense); 0 before the first
 *  assembly of a sparse matrix. */
int LGNGetNumDQColors(void *lgn_mem, long int *ncolors);
/** Work space of the integrator, like IDAGetWorkSpace: lenrw reals and leniw
 *  integers held by Lignum (vectors, model matrices, block storage, sparse
 *  patterns; not the user's A and linear solver). Allocated at the first
 *  LGNSolve, so call it afterwards. */
int LGNGetWorkSpace(void *lgn_mem, long int *lenrw, long int *leniw);
/** Number of linear solver setups (factorisations). */
int LGNGetNumLinSolvSetups(void *lgn_mem, long int *nlsetups);
/** Number of linear solves. */
int LGNGetNumLinSolves(void *lgn_mem, long int *nlsolves);

/** Number of Newton iterations solved with a reused (not freshly factorised)
 *  iteration matrix (modified Newton; 0 with full Newton). */
int LGNGetNumMatrixReuses(void *lgn_mem, long int *nreuses);

/** Number of steps whose modified Newton iteration failed with a reused
 *  matrix and was restarted, successfully or not, with a fresh one. */
int LGNGetNumNewtonRestarts(void *lgn_mem, long int *nrestarts);
/** Return flag of the last linear solver call. */
int LGNGetLastLinFlag(void *lgn_mem, long int *flag);
/** Print all counters as aligned "Name = value" lines or CSV. */
int LGNPrintAllStats(void *lgn_mem, FILE *outfile, SUNOutputFormat fmt);
/** Name of a return flag, e.g. "LGN_CONV_FAILURE" (static string, never NULL). */
const char *LGNGetReturnFlagName(long int flag);

/* =============================================================================
 * Error control: adaptive steps, stop time, output between steps
 * ===========================================================================*/

/** Select the step size control: LGN_STEP_FIXED (default: the step of
 *  LGNSetStepSize, the last step of LGN_NORMAL shortened to land on tout)
 *  or LGN_STEP_ADAPTIVE (the local error of every step is estimated and
 *  kept within the tolerances of LGNSStolerances / LGNSVtolerances; a step
 *  that fails the error test, whose Newton iteration fails or whose
 *  callback fails recoverably (> 0) is retried with a smaller h).
 *  In the adaptive mode LGN_NORMAL steps past tout and interpolates there
 *  (LGNGetDky), as IDA does; LGNSetStopTime lands on a time exactly.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT for another value. */
int LGNSetStepControl(void *lgn_mem, int control);

/** Tolerances with a vector of absolute tolerances, one per velocity
 *  component (length nv, > 0 each; in the units of the configuration's
 *  increment: lengths, angles). With error control the error test of a step
 *  is sqrt( (1/nv) sum_i (e_i / (atol_i + rtol |s_i|))^2 ) <= 1, with e the
 *  local error estimate and s the step's increment in the Lie algebra;
 *  the Newton iteration then converges to epcon (LGNSetNonlinConvCoef) times
 *  these. In the fixed-step mode the Newton iteration uses rtol and the mean
 *  of atol, as with LGNSStolerances. The vector is copied.
 *  @return LGN_SUCCESS, LGN_MEM_NULL, LGN_NO_MALLOC (before LGNInit),
 *          LGN_ILL_INPUT (rtol < 0, atol NULL, of the wrong length, or an
 *          entry <= 0 or not finite), LGN_MEM_FAIL. */
int LGNSVtolerances(void *lgn_mem, sunrealtype rtol, N_Vector atol);

/** The first step size of error control (0: estimated from the initial
 *  acceleration, the default). @return LGN_ILL_INPUT if h0 < 0 or not finite. */
int LGNSetInitStep(void *lgn_mem, sunrealtype h0);

/** The smallest step size error control may take (default 0).
 *  @return LGN_ILL_INPUT if hmin < 0, not finite or above hmax. */
int LGNSetMinStep(void *lgn_mem, sunrealtype hmin);

/** The largest step size error control may take (0: no limit, the default).
 *  @return LGN_ILL_INPUT if hmax < 0, not finite or below hmin. */
int LGNSetMaxStep(void *lgn_mem, sunrealtype hmax);

/** Error-test failures allowed in one step before LGN_ERR_FAILURE
 *  (0: the default 10). @return LGN_ILL_INPUT if maxnef < 0. */
int LGNSetMaxErrTestFails(void *lgn_mem, int maxnef);

/** Newton convergence failures (and recoverable callback failures) allowed
 *  in one step before LGN_CONV_FAILURE (or LGN_REPTD_CALLBACK_ERR)
 *  (0: the default 10). @return LGN_ILL_INPUT if maxncf < 0. */
int LGNSetMaxConvFails(void *lgn_mem, int maxncf);

/** The ratio of the Newton iteration's tolerances to the error test's with
 *  error control (0: the default 0.33, as IDA's epcon).
 *  @return LGN_ILL_INPUT unless 0 <= epcon <= 1 (0: default). */
int LGNSetNonlinConvCoef(void *lgn_mem, sunrealtype epcon);

/** A time error control must not step past: LGNSolve lands on it exactly
 *  and returns LGN_TSTOP_RETURN there; the stop time is then cleared.
 *  @return LGN_ILL_INPUT if tstop is not finite or behind the current time. */
int LGNSetStopTime(void *lgn_mem, sunrealtype tstop);

/** Forget the stop time. */
int LGNClearStopTime(void *lgn_mem);

/** q (k = 0, length nq), v (k = 1) or vdot (k = 2, length nv) at any t of
 *  the last step [t_n, t_{n+1}], from the dense output on the group: a
 *  cubic Hermite interpolant in the chart of the step, matching q and v at
 *  both ends, of the order of the method (vdot first order).
 *  @return LGN_SUCCESS, LGN_MEM_NULL, LGN_NO_MALLOC, LGN_BAD_T (t outside
 *          the last step, or no step taken yet), LGN_BAD_K, LGN_ILL_INPUT
 *          (dky NULL or of the wrong length), LGN_GROUP_FAIL. */
int LGNGetDky(void *lgn_mem, sunrealtype t, int k, N_Vector dky);

/** The step size to be tried next (error control) or the fixed h. */
int LGNGetCurrentStep(void *lgn_mem, sunrealtype *hcur);
/** The first step size tried (error control) or the fixed h. */
int LGNGetActualInitStep(void *lgn_mem, sunrealtype *hinused);
/** Steps rejected by the error test. */
int LGNGetNumErrTestFails(void *lgn_mem, long int *netfails);
/** The local error estimate of the last step attempted (length nv). */
int LGNGetEstLocalErrors(void *lgn_mem, N_Vector ele);
/** The error weights of the last step attempted, 1/(atol_i + rtol |s_i|)
 *  (length nv); the error test is the weighted RMS norm of ele. */
int LGNGetErrWeights(void *lgn_mem, N_Vector eweight);
/** The error test's norm of the last step attempted (<= 1: accepted). */
int LGNGetLastErrNorm(void *lgn_mem, sunrealtype *errnorm);

#ifdef __cplusplus
}
#endif

#endif
