/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Lifecycle and the time loop:
 *   LGNCreate, LGNInit, LGNReInit, LGNSolve, LGNFree,
 *   lgnAllocWork / lgnFreeWork (work space sized by nv and m),
 *   lgnAccessMem (the common guard of every public function).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_klu_solve.h"
#include "lgn_sparse.h"

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
  mem->kinematics   = LGN_KINEMATICS_SIMPLIFIED;
  mem->rtol         = LGN_RTOL_DEFAULT;
  mem->atol         = LGN_ATOL_DEFAULT;
  mem->maxcor       = LGN_MAXCOR_DEFAULT;
  mem->newton_mode  = LGN_NEWTON_FULL;
  mem->msbp         = LGN_MSBP_DEFAULT;
  mem->mxstep       = LGN_MXSTEP_DEFAULT;
  mem->predictor    = LGN_PREDICTOR_ZERO;
  mem->own_klu_solves = SUNFALSE;
  lgnErrSinkInit(&mem->err);
  return mem;
}

static void DestroyVector(N_Vector *x)
{
  if (*x != NULL) N_VDestroy(*x);
  *x = NULL;
}

static void DestroyMatrix(SUNMatrix *A)
{
  if (*A != NULL) SUNMatDestroy(*A);
  *A = NULL;
}

static void FreeState(LGNMem mem)
{
  DestroyVector(&mem->q);
  DestroyVector(&mem->v);
  DestroyVector(&mem->vdot);
  DestroyVector(&mem->a);
  DestroyVector(&mem->q1);
  DestroyVector(&mem->v1);
  DestroyVector(&mem->vdot1);
  DestroyVector(&mem->dq_q);
  DestroyVector(&mem->dq_v);
  mem->malloc_done = SUNFALSE;
}

void lgnFreeMatrices(LGNMem mem)
{
  DestroyMatrix(&mem->Mmat);
  DestroyMatrix(&mem->Bmat);
  DestroyMatrix(&mem->Kmat);
  DestroyMatrix(&mem->Cmat);
  DestroyMatrix(&mem->Mdq);
  DestroyMatrix(&mem->Bdq);
  free(mem->Bvq);
  mem->Bvq = NULL;
  lgnSparseWorkFree(mem);
  lgnKluCopyFree(&mem->klu);
  mem->klu_valid = SUNFALSE;
  mem->mat_done = SUNFALSE;
}

void lgnFreeWork(LGNMem mem)
{
  lgnFreeMatrices(mem);
  DestroyVector(&mem->lambda);
  DestroyVector(&mem->lambda1);
  DestroyVector(&mem->g);
  DestroyVector(&mem->rdyn);
  DestroyVector(&mem->phi);
  DestroyVector(&mem->rhs);
  DestroyVector(&mem->sol);
  DestroyVector(&mem->dq_g);
  DestroyVector(&mem->dq_r);
  DestroyVector(&mem->dq_z);
  free(mem->sigma);
  mem->sigma = NULL;
  mem->sigma_dot = mem->sigma_ddot = mem->a_pred = mem->work_nv = NULL;
  mem->work2_nv = mem->vdot_prev = mem->mass_diag = mem->lambda_prev = mem->work_m = NULL;
  mem->h_prev = SUN_RCONST(0.0);
  free(mem->Tm);
  mem->Tm = mem->Tv = mem->Ta = mem->blk_work = NULL;
  lgnBlocksFree(mem);
  mem->work_done = SUNFALSE;
  mem->ic_done = SUNFALSE;
}

void LGNFree(void **lgn_mem)
{
  LGNMem mem;
  if (lgn_mem == NULL || *lgn_mem == NULL) return;
  mem = (LGNMem)(*lgn_mem);
  lgnFreeWork(mem);
  FreeState(mem);
  free(mem);
  *lgn_mem = NULL;
}

/* The guard every public function starts with. */
int lgnAccessMem(void *lgn_mem, const char *func, LGNMem *mem)
{
  if (lgn_mem == NULL) {
    lgnProcessError(NULL, LGN_MEM_NULL, __LINE__, func, __FILE__, MSG_NO_MEM);
    return LGN_MEM_NULL;
  }
  *mem = (LGNMem)lgn_mem;
  return LGN_SUCCESS;
}

/* =============================================================================
 * Work space: everything whose size depends on nv and m. Allocated lazily at
 * the first LGNSolve (so the model may be described in any order) and
 * reallocated when m changes.
 * ===========================================================================*/

int lgnAllocWork(LGNMem mem)
{
  sunindextype nv = mem->nv, m = mem->m;
  SUNContext ctx = mem->sunctx;
  int fail = 0;

  lgnFreeWork(mem);
  fail = lgnBlocksBuild(mem) != LGN_SUCCESS;
  if (!fail) {
    mem->g    = N_VNew_Serial(nv, ctx);
    mem->rdyn = N_VNew_Serial(nv, ctx);
    mem->dq_g = N_VNew_Serial(nv, ctx);
    mem->dq_r = N_VNew_Serial(nv, ctx);
    mem->rhs  = N_VNew_Serial(nv + m, ctx);
    mem->sol  = N_VNew_Serial(nv + m, ctx);
    fail = (mem->g == NULL || mem->rdyn == NULL || mem->dq_g == NULL ||
            mem->dq_r == NULL || mem->rhs == NULL ||
            mem->sol == NULL);
  }
  if (m > 0 && !fail) {
    mem->lambda  = N_VNew_Serial(m, ctx);
    mem->lambda1 = N_VNew_Serial(m, ctx);
    mem->phi     = N_VNew_Serial(m, ctx);
    mem->dq_z    = N_VNew_Serial(m, ctx);
    fail = (mem->lambda == NULL || mem->lambda1 == NULL || mem->phi == NULL ||
            mem->dq_z == NULL);
  }
  if (!fail) {
    /* sigma, sigma_dot and sigma_ddot of the exact variant (BindIncrement
     * in lgn_step.c), a_pred, work_nv, work2_nv, vdot_prev, mass_diag
     * (nv each), lambda_prev and work_m (m each) in one block */
    mem->sigma = (sunrealtype *)calloc((size_t)(8 * nv + 2 * m), sizeof(sunrealtype));
    /* Tm, Tv, Ta (packed diagonal blocks) and the block scratch */
    mem->Tm    = (sunrealtype *)calloc((size_t)(3 * mem->tlen + 3 * mem->blk_max),
                                       sizeof(sunrealtype));
    fail       = (mem->sigma == NULL || mem->Tm == NULL);
  }
  if (fail) {
    lgnFreeWork(mem);
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  mem->Tv         = mem->Tm + mem->tlen;
  mem->Ta         = mem->Tm + 2 * mem->tlen;
  mem->blk_work   = mem->Tm + 3 * mem->tlen;
  mem->sigma_dot  = mem->sigma + nv;
  mem->sigma_ddot = mem->sigma + 2 * nv;
  mem->a_pred     = mem->sigma + 3 * nv;
  mem->work_nv    = mem->sigma + 4 * nv;
  mem->work2_nv   = mem->sigma + 5 * nv;
  mem->vdot_prev  = mem->sigma + 6 * nv;
  mem->mass_diag  = mem->sigma + 7 * nv;
  mem->lambda_prev = m > 0 ? mem->sigma + 8 * nv : NULL;
  mem->work_m      = m > 0 ? mem->sigma + 8 * nv + m : NULL;
  if (m > 0) N_VConst(SUN_RCONST(0.0), mem->lambda);
  mem->work_done = SUNTRUE;
  return LGN_SUCCESS;
}

/* A model matrix of the type of the iteration matrix: dense, or sparse in
 * A's format with room for nnz entries (a callback needing more calls
 * SUNSparseMatrix_Reallocate). */
static SUNMatrix NewModelMatrix(LGNMem mem, sunindextype rows,
                                sunindextype cols, sunindextype nnz)
{
  SUNMatrix S;
  if (!mem->sparse) return SUNDenseMatrix(rows, cols, mem->sunctx);
  S = SUNSparseMatrix(rows, cols, SUNMAX(SUNMIN(nnz, rows * cols), 1),
                      mem->sparsetype, mem->sunctx);
  if (S != NULL) SUNMatZero(S);
  return S;
}

/* The model matrices (M, B, K, C and their difference-quotient twins) of
 * the type of A; for the sparse path, first guesses of their sizes: a
 * body's blocks for M, K and C, 12 entries (two bodies) per constraint row. */
int lgnAllocMatrices(LGNMem mem)
{
  sunindextype nv = mem->nv, m = mem->m, nnzM = 0;
  int b, fail;

  lgnFreeMatrices(mem);
  mem->mass_current = SUNFALSE;
  mem->sparse = SUNMatGetID(mem->A) == SUNMATRIX_SPARSE;
  if (mem->sparse) mem->sparsetype = (int)SUNSparseMatrix_SparseType(mem->A);
  for (b = 0; b < mem->nblk; b++) {
    sunindextype size = mem->blk_voff[b + 1] - mem->blk_voff[b];
    nnzM += lgnBlockIsIdentity(mem, b) ? size : size * size;
  }
  mem->Mmat = NewModelMatrix(mem, nv, nv, nnzM);
  mem->Kmat = NewModelMatrix(mem, nv, nv, nnzM);
  mem->Cmat = NewModelMatrix(mem, nv, nv, nnzM);
  mem->Mdq  = NewModelMatrix(mem, nv, nv, nnzM);
  fail = (mem->Mmat == NULL || mem->Kmat == NULL || mem->Cmat == NULL ||
          mem->Mdq == NULL);
  if (m > 0 && !fail) {
    mem->Bmat = NewModelMatrix(mem, m, nv, 12 * m);
    mem->Bdq  = NewModelMatrix(mem, m, nv, 12 * m);
    if (!mem->sparse) mem->Bvq = (sunrealtype *)calloc((size_t)(m * nv), sizeof(sunrealtype));
    fail = (mem->Bmat == NULL || mem->Bdq == NULL || (!mem->sparse && mem->Bvq == NULL));
  }
  if (!fail && mem->sparse) fail = lgnSparseWorkCreate(mem) != LGN_SUCCESS;
  if (fail) {
    lgnFreeMatrices(mem);
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  mem->mat_done = SUNTRUE;
  return LGN_SUCCESS;
}

long int lgnIterationMatrixNnz(LGNMem mem)
{
  const long int n = (long int)(mem->nv + mem->m);
  if (mem->sp != NULL) return mem->sp->have_pattern ? (long int)mem->sp->A.colptr[n] : 0L;
  return n * n;
}

/* Reals and integers of one model matrix. */
static void MatrixSpace(SUNMatrix S, long int *rw, long int *iw)
{
  long int lrw = 0, liw = 0;
  if (S != NULL && SUNMatSpace(S, &lrw, &liw) == 0) {
    *rw += lrw;
    *iw += liw;
  }
}

void lgnWorkSpace(LGNMem mem, long int *lenrw, long int *leniw)
{
  const long int nq = (long int)mem->nq, nv = (long int)mem->nv, m = (long int)mem->m;
  long int rw = 0, iw = 0;
  if (mem->malloc_done) rw += 3 * nq + 6 * nv;           /* q, q1, dq_q; v ...  */
  if (mem->work_done) {
    rw += 4 * nv + 2 * (nv + m) + 4 * m;                  /* g ... sol; lambda ... */
    rw += 8 * nv + 2 * m + 3 * (long int)(mem->tlen + mem->blk_max);
    iw += 3 * (mem->nblk + 1) + nv + mem->nblk;           /* block tables        */
  }
  if (mem->mat_done) {
    MatrixSpace(mem->Mmat, &rw, &iw);
    MatrixSpace(mem->Kmat, &rw, &iw);
    MatrixSpace(mem->Cmat, &rw, &iw);
    MatrixSpace(mem->Mdq, &rw, &iw);
    MatrixSpace(mem->Bmat, &rw, &iw);
    MatrixSpace(mem->Bdq, &rw, &iw);
    if (mem->Bvq != NULL) rw += m * nv;
    lgnSparseWorkSpace(mem, &rw, &iw);
    lgnKluCopySpace(mem->klu, &rw, &iw);
  }
  *lenrw = rw;
  *leniw = iw;
}

/* =============================================================================
 * Initialisation
 * ===========================================================================*/

/* Check a vector argument of a public function: not NULL, with a data
 * array (serial N_Vector) of the expected length. */
int lgnCheckVector(LGNMem mem, N_Vector x, sunindextype len, const char *name,
                   const char *func)
{
  if (x == NULL) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s = NULL illegal.", name);
    return LGN_ILL_INPUT;
  }
  if (N_VGetArrayPointer(x) == NULL && len > 0) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s has no data array (a serial N_Vector is required).",
                    name);
    return LGN_ILL_INPUT;
  }
  if (N_VGetLength(x) != len) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s has length %lld, but %lld is needed.", name,
                    (long long)N_VGetLength(x), (long long)len);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

static void ResetCounters(LGNMem mem)
{
  mem->nst = mem->nni = mem->nncf = mem->nstall = mem->nfails = 0;
  mem->nre = mem->ndq = mem->nje = mem->nlsetup = mem->nlsolve = 0;
  mem->nreuse = mem->nrestart = 0;
  mem->lambda_noise = mem->lambda_noise_h = SUN_RCONST(0.0);
  mem->hlast = SUN_RCONST(0.0);
  mem->last_lin_flag = 0;
}

/* The arguments of LGNInit and LGNReInit: a group set, q0 and v0 of its
 * sizes, a finite t0. */
static int CheckInitialState(LGNMem mem, sunrealtype t0, N_Vector q0,
                             N_Vector v0, const char *func)
{
  int flag;
  if (mem->G == NULL) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    MSG_NO_GROUP);
    return LGN_ILL_INPUT;
  }
  flag = lgnCheckVector(mem, q0, mem->G->nq, "q0", func);
  if (flag == LGN_SUCCESS) flag = lgnCheckVector(mem, v0, mem->G->nv, "v0", func);
  if (flag != LGN_SUCCESS) return flag;
  if (!isfinite(t0)) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "t0 is not finite.");
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

/* Copy the (checked) initial state; shared by LGNInit and LGNReInit. */
static int SetInitialState(LGNMem mem, sunrealtype t0, N_Vector q0,
                           N_Vector v0, const char *func)
{
  N_VScale(SUN_RCONST(1.0), q0, mem->q);
  N_VScale(SUN_RCONST(1.0), v0, mem->v);
  if (LGNGroup_Normalize(mem->G, lgnData(mem->q)) != 0) {
    lgnProcessError(mem, LGN_GROUP_FAIL, __LINE__, func, __FILE__,
                    "The Lie group could not normalise q0.");
    return LGN_GROUP_FAIL;
  }
  mem->tn         = t0;
  mem->h_prev     = SUN_RCONST(0.0);
  mem->ic_done    = SUNFALSE;
  mem->user_vdot0 = SUNFALSE;
  mem->user_a0    = SUNFALSE;
  mem->mass_current = SUNFALSE;
  lgnInvalidateMatrix(mem);
  ResetCounters(mem);
  return LGN_SUCCESS;
}

int LGNInit(void *lgn_mem, sunrealtype t0, N_Vector q0, N_Vector v0)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  flag = CheckInitialState(mem, t0, q0, v0, __func__);
  if (flag != LGN_SUCCESS) return flag;

  lgnFreeWork(mem);
  FreeState(mem);
  mem->nq    = mem->G->nq;
  mem->nv    = mem->G->nv;
  mem->q     = N_VClone(q0);
  mem->q1    = N_VClone(q0);
  mem->dq_q  = N_VClone(q0);
  mem->v     = N_VClone(v0);
  mem->vdot  = N_VClone(v0);
  mem->a     = N_VClone(v0);
  mem->v1    = N_VClone(v0);
  mem->vdot1 = N_VClone(v0);
  mem->dq_v  = N_VClone(v0);
  if (mem->q == NULL || mem->q1 == NULL || mem->dq_q == NULL ||
      mem->v == NULL || mem->vdot == NULL || mem->a == NULL ||
      mem->v1 == NULL || mem->vdot1 == NULL || mem->dq_v == NULL) {
    FreeState(mem);
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  mem->malloc_done = SUNTRUE;
  flag = SetInitialState(mem, t0, q0, v0, __func__);
  if (flag != LGN_SUCCESS) FreeState(mem);
  return flag;
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
    return LGN_ILL_INPUT;
  }
  flag = CheckInitialState(mem, t0, q0, v0, __func__);
  if (flag != LGN_SUCCESS) return flag;
  return SetInitialState(mem, t0, q0, v0, __func__);
}

/* =============================================================================
 * LGNSolve
 * ===========================================================================*/

/* Everything LGNSolve needs before the first step: callbacks, step size,
 * linear solver, work space and consistent initial values. */
static int CheckReadyToSolve(LGNMem mem)
{
  int flag;
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
      (mem->kinematics != LGN_KINEMATICS_SIMPLIFIED &&
       mem->G->ops.tangent_dot_apply == NULL) ||
      (mem->kinematics == LGN_KINEMATICS_EXACT &&
       mem->G->ops.tangent_inverse_apply == NULL)) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The Lie group lacks an operation the method needs "
              "(compose_exp, tangent_apply, tangent_matrix%s).",
              mem->kinematics == LGN_KINEMATICS_SIMPLIFIED
                  ? ""
                  : ", tangent_dot_apply, tangent_inverse_apply");
    return LGN_ILL_INPUT;
  }
  if (!(mem->h > SUN_RCONST(0.0))) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "No step size: call LGNSetStepSize.");
    return LGN_ILL_INPUT;
  }
  if (mem->LS == NULL || mem->A == NULL) {
    LGN_ERROR(mem, LGN_NO_LINSOL, "No linear solver: call LGNSetLinearSolver.");
    return LGN_NO_LINSOL;
  }
  if (!mem->work_done) {
    flag = lgnAllocWork(mem);
    if (flag != LGN_SUCCESS) return flag;
  }
  flag = lgnLsCheck(mem);
  if (flag == LGN_SUCCESS && !mem->mat_done) flag = lgnAllocMatrices(mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->ic_done) {
    flag = lgnInitialConditions(mem);
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

int LGNSolve(void *lgn_mem, sunrealtype tout, sunrealtype *tret, N_Vector q,
             N_Vector v, int itask)
{
  LGNMem mem;
  sunrealtype troundoff, remaining, hstep;
  long int nstloc = 0;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  if (tret == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "tret = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  flag = lgnCheckVector(mem, q, mem->nq, "q", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckVector(mem, v, mem->nv, "v", __func__);
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
  flag = CheckReadyToSolve(mem);
  if (flag != LGN_SUCCESS) {
    CopyOut(mem, tret, q, v);
    return flag;
  }

  if (itask == LGN_ONE_STEP) {
    flag = lgnStep(mem, mem->h);
    CopyOut(mem, tret, q, v);
    return flag;
  }

  /* LGN_NORMAL: fixed steps; the last one lands exactly on tout. A remainder
   * up to 1e-6 h longer than h is taken as one step, so that roundoff in t
   * never produces a tiny extra step. */
  troundoff = SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF *
              SUNMAX(fabs(mem->tn), fabs(tout));
  if (tout < mem->tn - troundoff) {
    LGN_ERROR(mem, LGN_BAD_TOUT,
              "tout = %.17g is behind the current time t = %.17g.",
              (double)tout, (double)mem->tn);
    CopyOut(mem, tret, q, v);
    return LGN_BAD_TOUT;
  }
  while (tout - mem->tn > troundoff) {
    if (mem->mxstep > 0 && nstloc >= mem->mxstep) {
      LGN_ERROR(mem, LGN_TOO_MUCH_WORK,
                MSG_TIME "mxstep = %ld steps taken before reaching tout.",
                (double)mem->tn, mem->mxstep);
      flag = LGN_TOO_MUCH_WORK;
      break;
    }
    remaining = tout - mem->tn;
    hstep     = (remaining <= mem->h * (SUN_RCONST(1.0) + SUN_RCONST(1.0e-6)))
                    ? remaining
                    : mem->h;
    flag = lgnStep(mem, hstep);
    if (flag != LGN_SUCCESS) break;
    if (hstep == remaining) mem->tn = tout; /* exact arrival */
    nstloc++;
  }
  CopyOut(mem, tret, q, v);
  return flag;
}
