/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Optional inputs (LGNSet*), outputs (LGNGet*), LGNPrintAllStats and
 * LGNGetReturnFlagName. Every function checks the memory block first, then
 * each argument, and names the bad argument in its message.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lgn_impl.h"
#include "lgn_methods.h"
#include "lgn_sparse.h"

/* Common preamble: the memory block must exist. */
#define ACCESS_MEM(lgn_mem, mem)                             \
  do {                                                       \
    int access_flag_ = lgnAccessMem(lgn_mem, __func__, &mem); \
    if (access_flag_ != LGN_SUCCESS) return access_flag_;    \
  } while (0)

/* Common preamble of functions that need LGNInit. */
#define ACCESS_MALLOC(lgn_mem, mem)                          \
  do {                                                       \
    ACCESS_MEM(lgn_mem, mem);                                \
    if (!mem->malloc_done) {                                 \
      LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);          \
      return LGN_NO_MALLOC;                                  \
    }                                                        \
  } while (0)

/* =============================================================================
 * Model description
 * ===========================================================================*/

int LGNSetGroup(void *lgn_mem, LGNGroup G)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (G == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "G = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  if (G->nq < 1 || G->nv < 1) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "The Lie group has nq = %lld, nv = %lld.",
              (long long)G->nq, (long long)G->nv);
    return LGN_ILL_INPUT;
  }
  if (mem->malloc_done && (G->nq != mem->nq || G->nv != mem->nv)) {
    /* another size: the state given to LGNInit would not fit it (refused,
     * the state kept; a new problem starts with a new LGNCreate) */
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "G has nq = %lld, nv = %lld, but the state given to LGNInit has nq = "
              "%lld, nv = %lld: a group of another size after LGNInit is refused "
              "(create a new integrator with LGNCreate for it).",
              (long long)G->nq, (long long)G->nv, (long long)mem->nq, (long long)mem->nv);
    return LGN_ILL_INPUT;
  }
  if (G != mem->G) {
    /* the block table, T's storage, the patterns and the matrices follow
     * the group: rebuilt at the next LGNSolve, which also computes
     * consistent accelerations and multipliers anew at the current state */
    mem->G = G;
    lgnInvalidate(mem, LGN_CHANGE_GROUP);
  }
  return LGN_SUCCESS;
}

int LGNSetUserData(void *lgn_mem, void *user_data)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->user_data = user_data;
  /* the callbacks, the mass function too, may answer otherwise */
  lgnInvalidate(mem, LGN_CHANGE_MODEL | LGN_CHANGE_MASS);
  return LGN_SUCCESS;
}

int LGNSetMassFn(void *lgn_mem, LGNMassFn mass)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (mass == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "mass = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  mem->mass = mass;
  lgnInvalidate(mem, LGN_CHANGE_MASS);
  return LGN_SUCCESS;
}

int LGNSetForceFn(void *lgn_mem, LGNForceFn force)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (force == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "force = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  mem->force = force;
  lgnInvalidate(mem, LGN_CHANGE_MODEL);
  return LGN_SUCCESS;
}

int LGNSetConstraints(void *lgn_mem, sunindextype m, LGNConstrFn phi,
                      LGNConstrJacFn B)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (m < 0 || m > LGN_MAX_CONSTRAINTS) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "m = %lld illegal: must lie in [0, %lld].",
              (long long)m, (long long)LGN_MAX_CONSTRAINTS);
    return LGN_ILL_INPUT;
  }
  if (m > 0 && (phi == NULL || B == NULL)) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "%s = NULL illegal with m = %lld constraints.",
              phi == NULL ? "phi" : "B", (long long)m);
    return LGN_ILL_INPUT;
  }
  /* a new m: the work space is reallocated at the next LGNSolve (and the
   * redundant rows are selected anew there, lgn_redundancy.c) */
  lgnInvalidate(mem, m != mem->m || mem->red_nout > 0 ? LGN_CHANGE_SIZES : LGN_CHANGE_MODEL);
  mem->m          = m;
  mem->m_user     = m;
  mem->red_nout   = 0;
  mem->constr     = phi;
  mem->constr_jac = B;
  return LGN_SUCCESS;
}

int LGNSetRedundantConstraints(void *lgn_mem, int mode)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (mode != LGN_REDUNDANT_ELIMINATE && mode != LGN_REDUNDANT_REFUSE) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "mode = %d illegal: use LGN_REDUNDANT_ELIMINATE or LGN_REDUNDANT_REFUSE.",
              mode);
    return LGN_ILL_INPUT;
  }
  mem->red_mode = mode; /* acts at the next start (lgnRedundancyAnalyse) */
  return LGN_SUCCESS;
}

int LGNSetStiffnessFn(void *lgn_mem, LGNStiffnessFn K)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->stiffness = K;
  lgnInvalidate(mem, LGN_CHANGE_MODEL);
  return LGN_SUCCESS;
}

int LGNSetDampingFn(void *lgn_mem, LGNDampingFn C)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->damping = C;
  lgnInvalidate(mem, LGN_CHANGE_MODEL);
  return LGN_SUCCESS;
}

int LGNSetCurvatureFn(void *lgn_mem, LGNCurvatureFn Z)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->curvature = Z;
  lgnInvalidate(mem, LGN_CHANGE_MODEL);
  return LGN_SUCCESS;
}

int LGNSetConstraintTimeFn(void *lgn_mem, LGNConstrTimeFn phit)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->constr_time = phit;
  lgnInvalidate(mem, LGN_CHANGE_MODEL);
  return LGN_SUCCESS;
}

int LGNSetConstraintForceFn(void *lgn_mem, LGNConstrForceFn F)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->constr_force = F;
  lgnInvalidate(mem, LGN_CHANGE_MODEL);
  return LGN_SUCCESS;
}

int LGNSetMassConstant(void *lgn_mem, sunbooleantype constant)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->mass_constant = constant ? SUNTRUE : SUNFALSE;
  lgnInvalidate(mem, LGN_CHANGE_MASS);
  return LGN_SUCCESS;
}

/* =============================================================================
 * Method and solver settings
 * ===========================================================================*/

int LGNSetStepSize(void *lgn_mem, sunrealtype h)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  /* the step divides by h^2 (beta', the scaling of the equations): h^2
   * and 1/h^2 must be normal finite numbers */
  if (!(h > SUN_RCONST(0.0)) || !isfinite(h) || !(h * h >= SUN_SMALL_REAL) ||
      !(h * h <= SUN_BIG_REAL)) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "h = %g illegal: the step size must be > 0 with h^2 and 1/h^2 "
              "finite (about 1e-154 < h < 1e154).", (double)h);
    return LGN_ILL_INPUT;
  }
  mem->h = h;
  return LGN_SUCCESS;
}

static int SetParams(LGNMem mem, sunrealtype am, sunrealtype af,
                     sunrealtype beta, sunrealtype gamma, const char *func)
{
  const char *why = NULL;
  if (lgnCheckMethodParams(am, af, beta, gamma, &why) != LGN_SUCCESS) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "Illegal method parameters (alpha_m = %g, alpha_f = %g, "
                    "beta = %g, gamma = %g): %s.", (double)am, (double)af,
                    (double)beta, (double)gamma, why);
    return LGN_ILL_INPUT;
  }
  mem->alpha_m = am;
  mem->alpha_f = af;
  mem->beta    = beta;
  mem->gamma   = gamma;
  mem->family  = LGN_FAMILY_NEWMARK; /* (back) to the Newmark family */
  mem->kin     = lgnKinematicsOps(mem->kinematics);
  lgnInvalidate(mem, LGN_CHANGE_METHOD);
  return LGN_SUCCESS;
}

int LGNSetBDF(void *lgn_mem, int maxord)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (maxord < 1 || maxord > LGN_BDF_MAXORD) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "maxord = %d illegal: BDF orders are 1 to %d.",
              maxord, LGN_BDF_MAXORD);
    return LGN_ILL_INPUT;
  }
  mem->family     = LGN_FAMILY_BDF;
  mem->bdf_maxord = maxord;
  mem->kin        = lgnBDFOps();
  lgnInvalidate(mem, LGN_CHANGE_METHOD);
  return LGN_SUCCESS;
}

int LGNSetBDFForm(void *lgn_mem, int form)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (form != LGN_BDF_VARIABLE_COEFF && form != LGN_BDF_FIXED_LEADING) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "form = %d illegal: use LGN_BDF_VARIABLE_COEFF or "
              "LGN_BDF_FIXED_LEADING.", form);
    return LGN_ILL_INPUT;
  }
  if (lgnRefuseOtherFamily(mem, LGN_FAMILY_BDF, form == LGN_BDF_VARIABLE_COEFF, __func__) !=
      LGN_SUCCESS)
    return LGN_ILL_INPUT;
  mem->bdf_form = form;
  lgnInvalidate(mem, LGN_CHANGE_METHOD);
  return LGN_SUCCESS;
}

int LGNGetCurrentOrder(void *lgn_mem, int *order)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (order == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "order = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  *order = mem->family == LGN_FAMILY_BDF ? mem->bdf_order : 2;
  return LGN_SUCCESS;
}

int LGNGetLastOrder(void *lgn_mem, int *order)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (order == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "order = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  *order = mem->family == LGN_FAMILY_BDF ? mem->bdf_last_order : 2;
  return LGN_SUCCESS;
}

int LGNGetNumStepsAtOrder(void *lgn_mem, long int nsteps[LGN_BDF_MAX_ORDER + 1])
{
  LGNMem mem;
  int k;
  ACCESS_MEM(lgn_mem, mem);
  if (nsteps == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "nsteps = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  for (k = 0; k <= LGN_BDF_MAXORD; k++) nsteps[k] = mem->bdf_nord[k];
  return LGN_SUCCESS;
}

int LGNSetNewmark(void *lgn_mem, sunrealtype beta, sunrealtype gamma)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (!(beta > SUN_RCONST(0.0) && beta <= SUN_RCONST(0.5))) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "beta = %g illegal: Newmark needs 0 < beta <= 1/2.",
              (double)beta);
    return LGN_ILL_INPUT;
  }
  if (!(gamma > SUN_RCONST(0.0) && gamma <= SUN_RCONST(1.0))) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "gamma = %g illegal: Newmark needs 0 < gamma <= 1.",
              (double)gamma);
    return LGN_ILL_INPUT;
  }
  return SetParams(mem, SUN_RCONST(0.0), SUN_RCONST(0.0), beta, gamma, __func__);
}

int LGNSetGenAlpha(void *lgn_mem, sunrealtype rho_inf)
{
  LGNMem mem;
  sunrealtype am, af, beta, gamma;
  ACCESS_MEM(lgn_mem, mem);
  if (!(rho_inf >= SUN_RCONST(0.0) && rho_inf <= SUN_RCONST(1.0))) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "rho_inf = %g illegal: it must lie in [0, 1].",
              (double)rho_inf);
    return LGN_ILL_INPUT;
  }
  (void)LGNGenAlphaFromRhoInf(rho_inf, &am, &af, &beta, &gamma);
  return SetParams(mem, am, af, beta, gamma, __func__);
}

int LGNSetGenAlphaParams(void *lgn_mem, sunrealtype alpha_m, sunrealtype alpha_f,
                         sunrealtype beta, sunrealtype gamma)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  return SetParams(mem, alpha_m, alpha_f, beta, gamma, __func__);
}

int LGNSetConstraintIndex(void *lgn_mem, int index)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (index != LGN_CONSTR_INDEX3 && index != LGN_CONSTR_INDEX2 && index != LGN_CONSTR_GGL) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "index = %d illegal: use LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2 or "
              "LGN_CONSTR_GGL.", index);
    return LGN_ILL_INPUT;
  }
  /* GGL has m more unknowns (mu): the Newton vectors are made anew */
  if ((index == LGN_CONSTR_GGL) != (mem->constr_index == LGN_CONSTR_GGL)) {
    mem->constr_index = index;
    lgnInvalidate(mem, LGN_CHANGE_SIZES | LGN_CHANGE_METHOD);
    return LGN_SUCCESS;
  }
  mem->constr_index = index;
  lgnInvalidate(mem, LGN_CHANGE_METHOD);
  return LGN_SUCCESS;
}

int LGNSetKinematics(void *lgn_mem, int kinematics)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (kinematics != LGN_KINEMATICS_SIMPLIFIED &&
      kinematics != LGN_KINEMATICS_EXACT && kinematics != LGN_KINEMATICS_SIGMA) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "kinematics = %d illegal: use LGN_KINEMATICS_SIMPLIFIED, "
              "LGN_KINEMATICS_EXACT or LGN_KINEMATICS_SIGMA.", kinematics);
    return LGN_ILL_INPUT;
  }
  if (lgnRefuseOtherFamily(mem, LGN_FAMILY_NEWMARK, kinematics == LGN_KINEMATICS_SIMPLIFIED,
                           __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  mem->kinematics = kinematics;
  if (mem->family == LGN_FAMILY_NEWMARK) mem->kin = lgnKinematicsOps(kinematics);
  lgnInvalidate(mem, LGN_CHANGE_METHOD);
  return LGN_SUCCESS;
}

int LGNSetPredictor(void *lgn_mem, int predictor)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (predictor != LGN_PREDICTOR_ZERO && predictor != LGN_PREDICTOR_EXTRAPOLATE) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "predictor = %d illegal: use LGN_PREDICTOR_ZERO or "
              "LGN_PREDICTOR_EXTRAPOLATE.", predictor);
    return LGN_ILL_INPUT;
  }
  if (lgnRefuseOtherFamily(mem, LGN_FAMILY_NEWMARK, predictor == LGN_PREDICTOR_ZERO, __func__) !=
      LGN_SUCCESS)
    return LGN_ILL_INPUT;
  mem->predictor = predictor;
  return LGN_SUCCESS;
}

/* A tolerance: 0 (the default) or a finite normal number; below the
 * smallest normal number (e.g. 4.9e-324) the error weights 1/tol overflow,
 * and the error norms become inf or NaN. */
static int CheckTolerance(LGNMem mem, sunrealtype tol, const char *name, const char *func)
{
  if (!(tol >= SUN_RCONST(0.0)) || !isfinite(tol)) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s = %g illegal: must be >= 0.", name, (double)tol);
    return LGN_ILL_INPUT;
  }
  if (tol > SUN_RCONST(0.0) && tol < SUN_SMALL_REAL) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s = %g illegal: below the smallest normal number %g, its error "
                    "weights 1/%s would overflow (0 selects the default).",
                    name, (double)tol, (double)SUN_SMALL_REAL, name);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int LGNSStolerances(void *lgn_mem, sunrealtype rtol, sunrealtype atol)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (CheckTolerance(mem, rtol, "rtol", __func__) != LGN_SUCCESS ||
      CheckTolerance(mem, atol, "atol", __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  mem->rtol     = rtol == SUN_RCONST(0.0) ? LGN_RTOL_DEFAULT : rtol;
  mem->atol     = atol == SUN_RCONST(0.0) ? LGN_ATOL_DEFAULT : atol;
  mem->tols_set = SUNTRUE;
  if (mem->atol_vec != NULL) {
    free(mem->atol_vec); /* the scalar replaces the vector */
    mem->atol_vec = NULL;
  }
  return LGN_SUCCESS;
}

/* =============================================================================
 * Error control
 * ===========================================================================*/

int LGNSetAcceptStalls(void *lgn_mem, sunbooleantype accept)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (accept != SUNTRUE && accept != SUNFALSE) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "accept = %d illegal: use SUNTRUE or SUNFALSE.",
              (int)accept);
    return LGN_ILL_INPUT;
  }
  mem->accept_stalls = accept;
  return LGN_SUCCESS;
}

int LGNSetStepControl(void *lgn_mem, int control)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (control != LGN_STEP_FIXED && control != LGN_STEP_ADAPTIVE) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "control = %d illegal: use LGN_STEP_FIXED or LGN_STEP_ADAPTIVE.",
              control);
    return LGN_ILL_INPUT;
  }
  if (control != mem->step_control) {
    mem->step_control = control;
    mem->hnext = SUN_RCONST(0.0); /* error control starts anew */
  }
  return LGN_SUCCESS;
}

int LGNSVtolerances(void *lgn_mem, sunrealtype rtol, N_Vector atol)
{
  LGNMem mem;
  const sunrealtype *a;
  sunrealtype sum = SUN_RCONST(0.0);
  sunindextype i, nq_own, nv_own;
  int flag;
  ACCESS_MALLOC(lgn_mem, mem);
  lgnGhostsOwnedLengths(mem, &nq_own, &nv_own); /* ghosts' entries: not read */
  /* a local call across ranks too: the entries are copied into an array of
   * this rank's length, and the multipliers' atol (their mean over all
   * ranks) is formed by LGNSolve */
  if (CheckTolerance(mem, rtol, "rtol", __func__) != LGN_SUCCESS) return LGN_ILL_INPUT;
  flag = lgnCheckVector(mem, atol, mem->nv, "atol", __func__);
  if (flag != LGN_SUCCESS) return flag;
  a = N_VGetArrayPointer(atol);
  for (i = 0; i < nv_own; i++) {
    if (!(a[i] >= SUN_SMALL_REAL) || !isfinite(a[i])) {
      LGN_ERROR(mem, LGN_ILL_INPUT,
                "atol[%lld] = %g illegal: every entry must be finite and at least the "
                "smallest normal number %g (the error weights 1/atol must be finite).",
                (long long)i, (double)a[i], (double)SUN_SMALL_REAL);
      return LGN_ILL_INPUT;
    }
    sum += a[i];
  }
  if (mem->atol_vec == NULL) {
    mem->atol_vec = (sunrealtype *)malloc((size_t)SUNMAX(mem->nv, 1) * sizeof(sunrealtype));
    if (mem->atol_vec == NULL) {
      LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
      return LGN_MEM_FAIL;
    }
  }
  memcpy(mem->atol_vec, a, (size_t)mem->nv * sizeof(sunrealtype));
  mem->rtol     = rtol == SUN_RCONST(0.0) ? LGN_RTOL_DEFAULT : rtol;
  mem->atol     = sum / (sunrealtype)SUNMAX(nv_own, 1); /* this rank's mean */
  mem->tols_set = SUNTRUE;
  return LGN_SUCCESS;
}

/* Check a step size argument: finite and >= 0. */
static int CheckStepArg(LGNMem mem, sunrealtype x, const char *name, const char *func)
{
  if (!(x >= SUN_RCONST(0.0)) || !isfinite(x)) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s = %g illegal: must be >= 0 and finite.", name, (double)x);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int LGNSetInitStep(void *lgn_mem, sunrealtype h0)
{
  LGNMem mem;
  int flag;
  ACCESS_MEM(lgn_mem, mem);
  flag = CheckStepArg(mem, h0, "h0", __func__);
  if (flag != LGN_SUCCESS) return flag;
  mem->h0_user = h0;
  /* after steps (error control): the size of the next step, e.g. to go on
   * after a failure that left h tiny (0: estimated anew) */
  if (mem->malloc_done && mem->nst > 0) mem->hnext = h0;
  return LGN_SUCCESS;
}

int LGNSetMinStep(void *lgn_mem, sunrealtype hmin)
{
  LGNMem mem;
  int flag;
  ACCESS_MEM(lgn_mem, mem);
  flag = CheckStepArg(mem, hmin, "hmin", __func__);
  if (flag != LGN_SUCCESS) return flag;
  if (mem->hmax > SUN_RCONST(0.0) && hmin > mem->hmax) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "hmin = %g illegal: above hmax = %g.",
              (double)hmin, (double)mem->hmax);
    return LGN_ILL_INPUT;
  }
  mem->hmin = hmin;
  return LGN_SUCCESS;
}

int LGNSetMaxStep(void *lgn_mem, sunrealtype hmax)
{
  LGNMem mem;
  int flag;
  ACCESS_MEM(lgn_mem, mem);
  flag = CheckStepArg(mem, hmax, "hmax", __func__);
  if (flag != LGN_SUCCESS) return flag;
  if (hmax > SUN_RCONST(0.0) && hmax < mem->hmin) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "hmax = %g illegal: below hmin = %g.",
              (double)hmax, (double)mem->hmin);
    return LGN_ILL_INPUT;
  }
  mem->hmax = hmax;
  return LGN_SUCCESS;
}

/* A limit of the step (maxnef, maxncf, maxiters): >= 0, where 0 restores
 * the default dflt. */
static int SetLimit(LGNMem mem, int value, int dflt, const char *name,
                    const char *func, int *limit)
{
  if (value < 0) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s = %d illegal: must be >= 0.", name, value);
    return LGN_ILL_INPUT;
  }
  *limit = value == 0 ? dflt : value;
  return LGN_SUCCESS;
}

int LGNSetMaxErrTestFails(void *lgn_mem, int maxnef)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  return SetLimit(mem, maxnef, LGN_MAXNEF_DEFAULT, "maxnef", __func__, &mem->maxnef);
}

int LGNSetMaxConvFails(void *lgn_mem, int maxncf)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  return SetLimit(mem, maxncf, LGN_MAXNCF_DEFAULT, "maxncf", __func__, &mem->maxncf);
}

int LGNSetNonlinConvCoef(void *lgn_mem, sunrealtype epcon)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (!(epcon >= SUN_RCONST(0.0) && epcon <= SUN_RCONST(1.0))) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "epcon = %g illegal: must lie in [0, 1].",
              (double)epcon);
    return LGN_ILL_INPUT;
  }
  mem->epcon = epcon == SUN_RCONST(0.0) ? LGN_EPCON_DEFAULT : epcon;
  return LGN_SUCCESS;
}

int LGNSetStopTime(void *lgn_mem, sunrealtype tstop)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (!isfinite(tstop)) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "tstop is not finite.");
    return LGN_ILL_INPUT;
  }
  if (mem->malloc_done && tstop < mem->tn) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "tstop = %.17g illegal: behind the current time t = %.17g.",
              (double)tstop, (double)mem->tn);
    return LGN_ILL_INPUT;
  }
  mem->tstop     = tstop;
  mem->tstop_set = SUNTRUE;
  return LGN_SUCCESS;
}

int LGNClearStopTime(void *lgn_mem)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->tstop_set = SUNFALSE;
  return LGN_SUCCESS;
}

int LGNGetDky(void *lgn_mem, sunrealtype t, int k, N_Vector dky)
{
  LGNMem mem;
  sunrealtype fuzz;
  int flag;
  ACCESS_MALLOC(lgn_mem, mem);
  if (k < 0 || k > 2) {
    LGN_ERROR(mem, LGN_BAD_K, "k = %d illegal: use 0 (q), 1 (v) or 2 (vdot).", k);
    return LGN_BAD_K;
  }
  flag = lgnCheckVector(mem, dky, k == 0 ? mem->nq : mem->nv, "dky", __func__);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->dense_valid || !mem->work_done) {
    LGN_ERROR(mem, LGN_BAD_T, "No step to interpolate: take a step first.");
    return LGN_BAD_T;
  }
  fuzz = SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * SUNMAX(fabs(mem->tn), fabs(mem->tprev));
  if (!(t >= mem->tprev - fuzz && t <= mem->tn + fuzz)) {
    LGN_ERROR(mem, LGN_BAD_T,
              "t = %.17g illegal: outside the last step [%.17g, %.17g].",
              (double)t, (double)mem->tprev, (double)mem->tn);
    return LGN_BAD_T;
  }
  t = SUNMIN(SUNMAX(t, mem->tprev), mem->tn);
  return lgnOutputDky(mem, t, k, dky); /* projected, consistent (lgn_output.c) */
}

/* The getters' output x (length nv; NULL: no step attempted yet, zeros)
 * into the checked vector out (named name). */
static int CopyNv(LGNMem mem, const sunrealtype *x, N_Vector out, const char *name,
                  const char *func)
{
  int flag = lgnCheckVector(mem, out, mem->nv, name, func);
  if (flag != LGN_SUCCESS) return flag;
  if (x != NULL)
    memcpy(N_VGetArrayPointer(out), x, (size_t)mem->nv * sizeof(sunrealtype));
  else
    N_VConst(SUN_RCONST(0.0), out);
  return LGN_SUCCESS;
}

int LGNGetRedundantConstraints(void *lgn_mem, sunindextype *nred, sunindextype *rows)
{
  LGNMem mem;
  sunindextype i;
  ACCESS_MEM(lgn_mem, mem);
  if (nred == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "nred = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  if (mem->red_nout > 0) { /* left out at the start (lgn_redundancy.c) */
    *nred = mem->red_nout;
    if (rows != NULL)
      for (i = 0; i < *nred; i++) rows[i] = mem->red_rows[mem->m + i];
    return LGN_SUCCESS;
  }
  *nred = mem->work_done ? mem->diag_nred : 0;
  if (rows != NULL)
    for (i = 0; i < *nred; i++) rows[i] = mem->diag_red[i];
  return LGN_SUCCESS;
}

int LGNGetZeroPivot(void *lgn_mem, sunindextype *unknown)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (unknown == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "unknown = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  *unknown = mem->work_done ? mem->diag_pivot : -1;
  return LGN_SUCCESS;
}

int LGNGetEstLocalErrors(void *lgn_mem, N_Vector ele)
{
  LGNMem mem;
  ACCESS_MALLOC(lgn_mem, mem);
  return CopyNv(mem, mem->work_done ? mem->ele : NULL, ele, "ele", __func__);
}

int LGNGetErrWeights(void *lgn_mem, N_Vector eweight)
{
  LGNMem mem;
  ACCESS_MALLOC(lgn_mem, mem);
  return CopyNv(mem, mem->work_done ? mem->ewt : NULL, eweight, "eweight", __func__);
}

int LGNSetMaxNewtonIters(void *lgn_mem, int maxiters)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  return SetLimit(mem, maxiters, LGN_MAXCOR_DEFAULT, "maxiters", __func__, &mem->maxcor);
}

int LGNSetNewtonMode(void *lgn_mem, int mode)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (mode != LGN_NEWTON_FULL && mode != LGN_NEWTON_MODIFIED) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "mode = %d illegal: use LGN_NEWTON_FULL or LGN_NEWTON_MODIFIED.",
              mode);
    return LGN_ILL_INPUT;
  }
  mem->newton_mode = mode;
  lgnInvalidate(mem, LGN_CHANGE_METHOD);
  return LGN_SUCCESS;
}

int LGNSetLSetupFrequency(void *lgn_mem, long int msbp)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->msbp = msbp == 0 ? LGN_MSBP_DEFAULT : msbp;
  return LGN_SUCCESS;
}

int LGNSetMaxNumSteps(void *lgn_mem, long int mxsteps)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->mxstep = mxsteps == 0 ? LGN_MXSTEP_DEFAULT : mxsteps;
  return LGN_SUCCESS;
}

int LGNSetInitialAcceleration(void *lgn_mem, N_Vector vdot0, N_Vector lambda0)
{
  LGNMem mem;
  sunindextype nq_own, nv_own;
  int flag;
  ACCESS_MALLOC(lgn_mem, mem);
  flag = lgnCheckVector(mem, vdot0, mem->nv, "vdot0", __func__);
  if (flag == LGN_SUCCESS && mem->m_user > 0)
    flag = lgnCheckVector(mem, lambda0, mem->m_user, "lambda0", __func__);
  if (flag == LGN_SUCCESS && mem->nst > 0) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "vdot0 and lambda0 can only be set before the first step "
              "(call LGNReInit to start again from the current state).");
    flag = LGN_ILL_INPUT;
  }
  lgnGhostsOwnedLengths(mem, &nq_own, &nv_own); /* ghosts' entries: not read */
  if (flag == LGN_SUCCESS &&
      (!lgnAllFinite(N_VGetArrayPointer(vdot0), nv_own) ||
       (mem->m_user > 0 && !lgnAllFinite(N_VGetArrayPointer(lambda0), mem->m_user)))) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "vdot0 or lambda0 has a NaN or Inf entry.");
    flag = LGN_ILL_INPUT;
  }
  /* redundant rows: selected now (with a linear solver: B is of its kind),
   * and lambda0 must be 0 on the rows left out, as LGNGetMultipliers gives */
  if (flag == LGN_SUCCESS && mem->LS != NULL && mem->nst == 0)
    flag = lgnRedundancyAnalyse(mem, __func__);
  if (flag == LGN_SUCCESS && mem->red_nout > 0) {
    const sunrealtype *l0 = N_VGetArrayPointer(lambda0);
    sunindextype i;
    for (i = mem->m; i < mem->m_user; i++)
      if (l0[mem->red_rows[i]] != SUN_RCONST(0.0)) {
        LGN_ERROR(mem, LGN_ILL_INPUT,
                  "lambda0[%lld] = %g: constraint %lld is left out as redundant, its "
                  "multiplier must be 0 (the kept rows carry the constraint force).",
                  (long long)mem->red_rows[i], (double)l0[mem->red_rows[i]],
                  (long long)mem->red_rows[i]);
        flag = LGN_ILL_INPUT;
        break;
      }
  }
  /* across ranks a collective call: agreed before the work space is made */
  flag = lgnAgree(mem, flag);
  if (flag == LGN_SUCCESS) flag = lgnEnsureWork(mem);
  if (flag != LGN_SUCCESS) return flag;
  N_VScale(SUN_RCONST(1.0), vdot0, mem->vdot);
  if (mem->m > 0 && mem->red_nout == 0) N_VScale(SUN_RCONST(1.0), lambda0, mem->lambda);
  if (mem->m > 0 && mem->red_nout > 0) {
    const sunrealtype *l0 = N_VGetArrayPointer(lambda0);
    sunindextype i;
    for (i = 0; i < mem->m; i++) lgnData(mem->lambda)[i] = l0[mem->red_rows[i]];
  }
  mem->lambda_valid = SUNTRUE;
  lgnInvalidate(mem, LGN_CHANGE_STATE); /* initial values from these */
  mem->user_vdot0 = SUNTRUE;
  return LGN_SUCCESS;
}

int LGNSetInitialAux(void *lgn_mem, N_Vector a0)
{
  LGNMem mem;
  sunindextype nq_own, nv_own;
  int flag;
  ACCESS_MALLOC(lgn_mem, mem);
  flag = lgnCheckVector(mem, a0, mem->nv, "a0", __func__);
  if (flag != LGN_SUCCESS) return flag;
  lgnGhostsOwnedLengths(mem, &nq_own, &nv_own); /* ghosts' entries: not read */
  if (!lgnAllFinite(N_VGetArrayPointer(a0), nv_own)) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "a0 has a NaN or Inf entry.");
    return LGN_ILL_INPUT;
  }
  if (mem->nst > 0) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "a0 can only be set before the first step (call LGNReInit).");
    return LGN_ILL_INPUT;
  }
  N_VScale(SUN_RCONST(1.0), a0, mem->a);
  mem->user_a0 = SUNTRUE;
  return LGN_SUCCESS;
}

int LGNSetErrHandlerFn(void *lgn_mem, LGNErrHandlerFn ehfun, void *eh_data)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->err.ehfun   = ehfun;
  mem->err.eh_data = eh_data;
  return LGN_SUCCESS;
}

int LGNSetErrFile(void *lgn_mem, FILE *errfp)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  mem->err.errfp = errfp;
  return LGN_SUCCESS;
}

/* =============================================================================
 * Outputs
 * ===========================================================================*/

int LGNGetAcceleration(void *lgn_mem, N_Vector vdot)
{
  LGNMem mem;
  int flag;
  ACCESS_MALLOC(lgn_mem, mem);
  flag = lgnCheckVector(mem, vdot, mem->nv, "vdot", __func__);
  if (flag != LGN_SUCCESS) return flag;
  if (mem->out_valid) /* the last output's consistent value (lgn_output.c) */
    memcpy(N_VGetArrayPointer(vdot), mem->out_vdot, (size_t)mem->nv * sizeof(sunrealtype));
  else if (mem->out_keep != NULL && mem->out_keep_nv == mem->nv) /* kept (lgn_mem.c) */
    memcpy(N_VGetArrayPointer(vdot), mem->out_keep, (size_t)mem->nv * sizeof(sunrealtype));
  else
    N_VScale(SUN_RCONST(1.0), mem->vdot, vdot);
  return LGN_SUCCESS;
}

int LGNGetMultipliers(void *lgn_mem, N_Vector lambda)
{
  LGNMem mem;
  int flag;
  ACCESS_MALLOC(lgn_mem, mem);
  flag = lgnCheckVector(mem, lambda, mem->m_user, "lambda", __func__);
  if (flag != LGN_SUCCESS) return flag;
  if (mem->m_user > 0) {
    /* the last output's consistent value (lgn_output.c); else the last
     * valid multipliers: in the work space, or kept while a setter
     * dropped it (never the zeros of a new work space); 0 on the rows
     * left out as redundant (lgn_redundancy.c) */
    const sunrealtype *kept = NULL;
    if (mem->out_valid && mem->out_lambda != NULL)
      kept = mem->out_lambda;
    else if (mem->out_keep != NULL && mem->out_keep_m == mem->m && mem->m > 0)
      kept = mem->out_keep + mem->out_keep_nv;
    else if (mem->lambda != NULL && mem->lambda_valid)
      kept = lgnData(mem->lambda);
    else if (mem->lambda_keep != NULL && mem->lambda_keep_len == mem->m)
      kept = mem->lambda_keep;
    if (kept == NULL) {
      LGN_ERROR(mem, LGN_ILL_INPUT,
                "No multipliers yet for the %lld constraints: they are computed "
                "at the start of the next LGNSolve that gets that far.",
                (long long)mem->m_user);
      return LGN_ILL_INPUT;
    }
    lgnRedundancyExpand(mem, kept, N_VGetArrayPointer(lambda));
  }
  return LGN_SUCCESS;
}

int LGNGetAuxAcceleration(void *lgn_mem, N_Vector a)
{
  LGNMem mem;
  int flag;
  ACCESS_MALLOC(lgn_mem, mem);
  flag = lgnCheckVector(mem, a, mem->nv, "a", __func__);
  if (flag != LGN_SUCCESS) return flag;
  N_VScale(SUN_RCONST(1.0), mem->a, a);
  return LGN_SUCCESS;
}


int LGNGetTolerances(void *lgn_mem, sunrealtype *rtol, sunrealtype *atol)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (rtol == NULL || atol == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "%s = NULL illegal.", rtol == NULL ? "rtol" : "atol");
    return LGN_ILL_INPUT;
  }
  *rtol = mem->rtol;
  *atol = mem->atol; /* with LGNSVtolerances: their mean */
  return LGN_SUCCESS;
}

int LGNGetIntegratorStats(void *lgn_mem, long int *nsteps, long int *nrevals,
                          long int *nlinsetups, long int *netfails,
                          sunrealtype *hinused, sunrealtype *hlast,
                          sunrealtype *hcur, sunrealtype *tcur)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (nsteps == NULL || nrevals == NULL || nlinsetups == NULL || netfails == NULL ||
      hinused == NULL || hlast == NULL || hcur == NULL || tcur == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "An output argument is NULL (%s).",
              nsteps == NULL ? "nsteps" : nrevals == NULL ? "nrevals"
              : nlinsetups == NULL ? "nlinsetups" : netfails == NULL ? "netfails"
              : hinused == NULL ? "hinused" : hlast == NULL ? "hlast"
              : hcur == NULL ? "hcur" : "tcur");
    return LGN_ILL_INPUT;
  }
  *nsteps     = mem->nst;
  *nrevals    = mem->nre;
  *nlinsetups = mem->nlsetup;
  *netfails   = mem->netf;
  *hinused    = mem->step_control == LGN_STEP_ADAPTIVE ? mem->h0_actual : mem->h;
  *hlast      = mem->hlast;
  *hcur       = mem->step_control == LGN_STEP_ADAPTIVE ? mem->hnext : mem->h;
  *tcur       = mem->tn;
  return LGN_SUCCESS;
}

int LGNGetNewtonStats(void *lgn_mem, long int *nniters, long int *nncfails)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (nniters == NULL || nncfails == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "%s = NULL illegal.", nniters == NULL ? "nniters" : "nncfails");
    return LGN_ILL_INPUT;
  }
  *nniters  = mem->nni;
  *nncfails = mem->nncf;
  return LGN_SUCCESS;
}

int LGNGetWorkSpace(void *lgn_mem, long int *lenrw, long int *leniw)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (lenrw == NULL || leniw == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "An output argument is NULL.");
    return LGN_ILL_INPUT;
  }
  lgnWorkSpace(mem, lenrw, leniw);
  return LGN_SUCCESS;
}

int LGNResetSparsityPattern(void *lgn_mem)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  lgnInvalidate(mem, LGN_CHANGE_PATTERN); /* rebuilt, not extended */
  return LGN_SUCCESS;
}

int LGNGetMethodParams(void *lgn_mem, sunrealtype *alpha_m, sunrealtype *alpha_f,
                       sunrealtype *beta, sunrealtype *gamma)
{
  LGNMem mem;
  ACCESS_MEM(lgn_mem, mem);
  if (alpha_m == NULL || alpha_f == NULL || beta == NULL || gamma == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "An output argument is NULL.");
    return LGN_ILL_INPUT;
  }
  *alpha_m = mem->alpha_m;
  *alpha_f = mem->alpha_f;
  *beta    = mem->beta;
  *gamma   = mem->gamma;
  return LGN_SUCCESS;
}

int LGNPrintAllStats(void *lgn_mem, FILE *outfile, SUNOutputFormat fmt)
{
  LGNMem mem;
  const char *fmt_l, *fmt_r;
  ACCESS_MEM(lgn_mem, mem);
  if (outfile == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "outfile = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  if (fmt == SUN_OUTPUTFORMAT_TABLE) {
    fmt_l = "%-28s = %ld\n";
    fmt_r = "%-28s = %.6g\n";
  } else if (fmt == SUN_OUTPUTFORMAT_CSV) {
    fmt_l = "%s,%ld\n";
    fmt_r = "%s,%.17g\n";
  } else {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "fmt illegal: use SUN_OUTPUTFORMAT_TABLE or SUN_OUTPUTFORMAT_CSV.");
    return LGN_ILL_INPUT;
  }
  fprintf(outfile, fmt_r, "Current time", (double)mem->tn);
  fprintf(outfile, fmt_r, "Last step size", (double)mem->hlast);
  fprintf(outfile, fmt_l, "Steps", mem->nst);
  fprintf(outfile, fmt_l, "Newton iterations", mem->nni);
  fprintf(outfile, fmt_r, "Newton iterations per step",
          mem->nst > 0 ? (double)mem->nni / (double)mem->nst : 0.0);
  fprintf(outfile, fmt_l, "Newton convergence fails", mem->nncf);
  fprintf(outfile, fmt_l, "Newton multiplier stalls", mem->nstall);
  fprintf(outfile, fmt_l, "Step fails", mem->nfails);
  fprintf(outfile, fmt_l, "Residual evals", mem->nre);
  fprintf(outfile, fmt_l, "DQ evals", mem->ndq);
  fprintf(outfile, fmt_l, "Jacobian evals", mem->nje);
  fprintf(outfile, fmt_l, "Linear solver setups", mem->nlsetup);
  fprintf(outfile, fmt_l, "Linear solves", mem->nlsolve);
  fprintf(outfile, fmt_l, "Iterations w. reused matrix", mem->nreuse);
  fprintf(outfile, fmt_l, "Newton restarts", mem->nrestart);
  fprintf(outfile, fmt_l, "Last linear solver flag", mem->last_lin_flag);
  if (mem->krylov) { /* a matrix-free Krylov solver (lgn_krylov.c) */
    fprintf(outfile, fmt_l, "Krylov iterations", mem->nli);
    fprintf(outfile, fmt_r, "Krylov iters per Newton iter",
            mem->nni > 0 ? (double)mem->nli / (double)mem->nni : 0.0);
    fprintf(outfile, fmt_l, "Linear convergence fails", mem->nlcf);
    fprintf(outfile, fmt_l, "Preconditioner setups", mem->npe);
    fprintf(outfile, fmt_l, "Preconditioner solves", mem->nps);
    fprintf(outfile, fmt_l, "Jac-times evals", mem->njtimes);
  }
  if (mem->step_control == LGN_STEP_ADAPTIVE) {
    fprintf(outfile, fmt_l, "Error test fails", mem->netf);
    fprintf(outfile, fmt_r, "Initial step size", (double)mem->h0_actual);
    fprintf(outfile, fmt_r, "Current step size", (double)mem->hnext);
    fprintf(outfile, fmt_r, "Last error norm", (double)mem->err_norm);
  }
  if (mem->family == LGN_FAMILY_BDF) {
    int k;
    fprintf(outfile, fmt_l, "BDF maximum order", (long int)mem->bdf_maxord);
    fprintf(outfile, fmt_l, "BDF last order", (long int)mem->bdf_last_order);
    fprintf(outfile, fmt_l, "BDF current order", (long int)mem->bdf_order);
    for (k = 1; k <= LGN_BDF_MAXORD; k++) {
      char label[32];
      snprintf(label, sizeof label, "BDF steps at order %d", k);
      fprintf(outfile, fmt_l, label, mem->bdf_nord[k]);
    }
  }
  if (mem->nrtfn > 0) fprintf(outfile, fmt_l, "Root fn evals", mem->nge);
  if (mem->sp != NULL) {
    fprintf(outfile, fmt_l, "Sparse pattern analyses", mem->sp->npattern);
    fprintf(outfile, fmt_l, "Iteration matrix nonzeros", lgnIterationMatrixNnz(mem));
    fprintf(outfile, fmt_l, "DQ column colours", (long int)mem->sp->Kcol.ncolors);
  }
  if (mem->own_klu_solves) { /* LGNSetOwnKLUSolves: the getters of lgn_ls.c */
    long int ncopy, nvalue, nrefactor, nsolve, npivot, npattern, nnocopy;
    (void)LGNGetNumKLUFactorCopies(mem, &ncopy);
    (void)LGNGetNumKLUValueCopies(mem, &nvalue);
    (void)LGNGetNumOwnKLURefactors(mem, &nrefactor);
    (void)LGNGetNumOwnKLUSolves(mem, &nsolve);
    (void)LGNGetNumKLUFallbacks(mem, &npivot, &npattern, &nnocopy);
    fprintf(outfile, fmt_l, "KLU factor copies", ncopy);
    fprintf(outfile, fmt_l, "KLU factor value copies", nvalue);
    fprintf(outfile, fmt_l, "Own KLU refactorisations", nrefactor);
    fprintf(outfile, fmt_l, "Own KLU solves", nsolve);
    fprintf(outfile, fmt_l, "KLU fallbacks: small pivot", npivot);
    fprintf(outfile, fmt_l, "KLU fallbacks: new pattern", npattern);
    fprintf(outfile, fmt_l, "KLU fallbacks: no copy", nnocopy);
  }
  return LGN_SUCCESS;
}

const char *LGNGetReturnFlagName(long int flag)
{
  switch (flag) {
  case LGN_SUCCESS:            return "LGN_SUCCESS";
  case LGN_TOO_MUCH_WORK:      return "LGN_TOO_MUCH_WORK";
  case LGN_CONV_FAILURE:       return "LGN_CONV_FAILURE";
  case LGN_MASS_FAIL:          return "LGN_MASS_FAIL";
  case LGN_FORCE_FAIL:         return "LGN_FORCE_FAIL";
  case LGN_CONSTR_FAIL:        return "LGN_CONSTR_FAIL";
  case LGN_CONSTR_JAC_FAIL:    return "LGN_CONSTR_JAC_FAIL";
  case LGN_TANGENT_FAIL:       return "LGN_TANGENT_FAIL";
  case LGN_GROUP_FAIL:         return "LGN_GROUP_FAIL";
  case LGN_NONFINITE:          return "LGN_NONFINITE";
  case LGN_REPTD_CALLBACK_ERR: return "LGN_REPTD_CALLBACK_ERR";
  case LGN_IC_FAIL:            return "LGN_IC_FAIL";
  case LGN_ERR_FAILURE:        return "LGN_ERR_FAILURE";
  case LGN_STEP_TOO_SMALL:     return "LGN_STEP_TOO_SMALL";
  case LGN_INCONSISTENT_IC:    return "LGN_INCONSISTENT_IC";
  case LGN_TSTOP_RETURN:       return "LGN_TSTOP_RETURN";
  case LGN_ROOT_RETURN:        return "LGN_ROOT_RETURN";
  case LGN_RTFUNC_FAIL:        return "LGN_RTFUNC_FAIL";
  case LGN_WARNING:            return "LGN_WARNING";
  case LGN_REDUNDANT_INCONSISTENT: return "LGN_REDUNDANT_INCONSISTENT";
  case LGN_BAD_T:              return "LGN_BAD_T";
  case LGN_BAD_K:              return "LGN_BAD_K";
  case LGN_MEM_NULL:           return "LGN_MEM_NULL";
  case LGN_MEM_FAIL:           return "LGN_MEM_FAIL";
  case LGN_ILL_INPUT:          return "LGN_ILL_INPUT";
  case LGN_NO_MALLOC:          return "LGN_NO_MALLOC";
  case LGN_NO_LINSOL:          return "LGN_NO_LINSOL";
  case LGN_MISSING_FN:         return "LGN_MISSING_FN";
  case LGN_BAD_TOUT:           return "LGN_BAD_TOUT";
  case LGN_LINIT_FAIL:         return "LGN_LINIT_FAIL";
  case LGN_LSETUP_FAIL:        return "LGN_LSETUP_FAIL";
  case LGN_LSOLVE_FAIL:        return "LGN_LSOLVE_FAIL";
  case LGN_LS_MISMATCH:        return "LGN_LS_MISMATCH";
  case LGN_IO_FAIL:            return "LGN_IO_FAIL";
  case LGN_RESTART_BAD_FILE:   return "LGN_RESTART_BAD_FILE";
  case LGN_RESTART_MISMATCH:   return "LGN_RESTART_MISMATCH";
  case LGN_UNRECOGNIZED_ERR:   return "LGN_UNRECOGNIZED_ERR";
  default:                     return "NONE";
  }
}
