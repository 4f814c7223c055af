/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The public side of the consistent initial values (the top layer,
 * doc/architecture.md): LGNCalcIC, LGNGetConsistentIC, LGNSetPerturbedStart.
 * The numerics (projections, check, perturbed start) are lgn_consistent_ic.c's.
 * ---------------------------------------------------------------------------*/

#include "lgn_impl.h"

/* What LGNCalcIC needs of LGNSolve's preparation: the model callbacks and
 * the linear solver. */
static int CheckModel(LGNMem mem, const char *func)
{
  if (mem->mass == NULL || mem->force == NULL) {
    lgnProcessError(mem, LGN_MISSING_FN, __LINE__, func, __FILE__,
                    "No %s function: call %s first.",
                    mem->mass == NULL ? "mass matrix" : "force",
                    mem->mass == NULL ? "LGNSetMassFn" : "LGNSetForceFn");
    return LGN_MISSING_FN;
  }
  if (mem->m > 0 && (mem->constr == NULL || mem->constr_jac == NULL)) {
    lgnProcessError(mem, LGN_MISSING_FN, __LINE__, func, __FILE__,
                    "m = %lld constraints but no constraint function or "
                    "Jacobian.", (long long)mem->m);
    return LGN_MISSING_FN;
  }
  if (mem->G->ops.compose_exp == NULL) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "The Lie group lacks compose_exp.");
    return LGN_ILL_INPUT;
  }
  if (mem->LS == NULL || (mem->A == NULL && !mem->krylov)) {
    lgnProcessError(mem, LGN_NO_LINSOL, __LINE__, func, __FILE__,
                    "No linear solver: call LGNSetLinearSolver first.");
    return LGN_NO_LINSOL;
  }
  return LGN_SUCCESS;
}

/* The model checked (on every rank: the work space is made collectively),
 * the work space, the linear solver and the model matrices. */
static int PrepareModel(LGNMem mem, const char *func)
{
  int flag = lgnAgree(mem, CheckModel(mem, func));
  if (flag == LGN_SUCCESS) flag = lgnAgree(mem, lgnGhostsCheck(mem));
  if (flag == LGN_SUCCESS) flag = lgnAgree(mem, lgnCheckFamilySettings(mem, "LGNCalcIC"));
  /* (a halo on some ranks only is refused where the work space is made:
   * LGNSetHalo drops it, so lgnEnsureWork makes it anew on every rank) */
  /* the independent constraint rows at the current q (lgn_redundancy.c) */
  if (flag == LGN_SUCCESS) flag = lgnRedundancyAnalyse(mem, func);
  if (flag == LGN_SUCCESS) flag = lgnEnsureWork(mem);
  if (flag != LGN_SUCCESS) return flag;
  lgnGhostsRefreshState(mem); /* the owners' state (collective) */
  flag = lgnLsCheck(mem);
  if (flag == LGN_SUCCESS && !mem->mat_done) flag = lgnAllocMatrices(mem);
  return lgnAgree(mem, flag);
}

int LGNCalcIC(void *lgn_mem, int icopt)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  if (icopt != LGN_IC_PROJECT_Q && icopt != LGN_IC_PROJECT_V &&
      icopt != LGN_IC_PROJECT_QV) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "icopt = %d illegal: use LGN_IC_PROJECT_Q, LGN_IC_PROJECT_V or "
              "LGN_IC_PROJECT_QV.", icopt);
    return LGN_ILL_INPUT;
  }
  if (mem->nst > 0) {
    /* it corrects initial values only (a restart would change the state
     * the steps reached) */
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "LGNCalcIC corrects initial values: %ld steps were taken since "
              "LGNInit / LGNReInit. Call LGNReInit with the state to start from, "
              "then LGNCalcIC.", mem->nst);
    return LGN_ILL_INPUT;
  }
  flag = PrepareModel(mem, __func__);
  if (flag != LGN_SUCCESS) return flag;

  flag = lgnProjectIC(mem, icopt);
  if (flag == LGN_SUCCESS && mem->red_nout > 0 && icopt != LGN_IC_PROJECT_V) {
    /* the rows were selected at the q0 given; at the projected one the
     * selection may differ (the q0 given off the constraints can hide
     * their dependence): selected anew, and projected again if it did */
    const long int nsel = mem->red_nsel;
    flag = PrepareModel(mem, __func__);
    if (flag == LGN_SUCCESS && nsel != mem->red_nsel)
      flag = lgnProjectIC(mem, icopt);
  }
  /* the state may have changed: a new start at t_n */
  lgnInvalidate(mem, LGN_CHANGE_STATE);
  if (flag == LGN_SUCCESS) flag = lgnComputeIC(mem);
  if (flag == LGN_SUCCESS) flag = lgnRedundancyCheck(mem, mem->tn, mem->q, __func__);
  if (flag == LGN_RECOVERABLE) {
    LGN_ERROR(mem, LGN_REPTD_CALLBACK_ERR,
              MSG_TIME "a callback failed recoverably in LGNCalcIC.",
              (double)mem->tn);
    flag = LGN_REPTD_CALLBACK_ERR;
  }
  return flag;
}

int LGNGetConsistentIC(void *lgn_mem, N_Vector q0, N_Vector v0)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  if (q0 == NULL && v0 == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "q0 = NULL and v0 = NULL: nothing to return.");
    return LGN_ILL_INPUT;
  }
  if (q0 != NULL) flag = lgnCheckVector(mem, q0, mem->nq, "q0", __func__);
  if (flag == LGN_SUCCESS && v0 != NULL)
    flag = lgnCheckVector(mem, v0, mem->nv, "v0", __func__);
  if (flag != LGN_SUCCESS) return flag;
  if (mem->nst > 0) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "%ld steps taken since LGNInit / LGNReInit: the initial values "
              "are gone (call LGNGetConsistentIC before the first step).",
              mem->nst);
    return LGN_ILL_INPUT;
  }
  if (q0 != NULL) N_VScale(SUN_RCONST(1.0), mem->q, q0);
  if (v0 != NULL) N_VScale(SUN_RCONST(1.0), mem->v, v0);
  return LGN_SUCCESS;
}

int LGNSetPerturbedStart(void *lgn_mem, sunbooleantype on)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (on != SUNTRUE && on != SUNFALSE) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "on = %d illegal: use SUNTRUE or SUNFALSE.", (int)on);
    return LGN_ILL_INPUT;
  }
  /* read at the first step attempt after the initial values; no cache
   * depends on it (lgnInvalidate's table), so nothing to drop */
  mem->pstart_on = on;
  return LGN_SUCCESS;
}
