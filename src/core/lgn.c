/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Lifecycle and the time loop (the top layer, doc/architecture.md):
 *   LGNCreate, LGNInit, LGNReInit, LGNSolve, LGNFree.
 * The record itself (allocation, guards, invalidation) is lgn_mem.c's.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lgn_impl.h"

/* =============================================================================
 * Creation and destruction
 * ===========================================================================*/

void *LGNCreate(SUNContext sunctx)
{
  LGNMem mem;
  if (sunctx == NULL) {
    LGN_ERROR(NULL, LGN_ILL_INPUT, "sunctx = NULL illegal.");
    return NULL;
  }
  mem = (LGNMem)calloc(1, sizeof *mem);
  if (mem == NULL) {
    LGN_ERROR(NULL, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return NULL;
  }
  mem->sunctx = sunctx;
  (void)LGNGenAlphaFromRhoInf(LGN_RHO_INF_DEFAULT, &mem->alpha_m,
                              &mem->alpha_f, &mem->beta, &mem->gamma);
  mem->constr_index = LGN_CONSTR_INDEX3;
  mem->red.mode     = LGN_REDUNDANT_ELIMINATE;
  mem->kinematics   = LGN_KINEMATICS_SIMPLIFIED;
  mem->kin          = lgnKinematicsOps(LGN_KINEMATICS_SIMPLIFIED);
  mem->fam          = lgnFamilyOps(LGN_FAMILY_NEWMARK);
  mem->rtol         = LGN_RTOL_DEFAULT;
  mem->atol         = LGN_ATOL_DEFAULT;
  mem->maxcor       = LGN_MAXCOR_DEFAULT;
  mem->newton_mode  = LGN_NEWTON_FULL;
  mem->msbp         = LGN_MSBP_DEFAULT;
  mem->mxstep       = LGN_MXSTEP_DEFAULT;
  mem->predictor    = LGN_PREDICTOR_ZERO;
  mem->bdf.form     = LGN_BDF_VARIABLE_COEFF;
  mem->klu.own_solves = SUNFALSE;
  mem->ec.step_control = LGN_STEP_FIXED;
  mem->accept_stalls = SUNTRUE;
  mem->ec.epcon        = LGN_EPCON_DEFAULT;
  mem->ec.maxnef       = LGN_MAXNEF_DEFAULT;
  mem->ec.maxncf       = LGN_MAXNCF_DEFAULT;
  mem->kry.eplifac      = LGN_EPLIFAC_DEFAULT;
  mem->out.consistent = SUNTRUE;
  mem->out.project    = LGN_PROJECT_ALL;
  lgnErrSinkInit(&mem->err);
  return mem;
}

void LGNFree(void **lgn_mem)
{
  LGNMem mem;
  if (lgn_mem == NULL || *lgn_mem == NULL) return;
  mem = (LGNMem)(*lgn_mem);
  lgnFreeAll(mem);
  free(mem);
  *lgn_mem = NULL;
}

/* =============================================================================
 * Initialisation
 * ===========================================================================*/

static void ResetCounters(LGNMem mem)
{
  mem->nst = mem->nni = mem->nncf = mem->nstall = mem->nfails = 0;
  mem->nre = mem->ndq = mem->nje = mem->nlsetup = mem->nlsolve = 0;
  mem->nreuse = mem->nrestart = mem->ec.netf = 0;
  mem->stall_warned = SUNFALSE;
  mem->rt.nge = 0;
  mem->ec.err_norm = mem->ec.h0_actual = SUN_RCONST(0.0);
  mem->klu.nfallback = mem->klu.ncopy = mem->klu.nvalues = 0;
  mem->klu.nrefactor = mem->klu.nsolve = 0;
  mem->klu.nnewpattern = mem->klu.nnocopy = 0;
  mem->kry.nli = mem->kry.npe = mem->kry.nps = mem->kry.njtimes = mem->kry.nlcf = 0;
  mem->nls.lambda_noise = mem->nls.lambda_noise_h = SUN_RCONST(0.0);
  mem->hlast = SUN_RCONST(0.0);
  mem->ls.last_flag = 0;
  mem->out.n = 0;
}

/* q0 is an element of the group up to rounding: its normalisation (on a
 * copy, so that a refused q0 leaves the state as it was) is finite. */
static int CheckNormalisable(LGNMem mem, N_Vector q0, const char *func)
{
  /* a plain array, not N_VClone: cloning an MPI vector is collective */
  const size_t nq = (size_t)mem->G->nq;
  sunrealtype *q = (sunrealtype *)malloc(SUNMAX(nq, 1) * sizeof(sunrealtype));
  int ok;
  if (q == NULL) {
    lgnProcessError(mem, LGN_MEM_FAIL, __LINE__, func, __FILE__,
                    "A copy of q0 could not be allocated.");
    return LGN_MEM_FAIL;
  }
  memcpy(q, lgnData(q0), nq * sizeof(sunrealtype));
  lgnGhostsClear(mem, q, NULL); /* ghosts: their owners' values count */
  ok = LGNGroup_Normalize(mem->G, q) == 0 && lgnAllFinite(q, mem->G->nq);
  free(q);
  if (!ok) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "q0 is not an element of the Lie group (it could not be "
                    "normalised: a zero quaternion?).");
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

/* The arguments of LGNInit and LGNReInit: a group set, q0 and v0 of its
 * sizes, a finite t0, a q0 that normalises. All is checked before the
 * state is touched. */
static int CheckInitialState(LGNMem mem, sunrealtype t0, N_Vector q0,
                             N_Vector v0, const char *func)
{
  sunindextype nq_own, nv_own;
  int flag;
  if (mem->G == NULL) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    MSG_NO_GROUP);
    return LGN_ILL_INPUT;
  }
  flag = lgnCheckVector(mem, q0, mem->G->nq, "q0", func);
  if (flag == LGN_SUCCESS) flag = lgnCheckVector(mem, v0, mem->G->nv, "v0", func);
  if (flag != LGN_SUCCESS) return flag;
  lgnGhostsOwnedLengths(mem, &nq_own, &nv_own); /* ghosts' entries: not read */
  if (!lgnAllFinite(N_VGetArrayPointer(q0), nq_own) ||
      !lgnAllFinite(N_VGetArrayPointer(v0), nv_own)) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s has a NaN or Inf entry.",
                    lgnAllFinite(N_VGetArrayPointer(q0), nq_own) ? "v0" : "q0");
    return LGN_ILL_INPUT;
  }
  if (!isfinite(t0)) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "t0 is not finite.");
    return LGN_ILL_INPUT;
  }
  return CheckNormalisable(mem, q0, func);
}

/* Copy the initial state, checked by CheckInitialState (its normalisation
 * cannot fail); shared by LGNInit and LGNReInit. */
static void SetInitialState(LGNMem mem, sunrealtype t0, N_Vector q0,
                            N_Vector v0)
{
  N_VScale(SUN_RCONST(1.0), q0, mem->q);
  N_VScale(SUN_RCONST(1.0), v0, mem->v);
  /* ghosts: placeholders until LGNSolve brings their owners' values */
  lgnGhostsClear(mem, lgnData(mem->q), lgnData(mem->v));
  (void)LGNGroup_Normalize(mem->G, lgnData(mem->q));
  mem->tn         = t0;
  mem->user_vdot0 = SUNFALSE;
  mem->user_a0    = SUNFALSE;
  lgnInvalidate(mem, LGN_CHANGE_STATE);
  ResetCounters(mem);
}

int LGNInit(void *lgn_mem, sunrealtype t0, N_Vector q0, N_Vector v0)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (q0 == NULL || v0 == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "%s = NULL illegal.", q0 == NULL ? "q0" : "v0");
    return LGN_ILL_INPUT;
  }
  /* the ranks of q0 and v0 (a collective call on all of them) */
  lgnParallelFree(&mem->ranks.par);
  flag = lgnParallelCreate(q0, v0, &mem->err, __func__, &mem->ranks.par);
  if (flag != LGN_SUCCESS) return flag;
  if (mem->ranks.halo != NULL && mem->ranks.par == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "Ghost bodies (LGNSetHalo) need a run across ranks: q0 and v0 must "
              "be N_Vector_Parallel or MPIPlusX vectors.");
    return LGN_ILL_INPUT;
  }
  flag = lgnAgree(mem, CheckInitialState(mem, t0, q0, v0, __func__));
  if (flag != LGN_SUCCESS) return flag;

  flag = lgnAgree(mem, lgnAllocState(mem, q0, v0));
  if (flag != LGN_SUCCESS) return flag;
  SetInitialState(mem, t0, q0, v0);
  return LGN_SUCCESS;
}

int LGNReInit(void *lgn_mem, sunrealtype t0, N_Vector q0, N_Vector v0)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  if (mem->G == NULL || mem->G->nq != mem->nq || mem->G->nv != mem->nv) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The Lie group changed size since LGNInit: call LGNInit.");
    flag = LGN_ILL_INPUT;
  } else {
    flag = CheckInitialState(mem, t0, q0, v0, __func__);
  }
  flag = lgnAgree(mem, flag);
  if (flag != LGN_SUCCESS) return flag;
  SetInitialState(mem, t0, q0, v0);
  return LGN_SUCCESS;
}

/* =============================================================================
 * LGNSolve
 * ===========================================================================*/

/* The settings LGNSolve needs: callbacks, step size, tolerances, a linear
 * solver (checked on each rank alone). */
static int CheckSettings(LGNMem mem)
{
  int flag = lgnGhostsCheck(mem);
  if (flag == LGN_SUCCESS) flag = lgnCheckFamilySettings(mem, "LGNSolve");
  if (flag != LGN_SUCCESS) return flag;
  if (mem->mass == NULL) {
    LGN_ERROR(mem, LGN_MISSING_FN, "No mass matrix function: call LGNSetMassFn.");
    return LGN_MISSING_FN;
  }
  if (mem->force == NULL) {
    LGN_ERROR(mem, LGN_MISSING_FN, "No force function: call LGNSetForceFn.");
    return LGN_MISSING_FN;
  }
  if (mem->m > 0 && (mem->constr == NULL || mem->constr_jac == NULL)) {
    LGN_ERROR(mem, LGN_MISSING_FN,
              "m = %lld constraints but no constraint function or Jacobian.",
              (long long)mem->m);
    return LGN_MISSING_FN;
  }
  if (mem->G->ops.compose_exp == NULL || mem->G->ops.tangent_matrix == NULL ||
      mem->G->ops.tangent_apply == NULL ||
      (mem->kin->needs_tangent_dot && mem->G->ops.tangent_dot_apply == NULL) ||
      (mem->kin->needs_tangent_inverse &&
       mem->G->ops.tangent_inverse_apply == NULL)) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The Lie group lacks an operation the %s kinematics needs "
              "(compose_exp, tangent_apply, tangent_matrix%s%s).",
              mem->kin->name,
              mem->kin->needs_tangent_dot ? ", tangent_dot_apply" : "",
              mem->kin->needs_tangent_inverse ? ", tangent_inverse_apply" : "");
    return LGN_ILL_INPUT;
  }
  if (mem->ec.step_control == LGN_STEP_FIXED && !(mem->h > SUN_RCONST(0.0))) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "No step size: call LGNSetStepSize (or LGNSetStepControl with "
              "LGN_STEP_ADAPTIVE).");
    return LGN_ILL_INPUT;
  }
  if (mem->ec.step_control == LGN_STEP_ADAPTIVE) {
    if (!mem->ec.tols_set) {
      LGN_ERROR(mem, LGN_ILL_INPUT,
                "Error control needs tolerances: call LGNSStolerances or "
                "LGNSVtolerances.");
      return LGN_ILL_INPUT;
    }
    if (mem->G->ops.tangent_dot_apply == NULL ||
        mem->G->ops.tangent_inverse_apply == NULL) {
      LGN_ERROR(mem, LGN_ILL_INPUT,
                "Error control needs the Lie group's tangent_dot_apply (error "
                "estimate) and tangent_inverse_apply (output between steps).");
      return LGN_ILL_INPUT;
    }
  }
  if (mem->ec.step_control == LGN_STEP_ADAPTIVE && mem->ec.lambda_errcon && mem->m > 0 &&
      mem->constr_index == LGN_CONSTR_INDEX3) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The multipliers in the error test (LGNSetMultiplierErrorControl) need "
              "LGN_CONSTR_INDEX2 or LGN_CONSTR_GGL: at index 3 they are determined "
              "only to Newton's tolerance ~ atol / h, which grows as h shrinks.");
    return LGN_ILL_INPUT;
  }
  flag = lgnCheckIndex3Damping(mem); /* undamped index 3: refused (lgn_newmark_adapt.c) */
  if (flag != LGN_SUCCESS) return flag;
  if (mem->ls.LS == NULL || (mem->ls.A == NULL && !mem->kry.on)) {
    LGN_ERROR(mem, LGN_NO_LINSOL, "No linear solver: call LGNSetLinearSolver.");
    return LGN_NO_LINSOL;
  }
  return LGN_SUCCESS;
}

/* The settings that decide the steps, compared across the ranks
 * (CheckSameSettings). */
static int CompareSettings(LGNMem mem, sunrealtype tout, int itask)
{
  static const char *names[] = {
    "the method family (LGNSetBDF / LGNSetNewmark ...)", "the BDF order",
    "the BDF form",
    "the step control", "the step size", "rtol", "atol", "the Newton iterations",
    "the Newton mode", "the setups of modified Newton", "mxstep",
    "the constraint index", "the kinematics", "the predictor", "alpha_m",
    "alpha_f", "beta", "gamma", "the perturbed start", "the number of root functions",
    "the kind of linear solver (Krylov or direct)", "eplifac", "epcon",
    "the initial step", "hmin", "hmax", "maxnef", "maxncf", "the stop time",
    "the acceptance of stalls", "the tolerances set", "vector tolerances (LGNSVtolerances)",
    "tout (LGNSolve)", "itask (LGNSolve)", "the current time (a rank left behind)",
    "ghost bodies (LGNSetHalo)", "the consistent outputs (LGNSetConsistentOutputs)",
    "the projected outputs (LGNSetProjectOutputs)",
    "the multipliers in the error test (LGNSetMultiplierErrorControl)",
    "the multipliers' atol (LGNSetMultiplierErrorControl)"};
  const sunrealtype x[] = {
    (sunrealtype)mem->family, (sunrealtype)mem->bdf.maxord, (sunrealtype)mem->bdf.form,
    (sunrealtype)mem->ec.step_control,
    mem->h, mem->rtol, mem->ec.atol_vec != NULL ? -SUN_RCONST(1.0) : mem->atol,
    (sunrealtype)mem->maxcor, (sunrealtype)mem->newton_mode,
    (sunrealtype)mem->msbp, (sunrealtype)mem->mxstep, (sunrealtype)mem->constr_index,
    (sunrealtype)mem->kinematics, (sunrealtype)mem->predictor, mem->alpha_m, mem->alpha_f,
    mem->beta, mem->gamma, (sunrealtype)mem->pstart_on, (sunrealtype)mem->rt.nrtfn,
    (sunrealtype)mem->kry.on, mem->kry.eplifac, mem->ec.epcon, mem->ec.h0_user, mem->ec.hmin, mem->ec.hmax,
    (sunrealtype)mem->ec.maxnef, (sunrealtype)mem->ec.maxncf,
    mem->tstop_set ? mem->tstop : -SUN_BIG_REAL, (sunrealtype)mem->accept_stalls,
    (sunrealtype)mem->ec.tols_set, (sunrealtype)(mem->ec.atol_vec != NULL), tout,
    (sunrealtype)itask, mem->tn, (sunrealtype)(mem->ranks.halo != NULL),
    (sunrealtype)mem->out.consistent, (sunrealtype)mem->out.project,
    (sunrealtype)mem->ec.lambda_errcon, mem->ec.lambda_errcon ? mem->ec.lambda_atol : SUN_RCONST(0.0)};
  int first;
  _Static_assert(sizeof names / sizeof names[0] == sizeof x / sizeof x[0],
                 "a name for each setting");
  _Static_assert(sizeof x / sizeof x[0] <= LGN_PARALLEL_MAXSAME,
                 "lgnParallelSame compares them all");
  if (lgnParallelSame(mem->ranks.par, x, (int)(sizeof x / sizeof x[0]), &first))
    return LGN_SUCCESS;
  LGN_ERROR(mem, LGN_ILL_INPUT,
            "%s differs between the ranks: the settings of the method must be the "
            "same on every rank.", names[first]);
  return LGN_ILL_INPUT;
}

/* Across ranks the settings that decide the steps must be the same on
 * every rank (else the ranks would part ways in a collective): refused
 * with LGN_ILL_INPUT on all, naming the first that differs. */
static int CheckSameSettings(LGNMem mem, sunrealtype tout, int itask)
{
  if (mem->ranks.par == NULL) return LGN_SUCCESS; /* one process: nothing to compare */
  return CompareSettings(mem, tout, itask);
}

/* Everything LGNSolve needs before the first step: the settings, work
 * space and consistent initial values. Across ranks, each stage is agreed
 * before the next (which may be collective), and what one rank must make
 * (work space, initial values) every rank makes. */
static int CheckReadyToSolve(LGNMem mem, sunrealtype tout, int itask)
{
  int flag = lgnAgree(mem, CheckSettings(mem));
  if (flag == LGN_SUCCESS) flag = CheckSameSettings(mem, tout, itask);
  /* before the model is evaluated (the redundancy analysis below) */
  if (flag == LGN_SUCCESS && mem->kry.on) flag = lgnAgree(mem, lgnKrylovCheckPreconditioner(mem));
  if (flag != LGN_SUCCESS) return flag;
  /* Phi_t on any rank: every rank takes part in its error norm */
  mem->ranks.any_constr_time =
      lgnMaxAll(mem, mem->constr_time != NULL ? SUN_RCONST(1.0) : SUN_RCONST(0.0)) >
      SUN_RCONST(0.0);
  /* a new start: the independent constraint rows at q0 (lgn_redundancy.c;
   * one process only, so no agreement is needed) */
  if (!mem->ic_done) flag = lgnRedundancyAnalyse(mem, "LGNSolve");
  /* a direct solver fits before the work arrays are (re)made: a refusal
   * leaves the state and its getters as they were (fuzz finding 11); a
   * Krylov solver is set up on the work vectors, after them */
  if (flag == LGN_SUCCESS && !mem->kry.on) {
    lgnSetAlgebraicSize(mem);
    flag = lgnLsCheck(mem);
  }
  if (flag == LGN_SUCCESS) flag = lgnEnsureWork(mem);
  if (flag == LGN_SUCCESS && mem->rt.nrtfn > 0)
    flag = lgnAgree(mem, lgnAllocRootVectors(mem));
  if (flag == LGN_SUCCESS && mem->ec.atol_vec != NULL) {
    /* vector tolerances: the multipliers' atol is the mean of all ranks' */
    sunrealtype mean[2] = {SUN_RCONST(0.0), SUN_RCONST(0.0)};
    sunindextype i;
    for (i = 0; i < mem->ranks.nv_own; i++) mean[0] += mem->ec.atol_vec[i]; /* not the ghosts */
    mean[1] = (sunrealtype)mem->ranks.nv_own;
    lgnSumAll(mem, mean, 2);
    mem->atol = mean[0] / SUNMAX(mean[1], SUN_RCONST(1.0));
  }
  if (flag != LGN_SUCCESS) return flag;
  /* ghost bodies: the owners' state (q0 and v0's ghost entries are not
   * read; the state changes on every rank alike from here on) */
  lgnGhostsRefreshState(mem);
  if (mem->kry.on) flag = lgnLsCheck(mem);
  if (flag == LGN_SUCCESS && !mem->mat_done) flag = lgnAllocMatrices(mem);
  flag = lgnAgree(mem, flag);
  if (flag != LGN_SUCCESS) return flag;
  if (lgnMaxAll(mem, mem->ic_done ? SUN_RCONST(0.0) : SUN_RCONST(1.0)) > SUN_RCONST(0.0)) {
    flag = lgnInitialConditions(mem);
    if (flag == LGN_RECOVERABLE) {
      /* no smaller step can help the initial values */
      LGN_ERROR(mem, LGN_REPTD_CALLBACK_ERR,
                MSG_TIME "a callback failed recoverably while the consistent "
                "initial values were computed.", (double)mem->tn);
      flag = LGN_REPTD_CALLBACK_ERR;
    }
    if (flag == LGN_SUCCESS) flag = lgnRedundancyCheck(mem, mem->tn, mem->q, "LGNSolve");
    if (flag != LGN_SUCCESS) return flag;
  }
  return LGN_SUCCESS;
}

static void CopyOut(LGNMem mem, sunrealtype *tret, N_Vector q, N_Vector v)
{
  *tret = mem->tn;
  N_VScale(SUN_RCONST(1.0), mem->q, q);
  N_VScale(SUN_RCONST(1.0), mem->v, v);
}

/* The output at t of the last step: the state itself at its end, else the
 * dense output (lgn_dense_output.c). */
static int OutputAt(LGNMem mem, sunrealtype t, sunrealtype *tret, N_Vector q,
                    N_Vector v)
{
  int flag;
  if (t == mem->tn) {
    CopyOut(mem, tret, q, v);
    return LGN_SUCCESS;
  }
  *tret = t;
  flag = lgnDenseOutput(mem, t, 0, lgnData(q));
  if (flag == LGN_SUCCESS) flag = lgnDenseOutput(mem, t, 1, lgnData(v));
  flag = lgnAgree(mem, flag);
  return flag;
}

/* LGNSolve with error control, IDA's semantics: LGN_NORMAL steps past tout
 * and interpolates there (a stop time is landed on exactly and returns
 * LGN_TSTOP_RETURN); LGN_ONE_STEP takes one step. */
static int SolveAdaptive(LGNMem mem, sunrealtype tout, sunrealtype *tret,
                         N_Vector q, N_Vector v, int itask)
{
  const sunrealtype troundoff = SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF *
                                SUNMAX(fabs(mem->tn), fabs(tout));
  long int nstloc = 0;
  int flag = LGN_SUCCESS;

  /* tout inside the last step (already passed): interpolate */
  if (itask == LGN_NORMAL && tout < mem->tn - troundoff) {
    if (mem->dense.valid && tout >= mem->dense.tprev - troundoff)
      return OutputAt(mem, SUNMAX(tout, mem->dense.tprev), tret, q, v);
    LGN_ERROR(mem, LGN_BAD_TOUT,
              "tout = %.17g is behind the last step [%.17g, %.17g].",
              (double)tout, (double)(mem->dense.valid ? mem->dense.tprev : mem->tn),
              (double)mem->tn);
    CopyOut(mem, tret, q, v);
    return LGN_BAD_TOUT;
  }
  if (mem->tstop_set && mem->tstop < mem->tn - troundoff) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The stop time %.17g is behind the current time t = %.17g.",
              (double)mem->tstop, (double)mem->tn);
    CopyOut(mem, tret, q, v);
    return LGN_ILL_INPUT;
  }

  for (;;) {
    /* at the stop time: return there (and forget it, as IDA does) */
    if (mem->tstop_set && fabs(mem->tn - mem->tstop) <= troundoff &&
        (itask == LGN_ONE_STEP || nstloc > 0 || tout >= mem->tstop - troundoff)) {
      mem->tn        = mem->tstop;
      mem->tstop_set = SUNFALSE;
      CopyOut(mem, tret, q, v);
      return LGN_TSTOP_RETURN;
    }
    if (itask == LGN_NORMAL && mem->tn >= tout - troundoff) break;
    if (itask == LGN_ONE_STEP && nstloc > 0) break;
    if (mem->mxstep > 0 && nstloc >= mem->mxstep) {
      LGN_ERROR(mem, LGN_TOO_MUCH_WORK,
                MSG_TIME "mxstep = %ld steps taken before reaching tout.",
                (double)mem->tn, mem->mxstep);
      flag = LGN_TOO_MUCH_WORK;
      break;
    }
    flag = mem->fam->adaptive_step(mem, tout);
    if (flag == LGN_SUCCESS) flag = lgnRedundancyCheck(mem, mem->tn, mem->q, "LGNSolve");
    if (flag != LGN_SUCCESS) break;
    nstloc++;
    if (mem->rt.nrtfn > 0) { /* events in the step (lgn_root.c) */
      flag = lgnRootAfterStep(mem, tout, itask, tret, q, v);
      if (flag == LGN_ROOT_RETURN) return flag;
      if (flag != LGN_SUCCESS) break;
    }
  }
  if (flag == LGN_SUCCESS && itask == LGN_NORMAL && mem->tn > tout)
    return OutputAt(mem, tout, tret, q, v);
  CopyOut(mem, tret, q, v);
  return flag;
}

/* A warning, once per object, when most steps of a solve were accepted
 * with stalled multipliers (lgn_newton.c): the results then rest on the
 * multipliers being at their roundoff level, not at the tolerance. */
static void WarnStalls(LGNMem mem, long int nst0, long int nstall0)
{
  const long int steps = mem->nst - nst0, stalls = mem->nstall - nstall0;
  if (mem->stall_warned || steps < 10 || 2 * stalls < steps) return;
  mem->stall_warned = SUNTRUE;
  LGN_ERROR(mem, LGN_WARNING,
            MSG_TIME "%ld of the last %ld steps were accepted with the "
            "multipliers' Newton corrections stalled above the tolerance, at "
            "their roundoff level (the configuration converged). The "
            "multipliers are only as accurate as the conditioning allows; "
            "with LGNSetAcceptStalls(mem, SUNFALSE) Newton iterates until the "
            "tolerance is met, or fails.",
            (double)mem->tn, stalls, steps);
}

static int Solve(void *lgn_mem, sunrealtype tout, sunrealtype *tret, N_Vector q,
                 N_Vector v, int itask);
static int SolveFixed(LGNMem mem, sunrealtype tout, sunrealtype *tret, N_Vector q,
                      N_Vector v, int itask);

int LGNSolve(void *lgn_mem, sunrealtype tout, sunrealtype *tret, N_Vector q,
             N_Vector v, int itask)
{
  LGNMem mem = (LGNMem)lgn_mem;
  const long int nst0 = mem != NULL ? mem->nst : 0, nstall0 = mem != NULL ? mem->nstall : 0;
  int flag = Solve(lgn_mem, tout, tret, q, v, itask);
  if (mem != NULL && mem->malloc_done) WarnStalls(mem, nst0, nstall0);
  if (mem == NULL || !mem->malloc_done) return flag;
  if (flag == LGN_SUCCESS || flag == LGN_TSTOP_RETURN || flag == LGN_ROOT_RETURN) {
    /* the output: projected, with its consistent vdot and lambda (lgn_output.c) */
    const int oflag = lgnOutputAt(mem, *tret, q, v);
    if (oflag != LGN_SUCCESS) {
      /* the output failed (a callback, a singular matrix): the state at tn,
       * as after any failure (q, v may hold a part of the projection) */
      flag = oflag;
      CopyOut(mem, tret, q, v);
      if (mem->nst != nst0) mem->out.lvalid = SUNFALSE;
      if (mem->out.lvalid && *tret == mem->out.lt) {
        N_VScale(SUN_RCONST(1.0), mem->out.lq, q);
        N_VScale(SUN_RCONST(1.0), mem->out.lv, v);
      }
    }
  } else if (mem->nst != nst0) {
    mem->out.valid  = SUNFALSE; /* steps taken, then a failure: the state at tn */
    mem->out.lvalid = SUNFALSE;
  } else if (mem->out.lvalid && tret != NULL && *tret == mem->out.lt && q != NULL &&
             v != NULL && lgnLocalLength(q) == lgnLocalLength(mem->out.lq) &&
             lgnLocalLength(v) == lgnLocalLength(mem->out.lv)) {
    /* no step taken: the outputs as the last (projected) output returned them */
    N_VScale(SUN_RCONST(1.0), mem->out.lq, q);
    N_VScale(SUN_RCONST(1.0), mem->out.lv, v);
  }
  return flag;
}

/* LGNSolve's arguments (on this rank): tret, q and v, itask, a finite tout
 * not behind the last step (LGN_BAD_TOUT: checked before anything is
 * computed, so a refused call changes nothing; a tout inside the last step
 * is interpolated, and an event may have returned there). */
static int CheckSolveArguments(LGNMem mem, sunrealtype tout, sunrealtype *tret, N_Vector q,
                               N_Vector v, int itask)
{
  int flag;
  if (tret == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "tret = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  flag = lgnCheckVector(mem, q, mem->nq, "q", "LGNSolve");
  if (flag == LGN_SUCCESS) flag = lgnCheckVector(mem, v, mem->nv, "v", "LGNSolve");
  if (flag != LGN_SUCCESS) return flag;
  if (itask != LGN_NORMAL && itask != LGN_ONE_STEP) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "itask = %d illegal: use LGN_NORMAL or LGN_ONE_STEP.", itask);
    return LGN_ILL_INPUT;
  }
  if (!isfinite(tout)) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "tout is not finite.");
    return LGN_ILL_INPUT;
  }
  if (tout < (mem->dense.valid ? mem->dense.tprev : mem->tn) -
                 SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * SUNMAX(fabs(mem->tn), fabs(tout))) {
    LGN_ERROR(mem, LGN_BAD_TOUT,
              "tout = %.17g is behind the current time t = %.17g%s.", (double)tout,
              (double)mem->tn,
              itask == LGN_ONE_STEP ? " (LGN_ONE_STEP steps forward: give a tout ahead of t)"
                                    : "");
    return LGN_BAD_TOUT;
  }
  return LGN_SUCCESS;
}

static int Solve(void *lgn_mem, sunrealtype tout, sunrealtype *tret, N_Vector q,
                 N_Vector v, int itask)
{
  LGNMem mem;
  int local, flag = lgnAccessMem(lgn_mem, "LGNSolve", &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  /* the arguments, on each rank, then agreed: across ranks a refused call
   * must return on every rank (the rest of LGNSolve is collective) */
  local = CheckSolveArguments(mem, tout, tret, q, v, itask);
  flag  = lgnAgree(mem, local);
  if (flag != LGN_SUCCESS) {
    if (local == LGN_SUCCESS || local == LGN_BAD_TOUT) CopyOut(mem, tret, q, v);
    return flag;
  }
  flag = CheckReadyToSolve(mem, tout, itask);
  if (flag == LGN_SUCCESS && mem->rt.nrtfn > 0) {
    /* events: start, or the rest of the last step after a root */
    sunbooleantype done = SUNFALSE;
    flag = lgnRootSolveStart(mem, tout, itask, tret, q, v, &done);
    if (flag == LGN_ROOT_RETURN || (flag == LGN_SUCCESS && done)) return flag;
  }
  if (flag != LGN_SUCCESS) {
    CopyOut(mem, tret, q, v);
    return flag;
  }

  if (mem->ec.step_control == LGN_STEP_ADAPTIVE)
    return SolveAdaptive(mem, tout, tret, q, v, itask);

  return SolveFixed(mem, tout, tret, q, v, itask);
}

/* The stop time reached (within roundoff tr): t = tstop exactly, the stop
 * time forgotten (as IDA does), LGN_TSTOP_RETURN. */
static int StopTimeReturn(LGNMem mem, sunrealtype tr, sunrealtype *tret, N_Vector q,
                          N_Vector v)
{
  if (!mem->tstop_set || fabs(mem->tn - mem->tstop) > tr) return LGN_SUCCESS;
  mem->tn        = mem->tstop;
  mem->tstop_set = SUNFALSE;
  CopyOut(mem, tret, q, v);
  return LGN_TSTOP_RETURN;
}

/* LGNSolve with fixed steps of h. LGN_NORMAL: the last step lands exactly
 * on tout (BDF: steps past it and interpolates); LGN_ONE_STEP: one step.
 * A stop time is never stepped past: the step that would cross it is
 * shortened to end on it (BDF too: its variable coefficients take the
 * short step), and LGNSolve returns LGN_TSTOP_RETURN there, as with error
 * control. */
static int SolveFixed(LGNMem mem, sunrealtype tout, sunrealtype *tret, N_Vector q,
                      N_Vector v, int itask)
{
  sunrealtype troundoff, remaining, hstep, tend;
  sunbooleantype stop;
  long int nstloc = 0;
  int flag = LGN_SUCCESS;

  troundoff = SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF *
              SUNMAX(SUNMAX(fabs(mem->tn), fabs(tout)),
                     mem->tstop_set ? fabs(mem->tstop) : SUN_RCONST(0.0));
  if (mem->tstop_set && mem->tstop < mem->tn - troundoff) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The stop time %.17g is behind the current time t = %.17g (set "
              "before LGNReInit?): set another one or call LGNClearStopTime.",
              (double)mem->tstop, (double)mem->tn);
    CopyOut(mem, tret, q, v);
    return LGN_ILL_INPUT;
  }

  if (itask == LGN_ONE_STEP) {
    flag = StopTimeReturn(mem, troundoff, tret, q, v);
    if (flag != LGN_SUCCESS) return flag;
    hstep = mem->h;
    /* the step that would cross the stop time (or end within 1e-6 h of
     * it) ends on it */
    stop = mem->tstop_set &&
           mem->tn + mem->h * (SUN_RCONST(1.0) + SUN_RCONST(1.0e-6)) >= mem->tstop;
    if (stop) hstep = mem->tstop - mem->tn;
    flag = mem->fam->step(mem, hstep);
    if (flag == LGN_SUCCESS && stop) mem->tn = mem->tstop; /* exact arrival */
    if (flag == LGN_SUCCESS) flag = lgnRedundancyCheck(mem, mem->tn, mem->q, "LGNSolve");
    if (flag == LGN_SUCCESS && mem->rt.nrtfn > 0) {
      flag = lgnRootAfterStep(mem, tout, itask, tret, q, v);
      if (flag == LGN_ROOT_RETURN) return flag;
    }
    if (flag == LGN_SUCCESS && stop) return StopTimeReturn(mem, troundoff, tret, q, v);
    CopyOut(mem, tret, q, v);
    return flag;
  }

  /* LGN_NORMAL: fixed steps; the last one lands exactly on tout (or on a
   * stop time before it). A remainder up to 1e-6 h longer than h is taken
   * as one step, so that roundoff in t never produces a tiny extra step. */
  if (tout < mem->tn - troundoff && mem->dense.valid && tout >= mem->dense.tprev)
    return OutputAt(mem, tout, tret, q, v); /* inside the last step (after a root) */
  if (tout < mem->tn - troundoff) {
    LGN_ERROR(mem, LGN_BAD_TOUT,
              "tout = %.17g is behind the current time t = %.17g.",
              (double)tout, (double)mem->tn);
    CopyOut(mem, tret, q, v);
    return LGN_BAD_TOUT;
  }
  stop = mem->tstop_set && mem->tstop < tout - troundoff;
  tend = stop ? mem->tstop : tout;
  while (tend - mem->tn > troundoff) {
    if (mem->mxstep > 0 && nstloc >= mem->mxstep) {
      LGN_ERROR(mem, LGN_TOO_MUCH_WORK,
                MSG_TIME "mxstep = %ld steps taken before reaching tout.",
                (double)mem->tn, mem->mxstep);
      flag = LGN_TOO_MUCH_WORK;
      break;
    }
    remaining = tend - mem->tn;
    hstep     = (remaining <= mem->h * (SUN_RCONST(1.0) + SUN_RCONST(1.0e-6)))
                    ? remaining
                    : mem->h;
    /* BDF keeps its grid (a shortened step would enter its history with
     * an arbitrary step ratio): it steps past tout and interpolates there,
     * but never past a stop time */
    if (mem->fam->keeps_grid && !stop &&
        remaining < mem->h * (SUN_RCONST(1.0) - SUN_RCONST(1.0e-6)))
      hstep = mem->h;
    flag = mem->fam->step(mem, hstep);
    if (flag == LGN_SUCCESS) flag = lgnRedundancyCheck(mem, mem->tn, mem->q, "LGNSolve");
    if (flag != LGN_SUCCESS) break;
    if (hstep == remaining) mem->tn = tend; /* exact arrival */
    nstloc++;
    if (mem->rt.nrtfn > 0) { /* events in the step (lgn_root.c) */
      flag = lgnRootAfterStep(mem, tout, itask, tret, q, v);
      if (flag == LGN_ROOT_RETURN) return flag;
      if (flag != LGN_SUCCESS) break;
    }
  }
  if (flag == LGN_SUCCESS && stop) return StopTimeReturn(mem, troundoff, tret, q, v);
  if (flag == LGN_SUCCESS && mem->tn > tout + troundoff)
    return OutputAt(mem, tout, tret, q, v); /* BDF: past tout */
  CopyOut(mem, tret, q, v);
  return flag;
}
