/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The owner of the integrator's memory record (the bottom layer of every
 * file that sees it; doc/architecture.md):
 *   - the guards of public functions (lgnAccessMem, lgnCheckVector) and
 *     error reporting through the record (lgnProcessError, lgnCallbackFlag);
 *   - allocation: the state (sized by the group), the work space (sized by
 *     nv and m), the block table of the group, the model matrices of the
 *     type of A and the sparse work space, and their sizes (lgnWorkSpace);
 *   - the arrays and scratch vectors of root finding (lgn_root.c uses them);
 *   - lgnInvalidate, the one place that knows which cached item depends on
 *     which setting: every setter calls it with what it changed.
 * ---------------------------------------------------------------------------*/

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "groups/lgn_group_impl.h"
#include "lgn_blockprec.h"
#include "lgn_dense_lu.h"
#include "lgn_halo.h"
#include "lgn_impl.h"
#include "lgn_klu_solve.h"
#include "lgn_sparse.h"
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

/* =============================================================================
 * Invalidation: what each change makes stale
 * ===========================================================================*/

/* Every cache of the record and the changes that make it stale:
 *
 *   cache                                  dropped by
 *   work space, block table (work_done)    GROUP, SIZES
 *   model matrices, sparse work, KLU copy  GROUP, SIZES, LINSOL
 *   (mat_done)
 *   sparsity patterns of A and of the DQ   PATTERN (and with the matrices)
 *   SUNLinSolInitialize done               LINSOL
 *   consistent vdot, lambda, a (ic_done)   GROUP, SIZES, STATE
 *   predictor history (h_prev), the next   GROUP, SIZES, STATE
 *   step size (hnext), the dense output
 *   constant M evaluated (mass_current)    GROUP, SIZES, LINSOL, MASS, STATE
 *   root finding's g at the last point     STATE (g is evaluated anew at the
 *   checked (rt_started), the pending      new t0 at the next LGNSolve)
 *   return of tn after a root
 *   factorised iteration matrix            every change, and MATRIX
 *   (lu_valid, klu_valid), Newton's last
 *   rate and multiplier noise level
 *
 * so that a setter only says what it changed, never which caches to drop. */
void lgnInvalidate(LGNMem mem, unsigned int what)
{
  if (what & (LGN_CHANGE_GROUP | LGN_CHANGE_SIZES)) {
    lgnFreeWork(mem); /* and the matrices; sizes or blocks are new */
  } else if (what & LGN_CHANGE_LINSOL) {
    lgnFreeMatrices(mem); /* reallocated for A's type at the next solve */
  } else if ((what & LGN_CHANGE_PATTERN) && mem->ls.sp != NULL) {
    mem->ls.sp->have_pattern     = SUNFALSE; /* rebuilt, not extended */
    mem->ls.sp->have_dq_patterns = SUNFALSE;
  }
  if (what & LGN_CHANGE_LINSOL) mem->ls.initialized = SUNFALSE;
  if (what & (LGN_CHANGE_STATE | LGN_CHANGE_METHOD | LGN_CHANGE_MODEL |
              LGN_CHANGE_MASS))
    mem->bdf.nhist = 0; /* the BDF history belongs to the old problem */
  if (what & LGN_CHANGE_STATE) {
    mem->ic_done     = SUNFALSE;
    mem->h_prev      = SUN_RCONST(0.0);
    mem->ec.hnext       = SUN_RCONST(0.0); /* error control starts anew */
    mem->ec.err_prev    = SUN_RCONST(0.0);
    mem->dense.valid = SUNFALSE;
    mem->rt.started  = SUNFALSE; /* root finding restarts at the new t0 */
    mem->rt.pending  = SUNFALSE;
    mem->out.valid   = SUNFALSE; /* the last output's vdot, lambda */
    mem->out.lvalid  = SUNFALSE; /* ... and its projected q, v */
  }
  if (what & (LGN_CHANGE_MASS | LGN_CHANGE_STATE)) mem->mass_current = SUNFALSE;
  if (what & (LGN_CHANGE_STATE | LGN_CHANGE_MODEL | LGN_CHANGE_METHOD))
    mem->ggl_Bn_valid = SUNFALSE; /* GGL's B(q_n) (Newmark family) */
  /* the factorised matrix in A no longer fits the model or method: the next
   * step of a modified Newton iteration rebuilds it */
  mem->nls.lu_valid  = SUNFALSE;
  mem->klu.valid = SUNFALSE; /* copied again after the next setup */
  if (what != LGN_CHANGE_MATRIX) {
    /* contraction rate and multiplier noise were seen with another model,
     * method or matrix */
    mem->nls.rate    = SUN_RCONST(0.0);
    mem->nls.lambda_noise   = SUN_RCONST(0.0);
    mem->nls.lambda_noise_h = SUN_RCONST(0.0);
  }
}

/* =============================================================================
 * Guards and error reporting
 * ===========================================================================*/

/* The guard every public function starts with. */
int lgnAccessMem(void *lgn_mem, const char *func, LGNMem *mem)
{
  if (lgn_mem == NULL) {
    lgnProcessError(NULL, LGN_MEM_NULL, __LINE__, func, __FILE__, MSG_NO_MEM);
    return LGN_MEM_NULL;
  }
  *mem = (LGNMem)lgn_mem;
  (*mem)->api_func = func; /* messages from below name this public function */
  return LGN_SUCCESS;
}

/* Check a vector argument of a public function: not NULL, with a data
 * array whose rank-local part (all of it on one process) has the expected
 * length. */
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
                    "%s has no data array (a serial, parallel or MPIPlusX "
                    "N_Vector is required).", name);
    return LGN_ILL_INPUT;
  }
  if (lgnLocalLength(x) != len) {
    lgnProcessError(mem, LGN_ILL_INPUT, __LINE__, func, __FILE__,
                    "%s has length %lld, but %lld is needed.", name,
                    (long long)lgnLocalLength(x), (long long)len);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

void lgnProcessError(LGNMem mem, int error_code, int line, const char *func,
                     const char *file, const char *msgfmt, ...)
{
  va_list ap;
  (void)line;
  (void)file;
  va_start(ap, msgfmt);
  /* the public function the user called, not the internal one that found
   * the error */
  lgnReportV(mem == NULL ? NULL : &mem->err, error_code,
             mem != NULL && mem->api_func != NULL ? mem->api_func : func, msgfmt, ap);
  va_end(ap);
}

static const char *CallbackName(LGNCallbackId cb)
{
  static const char *names[LGN_CB_COUNT] = {
    "mass matrix", "force", "constraint", "constraint Jacobian",
    "stiffness", "damping", "curvature", "constraint force",
    "constraint time derivative", "Lie group"};
  return names[cb];
}

static int UnrecoverableFlag(LGNCallbackId cb)
{
  switch (cb) {
  case LGN_CB_MASS:       return LGN_MASS_FAIL;
  case LGN_CB_FORCE:      return LGN_FORCE_FAIL;
  case LGN_CB_CONSTR:
  case LGN_CB_CONSTR_TIME: return LGN_CONSTR_FAIL;
  case LGN_CB_CONSTR_JAC:
  case LGN_CB_CONSTR_FORCE: return LGN_CONSTR_JAC_FAIL;
  case LGN_CB_GROUP:      return LGN_GROUP_FAIL;
  default:                return LGN_TANGENT_FAIL;
  }
}

/* Map the return value of a user callback (0 ok, > 0 recoverable, < 0 fatal)
 * to a flag and report it. With a fixed step size a recoverable failure
 * cannot be cured by a smaller step, so it is reported as
 * LGN_REPTD_CALLBACK_ERR; the state at t_n stays intact either way. */
int lgnCallbackFlag(LGNMem mem, LGNCallbackId cb, int retval, const char *func)
{
  int flag;
  if (retval == 0) return LGN_SUCCESS;
  if (retval > 0 && mem->ec.step_control == LGN_STEP_ADAPTIVE) {
    return LGN_RECOVERABLE; /* retried with a smaller step (lgn_newmark_adapt.c) */
  }
  if (retval > 0) {
    flag = LGN_REPTD_CALLBACK_ERR;
    lgnProcessError(mem, flag, __LINE__, func, __FILE__,
                    MSG_TIME "the %s function failed recoverably (returned %d)"
                    " and the fixed step size cannot be reduced.",
                    (double)mem->tn, CallbackName(cb), retval);
  } else {
    flag = UnrecoverableFlag(cb);
    lgnProcessError(mem, flag, __LINE__, func, __FILE__,
                    MSG_TIME "the %s function failed unrecoverably"
                    " (returned %d).",
                    (double)mem->tn, CallbackName(cb), retval);
  }
  return flag;
}

/* The first non-finite entry of n values, or -1. */
static sunindextype FirstNonFinite(const sunrealtype *x, sunindextype n)
{
  sunindextype i;
  if (lgnAllFinite(x, n)) return -1;
  for (i = 0; i < n; i++)
    if (!isfinite(x[i])) return i;
  return -1;
}

/* A callback's vector output: its return value (lgnCallbackFlag), then
 * every entry finite, else LGN_NONFINITE naming the callback, the entry
 * and the time. */
int lgnCallbackVector(LGNMem mem, LGNCallbackId cb, int retval, N_Vector x,
                      const char *func)
{
  sunindextype k;
  if (retval != 0) return lgnCallbackFlag(mem, cb, retval, func);
  k = FirstNonFinite(lgnData(x), lgnLocalLength(x));
  if (k < 0) return LGN_SUCCESS;
  lgnProcessError(mem, LGN_NONFINITE, __LINE__, func, __FILE__,
                  MSG_TIME "the %s function returned %g in entry %lld.",
                  (double)mem->tn, CallbackName(cb),
                  (double)N_VGetArrayPointer(x)[k], (long long)k);
  return LGN_NONFINITE;
}

/* The same for a matrix output (dense, or the stored entries of a sparse
 * one): a non-finite entry never reaches a factorisation. */
int lgnCallbackMatrix(LGNMem mem, LGNCallbackId cb, int retval, SUNMatrix A,
                      const char *func)
{
  sunindextype k, row, col;
  if (retval != 0) return lgnCallbackFlag(mem, cb, retval, func);
  if (lgnMatIsSparse(A)) {
    const sunindextype np = SUNSparseMatrix_NP(A);
    const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A);
    const sunindextype *ind = SUNSparseMatrix_IndexValues(A);
    const sunrealtype *val = SUNSparseMatrix_Data(A);
    sunindextype j;
    k = FirstNonFinite(val, ptr[np]);
    if (k < 0) return LGN_SUCCESS;
    for (j = 0; ptr[j + 1] <= k; j++) {}
    /* compressed columns: (ind[k], j); compressed rows: (j, ind[k]) */
    row = SUNSparseMatrix_SparseType(A) == CSC_MAT ? ind[k] : j;
    col = SUNSparseMatrix_SparseType(A) == CSC_MAT ? j : ind[k];
    lgnProcessError(mem, LGN_NONFINITE, __LINE__, func, __FILE__,
                    MSG_TIME "the %s function returned %g in entry (%lld, %lld).",
                    (double)mem->tn, CallbackName(cb), (double)val[k],
                    (long long)row, (long long)col);
    return LGN_NONFINITE;
  }
  k = FirstNonFinite(SM_DATA_D(A), SM_LDATA_D(A));
  if (k < 0) return LGN_SUCCESS;
  row = k % SUNDenseMatrix_Rows(A);
  col = k / SUNDenseMatrix_Rows(A);
  lgnProcessError(mem, LGN_NONFINITE, __LINE__, func, __FILE__,
                  MSG_TIME "the %s function returned %g in entry (%lld, %lld).",
                  (double)mem->tn, CallbackName(cb), (double)SUNDenseMatrix_Data(A)[k],
                  (long long)row, (long long)col);
  return LGN_NONFINITE;
}

/* =============================================================================
 * The block table: the leaves of the group, on which T is block diagonal
 * ===========================================================================*/

/* Count (pass 1, out == NULL) or record the leaves of G at offsets (qo, vo). */
static int FlattenGroup(LGNGroup G, sunindextype qo, sunindextype vo,
                        LGNMem out, int nblk)
{
  int nf, k;
  const LGNGroup *f;
  const sunindextype *qoff, *voff;
  if (lgnGroupProductFactors(G, &nf, &f, &qoff, &voff) == 0) {
    for (k = 0; k < nf; k++)
      nblk = FlattenGroup(f[k], qo + qoff[k], vo + voff[k], out, nblk);
    return nblk;
  }
  if (out != NULL) {
    out->blk.group[nblk] = G;
    out->blk.qoff[nblk]  = qo;
    out->blk.voff[nblk]  = vo;
  }
  return nblk + 1;
}

static void BlocksFree(LGNMem mem)
{
  free(mem->blk.voff);
  free(mem->blk.qoff);
  free(mem->blk.toff);
  free(mem->blk.of);
  free(mem->blk.group);
  mem->blk.voff = mem->blk.qoff = mem->blk.toff = mem->blk.of = NULL;
  mem->blk.group = NULL;
  mem->blk.n = 0;
  mem->blk.max = mem->blk.tlen = 0;
}

static int BlocksBuild(LGNMem mem)
{
  int b, nblk = FlattenGroup(mem->G, 0, 0, NULL, 0);
  sunindextype i, size;

  BlocksFree(mem);
  mem->blk.voff  = (sunindextype *)malloc((size_t)(nblk + 1) * sizeof(sunindextype));
  mem->blk.qoff  = (sunindextype *)malloc((size_t)(nblk + 1) * sizeof(sunindextype));
  mem->blk.toff  = (sunindextype *)malloc((size_t)(nblk + 1) * sizeof(sunindextype));
  mem->blk.of    = (sunindextype *)malloc((size_t)mem->nv * sizeof(sunindextype));
  mem->blk.group = (LGNGroup *)malloc((size_t)nblk * sizeof(LGNGroup));
  if (mem->blk.voff == NULL || mem->blk.qoff == NULL || mem->blk.toff == NULL ||
      mem->blk.of == NULL || mem->blk.group == NULL) {
    BlocksFree(mem);
    return LGN_MEM_FAIL;
  }
  mem->blk.n = FlattenGroup(mem->G, 0, 0, mem, 0);
  mem->blk.voff[nblk] = mem->nv;
  mem->blk.qoff[nblk] = mem->nq;
  mem->blk.toff[0]    = 0;
  for (b = 0; b < nblk; b++) {
    size = mem->blk.voff[b + 1] - mem->blk.voff[b];
    mem->blk.max = SUNMAX(mem->blk.max, size);
    mem->blk.toff[b + 1] = mem->blk.toff[b] + (lgnBlockIsIdentity(mem, b) ? 0 : size * size);
    for (i = mem->blk.voff[b]; i < mem->blk.voff[b + 1]; i++) mem->blk.of[i] = b;
  }
  mem->blk.tlen = mem->blk.toff[nblk];
  return LGN_SUCCESS;
}

/* =============================================================================
 * A run across ranks: the agreement on failures, and reductions
 * ===========================================================================*/

/* The flag every rank goes on with (lgnParallelAgree; lgnAgree in
 * lgn_impl.h calls this across ranks only). A rank that did not fail itself
 * (or only recoverably) reports the failure of the other rank (the failing rank has reported what
 * failed); recoverable flags stay silent, as they are on one process. */
int lgnAgreeRanks(LGNMem mem, int flag)
{
  int rank;
  const int agreed = lgnParallelAgree(mem->ranks.par, flag, &rank);
  if (agreed < 0 && flag >= 0 && agreed != LGN_CONV_FAILURE)
    LGN_ERROR(mem, agreed, MSG_TIME "failed on rank %d (flag %d): see its message.",
              (double)mem->tn, rank, agreed);
  return agreed;
}

/* =============================================================================
 * Allocation and release
 * ===========================================================================*/

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

/* The state vectors (cloned from q0 and v0 by LGNInit). */
void lgnFreeState(LGNMem mem)
{
  DestroyVector(&mem->q);
  DestroyVector(&mem->v);
  DestroyVector(&mem->vdot);
  DestroyVector(&mem->a);
  DestroyVector(&mem->q1);
  DestroyVector(&mem->v1);
  DestroyVector(&mem->vdot1);
  DestroyVector(&mem->dq.q);
  DestroyVector(&mem->dq.v);
  DestroyVector(&mem->rt.q);
  DestroyVector(&mem->rt.v);
  DestroyVector(&mem->out.lq); /* the last projected output (lgn_output.c) */
  DestroyVector(&mem->out.lv);
  mem->out.lvalid  = SUNFALSE;
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
  lgnKluCopyFree(&mem->klu.copy);
  mem->klu.valid = SUNFALSE;
  mem->mat_done = SUNFALSE;
  /* the pattern of A is built anew and may differ: KLU analyses again
   * (refactoring with the old analysis would write past its factors) */
  mem->ls.restart = SUNTRUE;
}

/* The last valid multipliers outlive the work space that holds them (a
 * setter of the sizes drops it; LGNGetMultipliers then still reports them,
 * never the zeros of a new work space): kept here, restored by
 * lgnAllocWork when m is the same. */
static void KeepMultipliers(LGNMem mem)
{
  const sunindextype m = mem->lambda != NULL ? lgnLocalLength(mem->lambda) : 0;
  if (mem->out.valid && mem->out.vdot != NULL) {
    /* the last output's consistent vdot and lambda (LGNGetAcceleration,
     * LGNGetMultipliers report them) */
    const size_t n = (size_t)(mem->nv + mem->m);
    free(mem->out.keep);
    mem->out.keep = (sunrealtype *)malloc(n * sizeof(sunrealtype));
    if (mem->out.keep != NULL) {
      memcpy(mem->out.keep, mem->out.vdot, n * sizeof(sunrealtype)); /* out_lambda follows */
      mem->out.keep_nv = mem->nv;
      mem->out.keep_m  = mem->m;
    }
  }
  if (!mem->lambda_valid || m == 0) return;
  free(mem->lambda_keep);
  mem->lambda_keep     = (sunrealtype *)malloc((size_t)m * sizeof(sunrealtype));
  mem->lambda_keep_len = mem->lambda_keep != NULL ? m : 0;
  if (mem->lambda_keep != NULL)
    memcpy(mem->lambda_keep, lgnData(mem->lambda), (size_t)m * sizeof(sunrealtype));
  mem->lambda_valid = SUNFALSE;
}

/* The kept output's vdot and lambda (KeepMultipliers) freed. */
static void FreeKeptOutput(LGNMem mem)
{
  free(mem->out.keep);
  mem->out.keep    = NULL;
  mem->out.keep_nv = mem->out.keep_m = 0;
}

static void RestoreMultipliers(LGNMem mem)
{
  if (mem->out.keep != NULL && mem->out.keep_nv == mem->nv && mem->out.keep_m == mem->m &&
      mem->out.vdot != NULL) {
    memcpy(mem->out.vdot, mem->out.keep, (size_t)(mem->nv + mem->m) * sizeof(sunrealtype));
    mem->out.valid = SUNTRUE;
  }
  FreeKeptOutput(mem);
  if (mem->lambda != NULL && mem->lambda_keep != NULL && mem->lambda_keep_len == mem->m) {
    memcpy(lgnData(mem->lambda), mem->lambda_keep, (size_t)mem->m * sizeof(sunrealtype));
    mem->lambda_valid = SUNTRUE;
  }
  free(mem->lambda_keep);
  mem->lambda_keep     = NULL;
  mem->lambda_keep_len = 0;
}

void lgnFreeWork(LGNMem mem)
{
  lgnFreeMatrices(mem);
  KeepMultipliers(mem);
  DestroyVector(&mem->lambda);
  DestroyVector(&mem->lambda1);
  DestroyVector(&mem->g);
  DestroyVector(&mem->rdyn);
  DestroyVector(&mem->phi);
  DestroyVector(&mem->rhs);
  DestroyVector(&mem->sol);
  DestroyVector(&mem->dq.g);
  DestroyVector(&mem->dq.r);
  DestroyVector(&mem->dq.z);
  DestroyVector(&mem->phit);
  DestroyVector(&mem->ranks.hx_b);
  DestroyVector(&mem->ranks.hx_x);
  free(mem->ranks.hx_ext);
  mem->ranks.hx_ext = mem->ranks.hx_ext2 = NULL;
  lgnWorkBlockFree(mem, LGN_WORK_STEP);
  mem->ggl_Bn_valid = SUNFALSE;
  lgnWorkBlockFree(mem, LGN_WORK_OUTPUT); /* the outputs' block (lgn_output.c) */
  mem->out.valid = SUNFALSE;
  DestroyVector(&mem->out.q);
  DestroyVector(&mem->out.v);
  free(mem->diag.red);
  mem->diag.red  = NULL;
  mem->diag.nred = 0;
  mem->diag.pivot = -1;
  mem->ec.a_step = NULL;
  mem->dense.valid = SUNFALSE;
  mem->h_prev = SUN_RCONST(0.0);
  lgnWorkBlockFree(mem, LGN_WORK_TANGENT);
  lgnWorkBlockFree(mem, LGN_WORK_BDF);
  mem->bdf.nhist = 0;
  BlocksFree(mem);
  mem->work_done = SUNFALSE;
  mem->ic_done = SUNFALSE;
  /* lambda_0 given with LGNSetInitialAcceleration went with the work space */
  mem->user_vdot0 = SUNFALSE;
}

/* Everything the record holds (LGNFree). */
/* The redundancy's arrays (lgn_redundancy.c): for m_user rows, B of the
 * kind the model matrices will have (sparse for a sparse A or a Krylov
 * solver, as lgnAllocMatrices decides), kept while those stay the same. */
int lgnAllocRedundancy(LGNMem mem)
{
  const sunindextype mu = mem->red.m_user, nv = mem->nv;
  const sunbooleantype sparse = mem->kry.on || (mem->ls.A != NULL && lgnMatIsSparse(mem->ls.A));
  const int type = mem->ls.A != NULL && lgnMatIsSparse(mem->ls.A)
                       ? (int)SUNSparseMatrix_SparseType(mem->ls.A) : CSC_MAT;
  if (mem->red.B != NULL && N_VGetLength(mem->red.full) == mu &&
      lgnMatIsSparse(mem->red.B) == sparse &&
      (sparse ? SUNSparseMatrix_Columns(mem->red.B) == nv &&
                    (int)SUNSparseMatrix_SparseType(mem->red.B) == type
              : SUNDenseMatrix_Columns(mem->red.B) == nv))
    return LGN_SUCCESS;
  lgnFreeRedundancy(mem);
  mem->red.rows = (sunindextype *)malloc((size_t)(3 * mu) * sizeof(sunindextype));
  mem->red.keep = mem->red.rows != NULL ? mem->red.rows + 2 * mu : NULL;
  mem->red.full = N_VNew_Serial(mu, mem->sunctx);
  mem->red.lam  = N_VNew_Serial(mu, mem->sunctx);
  mem->red.B    = sparse ? SUNSparseMatrix(mu, nv, SUNMAX(12 * mu, 1), type, mem->sunctx)
                         : SUNDenseMatrix(mu, nv, mem->sunctx);
  if (mem->red.rows == NULL || mem->red.full == NULL || mem->red.lam == NULL ||
      mem->red.B == NULL) {
    lgnFreeRedundancy(mem);
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  return LGN_SUCCESS;
}

/* A direct solver of the user's kind (SUNDIALS' dense LU, Lignum's, KLU)
 * for the n x n system of the kept rows, standing in for the user's (made
 * for all m_user rows) while rows are left out (lgn_ls.c). */
int lgnAllocRedundancySolver(LGNMem mem, sunindextype n)
{
  SUNLinearSolver LS = NULL;
  SUNMatrix A = NULL;
  N_Vector y  = N_VNew_Serial(n, mem->sunctx);
  if (y != NULL && lgnDenseLUSize(mem->ls.LS) >= 0) {
    A  = SUNDenseMatrix(n, n, mem->sunctx);
    LS = A != NULL ? LGNLinSol_Dense(y, A, mem->sunctx) : NULL;
  } else if (y != NULL && SUNLinSolGetID(mem->ls.LS) == SUNLINEARSOLVER_DENSE) {
    A  = SUNDenseMatrix(n, n, mem->sunctx);
    LS = A != NULL ? SUNLinSol_Dense(y, A, mem->sunctx) : NULL;
#if defined(LGN_HAVE_KLU)
  } else if (y != NULL && SUNLinSolGetID(mem->ls.LS) == SUNLINEARSOLVER_KLU) {
    A  = SUNSparseMatrix(n, n, SUNMAX(SUNSparseMatrix_NNZ(mem->ls.A), 1),
                         SUNSparseMatrix_SparseType(mem->ls.A), mem->sunctx);
    LS = A != NULL ? SUNLinSol_KLU(y, A, mem->sunctx) : NULL;
#endif
  } else if (y != NULL) {
    N_VDestroy(y);
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "Redundant constraints are left out (B has rank %lld of %lld): the system "
              "has %lld unknowns, and this linear solver cannot be remade for them by "
              "Lignum; size A for the kept rows, or use SUNLinSol_Dense, "
              "LGNLinSol_Dense or SUNLinSol_KLU.",
              (long long)mem->m, (long long)mem->red.m_user, (long long)n);
    return LGN_LS_MISMATCH;
  }
  if (y != NULL) N_VDestroy(y);
  if (LS == NULL) {
    if (A != NULL) SUNMatDestroy(A);
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  mem->red.Auser  = mem->ls.A;
  mem->red.LSuser = mem->ls.LS;
  mem->red.A = mem->ls.A = A;
  mem->red.LS = mem->ls.LS = LS;
  lgnInvalidate(mem, LGN_CHANGE_LINSOL);
  return LGN_SUCCESS;
}

/* The user's solver back in place of the stand-in (if any). */
void lgnFreeRedundancySolver(LGNMem mem)
{
  if (mem->red.LS == NULL) return;
  mem->ls.A  = mem->red.Auser;
  mem->ls.LS = mem->red.LSuser;
  SUNLinSolFree(mem->red.LS);
  SUNMatDestroy(mem->red.A);
  mem->red.A = NULL;
  mem->red.LS = NULL;
  mem->red.Auser = NULL;
  mem->red.LSuser = NULL;
  lgnInvalidate(mem, LGN_CHANGE_LINSOL);
}

void lgnFreeRedundancy(LGNMem mem)
{
  lgnFreeRedundancySolver(mem);
  free(mem->red.rows);
  mem->red.rows = mem->red.keep = NULL;
  DestroyVector(&mem->red.full);
  DestroyVector(&mem->red.lam);
  if (mem->red.B != NULL) SUNMatDestroy(mem->red.B);
  mem->red.B = NULL;
  if (mem->red.nout > 0) { /* the work space was made for the kept rows */
    mem->red.nout = 0;
    mem->m        = mem->red.m_user;
    lgnInvalidate(mem, LGN_CHANGE_SIZES);
  }
}

void lgnFreeAll(LGNMem mem)
{
  lgnFreeRedundancy(mem);
  lgnFreeWork(mem);
  lgnFreeKrylov(mem, SUNTRUE);
  lgnFreeState(mem);
  free(mem->ec.atol_vec);
  mem->ec.atol_vec = NULL;
  lgnFreeRoots(mem);
  lgnParallelFree(&mem->ranks.par);
  free(mem->lambda_keep); /* (kept by lgnFreeWork above) */
  mem->lambda_keep     = NULL;
  mem->lambda_keep_len = 0;
  FreeKeptOutput(mem);
}

/* =============================================================================
 * The Krylov solvers' matrix and vectors (lgn_krylov.c)
 * ===========================================================================*/

/* Lignum's own iteration matrix A (CSC, nv + m square: the products of
 * ATimes and the block preconditioner's blocks), the weights and a scratch
 * vector, (re)made for the current sizes; a new A drops the model matrices
 * and the block preconditioner built for the old one. */
int lgnAllocKrylov(LGNMem mem)
{
  const sunindextype n = mem->nv + mem->m;
  /* the Krylov solver's vectors: the owned unknowns (all but the ghosts) */
  const sunindextype nk = mem->ranks.nv_own + mem->m;
  if (mem->kry.own_A && mem->ls.A != NULL && SUNSparseMatrix_Rows(mem->ls.A) != n) {
    lgnFreeMatrices(mem);
    DestroyMatrix(&mem->ls.A);
  }
  /* remade on every rank when one needs it (making them is collective) */
  if (lgnMaxAll(mem, mem->kry.w != NULL && lgnLocalLength(mem->kry.w) != nk
                         ? SUN_RCONST(1.0)
                         : SUN_RCONST(0.0)) > SUN_RCONST(0.0)) {
    DestroyVector(&mem->kry.w);
    DestroyVector(&mem->kry.tmp);
  }
  if (mem->ls.A == NULL) {
    lgnFreeMatrices(mem);
    lgnBlockPrecFree(&mem->kry.bp);
    mem->ls.A     = SUNSparseMatrix(n, n, SUNMAX(10 * n, 1), CSC_MAT, mem->sunctx);
    mem->kry.own_A = mem->ls.A != NULL ? SUNTRUE : SUNFALSE;
  }
  if (mem->kry.w == NULL) mem->kry.w = lgnParallelNewVector(mem->ranks.par, nk, mem->sunctx);
  if (mem->kry.tmp == NULL) mem->kry.tmp = lgnParallelNewVector(mem->ranks.par, nk, mem->sunctx);
  if (lgnAgree(mem, mem->ls.A == NULL || mem->kry.w == NULL || mem->kry.tmp == NULL
                        ? LGN_MEM_FAIL
                        : LGN_SUCCESS) != LGN_SUCCESS) {
    lgnFreeKrylov(mem, SUNFALSE);
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  return LGN_SUCCESS;
}

/* Lignum's A (the model matrices made for it go too), the vectors and the
 * block preconditioner; settings: its partition as well (LGNFree). */
void lgnFreeKrylov(LGNMem mem, sunbooleantype settings)
{
  if (mem->kry.own_A) {
    lgnFreeMatrices(mem);
    DestroyMatrix(&mem->ls.A);
    mem->kry.own_A = SUNFALSE;
  }
  DestroyVector(&mem->kry.w);
  DestroyVector(&mem->kry.tmp);
  lgnBlockPrecFree(&mem->kry.bp);
  if (settings) {
    free(mem->kry.bp_bodies);
    mem->kry.bp_bodies = NULL;
  }
}

/* =============================================================================
 * Root finding: the arrays of LGNRootInit and the vectors handed to g
 * ===========================================================================*/

/* Root finding off: its arrays and scratch vectors released, nrtfn = 0. */
void lgnFreeRoots(LGNMem mem)
{
  free(mem->rt.glo);
  free(mem->rt.iroots);
  free(mem->rt.gactive);
  mem->rt.glo = mem->rt.ghi = mem->rt.grout = NULL;
  mem->rt.iroots = mem->rt.rootdir = NULL;
  mem->rt.gactive = NULL;
  DestroyVector(&mem->rt.q);
  DestroyVector(&mem->rt.v);
  mem->rt.nrtfn      = 0;
  mem->rt.gfun       = NULL;
  mem->rt.started = SUNFALSE;
  mem->rt.pending = SUNFALSE;
}

/* The scratch q and v handed to g: clones of the state (LGNInit done). */
int lgnAllocRootVectors(LGNMem mem)
{
  /* made again on every rank when one lacks them (collective clones) */
  if (lgnMaxAll(mem, mem->rt.q == NULL || mem->rt.v == NULL ? SUN_RCONST(1.0)
                                                            : SUN_RCONST(0.0)) ==
      SUN_RCONST(0.0))
    return LGN_SUCCESS;
  DestroyVector(&mem->rt.q);
  DestroyVector(&mem->rt.v);
  mem->rt.q = N_VClone(mem->q);
  mem->rt.v = N_VClone(mem->v);
  if (mem->rt.q == NULL || mem->rt.v == NULL) {
    DestroyVector(&mem->rt.q);
    DestroyVector(&mem->rt.v);
    return LGN_MEM_FAIL;
  }
  return LGN_SUCCESS;
}

/* Arrays for nrtfn > 0 root functions (directions 0, all active); on
 * failure root finding is off. No message: the caller (LGNRootInit)
 * reports. The vectors handed to g are cloned by LGNSolve
 * (lgnAllocRootVectors): cloning an MPI vector is collective, and
 * LGNRootInit is not. */
int lgnAllocRoots(LGNMem mem, int nrtfn)
{
  /* sizes in size_t (3 nrtfn overflows an int; LGNRootInit refuses
   * nrtfn > LGN_MAX_ROOTS); the old arrays stay until the new ones exist */
  const size_t n = (size_t)nrtfn;
  sunrealtype *glo  = (sunrealtype *)calloc(3 * n, sizeof(sunrealtype));
  int *iroots       = (int *)calloc(2 * n, sizeof(int));
  sunbooleantype *gactive = (sunbooleantype *)calloc(n, sizeof(sunbooleantype));
  int i;
  if (glo == NULL || iroots == NULL || gactive == NULL) {
    free(glo);
    free(iroots);
    free(gactive);
    return LGN_MEM_FAIL;
  }
  lgnFreeRoots(mem);
  mem->rt.glo     = glo;
  mem->rt.iroots  = iroots;
  mem->rt.gactive = gactive;
  mem->rt.ghi     = mem->rt.glo + nrtfn;
  mem->rt.grout   = mem->rt.glo + 2 * nrtfn;
  mem->rt.rootdir = mem->rt.iroots + nrtfn;
  for (i = 0; i < nrtfn; i++) mem->rt.gactive[i] = SUNTRUE;
  mem->rt.nrtfn = nrtfn;
  return LGN_SUCCESS;
}

/* The state vectors, cloned from q0 and v0 (the sizes of the group). */
int lgnAllocState(LGNMem mem, N_Vector q0, N_Vector v0)
{
  lgnFreeWork(mem);
  lgnFreeState(mem);
  free(mem->lambda_keep); /* a new problem: the old multipliers are not its */
  mem->lambda_keep     = NULL;
  mem->lambda_keep_len = 0;
  FreeKeptOutput(mem);
  mem->nq    = mem->G->nq;
  mem->nv    = mem->G->nv;
  mem->ranks.nq_own = mem->nq; /* without ghosts (lgnAllocWork sets them) */
  mem->ranks.nv_own = mem->nv;
  mem->q     = N_VClone(q0);
  mem->q1    = N_VClone(q0);
  mem->dq.q  = N_VClone(q0);
  mem->v     = N_VClone(v0);
  mem->vdot  = N_VClone(v0);
  mem->a     = N_VClone(v0);
  mem->v1    = N_VClone(v0);
  mem->vdot1 = N_VClone(v0);
  mem->dq.v  = N_VClone(v0);
  /* every rank clones every vector (cloning an MPI vector is collective) */
  if (mem->q == NULL || mem->q1 == NULL || mem->dq.q == NULL ||
      mem->v == NULL || mem->vdot == NULL || mem->a == NULL ||
      mem->v1 == NULL || mem->vdot1 == NULL || mem->dq.v == NULL) {
    lgnFreeState(mem);
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  /* defined before the consistent values are computed (the getters) */
  N_VConst(SUN_RCONST(0.0), mem->vdot);
  N_VConst(SUN_RCONST(0.0), mem->a);
  mem->malloc_done = SUNTRUE;
  return LGN_SUCCESS;
}

/* Work space: everything whose size depends on nv and m (and the group's
 * block structure). Allocated lazily at the first LGNSolve (so the model
 * may be described in any order) and again after lgnInvalidate drops it. */

/* The algebraic unknowns after the velocities: lambda, and mu under GGL
 * (before the work arrays: the linear solver is checked against them). */
void lgnSetAlgebraicSize(LGNMem mem)
{
  mem->nalg = mem->constr_index == LGN_CONSTR_GGL ? 2 * mem->m : mem->m;
}

int lgnAllocWork(LGNMem mem)
{
  sunindextype nv = mem->nv, m = mem->m;
  SUNContext ctx = mem->sunctx;
  int fail = 0;

  lgnFreeWork(mem);
  lgnSetAlgebraicSize(mem);
  /* every rank allocates or none (the vectors below are made collectively) */
  fail = lgnAgree(mem, BlocksBuild(mem) != LGN_SUCCESS ? LGN_MEM_FAIL : LGN_SUCCESS) !=
         LGN_SUCCESS;
  if (!fail) {
    /* the sizes of the weighted RMS norms: nv and m of all ranks */
    sunrealtype sizes[3];
    mem->ranks.nv_own = nv;
    mem->ranks.nq_own = mem->nq;
#if defined(LGN_HAVE_MPI)
    if (mem->ranks.halo != NULL) lgnHaloOwnedLengths(mem->ranks.halo, &mem->ranks.nq_own, &mem->ranks.nv_own);
#endif
    sizes[0] = (sunrealtype)mem->ranks.nv_own;
    sizes[1] = (sunrealtype)m;
    sizes[2] = m == 0 ? SUN_RCONST(1.0) : SUN_RCONST(0.0);
    if (mem->ranks.par != NULL) { /* ghost bodies on every rank or on none */
      const sunrealtype any = lgnMaxAll(mem, mem->ranks.halo != NULL ? SUN_RCONST(1.0) : SUN_RCONST(0.0));
      const sunrealtype all = -lgnMaxAll(mem, mem->ranks.halo != NULL ? SUN_RCONST(-1.0) : SUN_RCONST(0.0));
      if (any != all) {
        LGN_ERROR(mem, LGN_ILL_INPUT,
                  "Ghost bodies (LGNSetHalo) are set on some ranks only: set them on "
                  "every rank or on none.");
        lgnFreeWork(mem);
        return LGN_ILL_INPUT;
      }
    }
    lgnSumAll(mem, sizes, 3);
    mem->ranks.nv_all = sizes[0];
    mem->ranks.m_all  = sizes[1];
    if (sizes[1] > SUN_RCONST(0.0) && sizes[2] > SUN_RCONST(0.0)) {
      /* the step takes the constrained path on every rank or on none */
      LGN_ERROR(mem, LGN_ILL_INPUT,
                "%g of %d ranks have no constraints (m = 0) while others have: "
                "give every rank constraints, or none.",
                (double)sizes[2], lgnParallelSize(mem->ranks.par));
      lgnFreeWork(mem);
      return LGN_ILL_INPUT;
    }
  }
  if (!fail) {
    /* every rank makes every vector, whatever failed (collective types) */
    mem->g    = N_VClone(mem->v);
    mem->rdyn = N_VClone(mem->v);
    mem->dq.g = N_VClone(mem->v);
    mem->dq.r = N_VClone(mem->v);
    mem->rhs  = lgnParallelNewVector(mem->ranks.par, nv + mem->nalg, ctx);
    mem->sol  = lgnParallelNewVector(mem->ranks.par, nv + mem->nalg, ctx);
    fail = (mem->g == NULL || mem->rdyn == NULL || mem->dq.g == NULL ||
            mem->dq.r == NULL || mem->rhs == NULL ||
            mem->sol == NULL);
    if (mem->ranks.halo != NULL) { /* the owned unknowns of a solve (lgn_ghosts.c) */
      mem->ranks.hx_b   = lgnParallelNewVector(mem->ranks.par, mem->ranks.nv_own + m, ctx);
      mem->ranks.hx_x   = lgnParallelNewVector(mem->ranks.par, mem->ranks.nv_own + m, ctx);
      mem->ranks.hx_ext = (sunrealtype *)malloc((size_t)(2 * (nv + m)) * sizeof(sunrealtype));
      fail = fail || mem->ranks.hx_b == NULL || mem->ranks.hx_x == NULL || mem->ranks.hx_ext == NULL;
      if (mem->ranks.hx_ext != NULL) mem->ranks.hx_ext2 = mem->ranks.hx_ext + nv + m;
    }
    if (m > 0) {
      mem->lambda  = lgnParallelNewVector(mem->ranks.par, m, ctx);
      mem->lambda1 = lgnParallelNewVector(mem->ranks.par, m, ctx);
      mem->phi     = lgnParallelNewVector(mem->ranks.par, m, ctx);
      mem->dq.z    = lgnParallelNewVector(mem->ranks.par, m, ctx);
      mem->phit    = lgnParallelNewVector(mem->ranks.par, m, ctx);
      fail = fail || mem->lambda == NULL || mem->lambda1 == NULL || mem->phi == NULL ||
             mem->dq.z == NULL || mem->phit == NULL;
    }
  }
  if (!fail) {
    /* the step's arrays, T's blocks, the outputs (lgn_workspace.c) */
    fail = lgnWorkBlockAlloc(mem, LGN_WORK_STEP) != LGN_SUCCESS;
    fail = lgnWorkBlockAlloc(mem, LGN_WORK_TANGENT) != LGN_SUCCESS || fail;
    fail = lgnWorkBlockAlloc(mem, LGN_WORK_OUTPUT) != LGN_SUCCESS || fail;
    /* the redundant constraints of a singular matrix (lgn_diag.c) */
    mem->diag.red = (sunindextype *)malloc((size_t)SUNMAX(m, 1) * sizeof(sunindextype));
    fail          = fail || mem->diag.red == NULL;
  }
  if (lgnAgree(mem, fail ? LGN_MEM_FAIL : LGN_SUCCESS) != LGN_SUCCESS) {
    lgnFreeWork(mem);
    if (fail) LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  mem->ggl_Bn_valid = SUNFALSE;
  mem->out.valid   = SUNFALSE;
  if (m > 0) N_VConst(SUN_RCONST(0.0), mem->lambda);
  mem->lambda_valid = SUNFALSE;
  RestoreMultipliers(mem); /* the last valid ones, if m is the same */
  mem->work_done = SUNTRUE;
  return LGN_SUCCESS;
}

/* The work space on every rank when one lacks it (a setter dropped it on
 * that rank only: making its vectors is collective across ranks). A rank
 * whose work space is made again also computes its initial values again,
 * at the current state, as the rank whose model changed does. */
int lgnEnsureWork(LGNMem mem)
{
  const sunbooleantype had = mem->work_done;
  int flag;
  if (lgnMaxAll(mem, had ? SUN_RCONST(0.0) : SUN_RCONST(1.0)) == SUN_RCONST(0.0))
    return LGN_SUCCESS;
  flag = lgnAllocWork(mem);
  if (had) mem->ic_done = SUNFALSE;
  return flag;
}

/* The BDF history and work arrays (lgn_bdf.c), allocated once in one
 * block (lgn_workspace.c's BDF table) and counted by lgnWorkSpace. */
int lgnAllocBDF(LGNMem mem)
{
  if (mem->bdf.q != NULL) return LGN_SUCCESS;
  if (lgnWorkBlockAlloc(mem, LGN_WORK_BDF) != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  mem->bdf.nhist = 0;
  return LGN_SUCCESS;
}

/* A model matrix of the type of the iteration matrix: dense, or sparse in
 * A's format with room for nnz entries (a callback needing more calls
 * SUNSparseMatrix_Reallocate). */
static SUNMatrix NewModelMatrix(LGNMem mem, sunindextype rows,
                                sunindextype cols, sunindextype nnz)
{
  SUNMatrix S;
  if (!mem->ls.sparse) return SUNDenseMatrix(rows, cols, mem->sunctx);
  S = SUNSparseMatrix(rows, cols, SUNMAX(SUNMIN(nnz, rows * cols), 1),
                      mem->ls.sparsetype, mem->sunctx);
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
  mem->ls.sparse = lgnMatID(mem->ls.A) == SUNMATRIX_SPARSE;
  if (mem->ls.sparse) mem->ls.sparsetype = (int)SUNSparseMatrix_SparseType(mem->ls.A);
  for (b = 0; b < mem->blk.n; b++) {
    sunindextype size = mem->blk.voff[b + 1] - mem->blk.voff[b];
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
    if (!mem->ls.sparse) mem->Bvq = (sunrealtype *)calloc((size_t)(m * nv), sizeof(sunrealtype));
    fail = (mem->Bmat == NULL || mem->Bdq == NULL || (!mem->ls.sparse && mem->Bvq == NULL));
  }
  if (!fail && mem->ls.sparse) fail = lgnSparseWorkCreate(mem) != LGN_SUCCESS;
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
  const long int n = (long int)(mem->nv + (mem->constr_index == LGN_CONSTR_GGL ? 2 * mem->m
                                                                               : mem->m));
  if (mem->ls.sp != NULL) return mem->ls.sp->have_pattern ? (long int)mem->ls.sp->A.colptr[n] : 0L;
  /* dense: n^2, saturated rather than overflowing */
  return n > 0 && n > LONG_MAX / n ? LONG_MAX : n * n;
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
  if (mem->rt.nrtfn > 0) {                                   /* root finding        */
    rw += 3L * mem->rt.nrtfn + nq + nv;
    iw += 3L * mem->rt.nrtfn;
  }
  if (mem->work_done) {
    rw += 4 * nv + 2 * (nv + (long int)mem->nalg) + 4 * m; /* g ... sol; lambda ... */
    rw += (long int)lgnWorkBlockLength(mem, LGN_WORK_STEP);    /* the work blocks */
    rw += (long int)lgnWorkBlockLength(mem, LGN_WORK_TANGENT); /* (lgn_workspace.c) */
    rw += (long int)lgnWorkBlockLength(mem, LGN_WORK_OUTPUT);
    if (mem->out.q != NULL) rw += nq + nv;                /* LGNGetDky's q, v    */
    if (mem->out.lq != NULL) rw += nq + nv;               /* the last output's   */
    iw += 3 * (mem->blk.n + 1) + nv + mem->blk.n;           /* block tables        */
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
    lgnKluCopySpace(mem->klu.copy, &rw, &iw);
  }
  if (lgnWorkBlockAllocated(mem, LGN_WORK_BDF)) /* the BDF history (lgnAllocBDF) */
    rw += (long int)lgnWorkBlockLength(mem, LGN_WORK_BDF);
  if (mem->kry.own_A) MatrixSpace(mem->ls.A, &rw, &iw); /* Krylov: Lignum's A */
  if (mem->red.B != NULL) { /* redundant rows: the user's B, 2 vectors, the maps */
    MatrixSpace(mem->red.B, &rw, &iw);
    rw += 2L * (long int)mem->red.m_user;
    iw += 3L * (long int)mem->red.m_user;
  }
  if (mem->red.A != NULL) MatrixSpace(mem->red.A, &rw, &iw); /* the stand-in's matrix */
  if (mem->kry.w != NULL) rw += 2 * (long int)lgnLocalLength(mem->kry.w);
  lgnBlockPrecSpace(mem->kry.bp, &rw, &iw);
  *lenrw = rw;
  *leniw = iw;
}

/* =============================================================================
 * The sparse work space (lgn_sparse.h): patterns, maps and colourings
 * ===========================================================================*/

int lgnSparseWorkCreate(LGNMem mem)
{
  const sunindextype n = mem->nv + mem->m;
  sunindextype i;
  struct LGNSparseWorkRec *sp = (struct LGNSparseWorkRec *)calloc(1, sizeof *sp);
  if (sp == NULL) return LGN_MEM_FAIL;
  mem->ls.sp  = sp;
  sp->mark = (sunindextype *)malloc((size_t)n * sizeof(sunindextype));
  sp->list = (sunindextype *)malloc((size_t)n * sizeof(sunindextype));
  if (sp->mark == NULL || sp->list == NULL) {
    lgnSparseWorkFree(mem);
    return LGN_MEM_FAIL;
  }
  for (i = 0; i < n; i++) sp->mark[i] = -1;
  return LGN_SUCCESS;
}

void lgnSparseWorkFree(LGNMem mem)
{
  struct LGNSparseWorkRec *sp = mem->ls.sp;
  int k;
  if (sp == NULL) return;
  for (k = 0; k < LGN_NMAPS; k++) free(sp->map[k].off);
  lgnPatternMemoFree(&sp->Mseen);
  lgnPatternMemoFree(&sp->Bseen);
  lgnPatternMemoFree(&sp->Kseen);
  lgnPatternMemoFree(&sp->Cseen);
  lgnCscFree(&sp->A);
  lgnCscFree(&sp->M);
  lgnCscFree(&sp->B);
  lgnCscFree(&sp->Bt);
  lgnCscFree(&sp->K);
  lgnCscFree(&sp->C);
  lgnCscFree(&sp->Kdq);
  lgnCscFree(&sp->Cdq);
  lgnColoringFree(&sp->Kcol);
  lgnColoringFree(&sp->Ccol);
  free(sp->csr_perm);
  free(sp->Bvq);
  free(sp->mark);
  free(sp->list);
  free(sp);
  mem->ls.sp = NULL;
}

/* Reals and indices held by the sparse work space. */
void lgnSparseWorkSpace(const LGNMem mem, long int *rw, long int *iw)
{
  const struct LGNSparseWorkRec *sp = mem->ls.sp;
  const LGNCsc *all[8];
  const LGNPatternMemo *seen[4];
  int k;
  if (sp == NULL) return;
  all[0] = &sp->A;  all[1] = &sp->M;  all[2] = &sp->B;   all[3] = &sp->Bt;
  all[4] = &sp->K;  all[5] = &sp->C;  all[6] = &sp->Kdq; all[7] = &sp->Cdq;
  for (k = 0; k < 8; k++) {
    if (all[k]->val != NULL) *rw += (long int)all[k]->cap; /* not A's, if CSC */
    *iw += (long int)(all[k]->cap + all[k]->capcol);
  }
  seen[0] = &sp->Mseen; seen[1] = &sp->Bseen; seen[2] = &sp->Kseen; seen[3] = &sp->Cseen;
  for (k = 0; k < 4; k++)
    *iw += (long int)(seen[k]->capp + (seen[k]->perm != NULL ? 2 : 1) * seen[k]->cap);
  for (k = 0; k < LGN_NMAPS; k++) *iw += (long int)sp->map[k].cap;
  *rw += (long int)sp->Bvq_cap;
  *iw += 2L * (long int)(mem->nv + mem->m);
  if (sp->csr_perm != NULL) *iw += (long int)sp->A.cap;
  if (sp->Kcol.ptr != NULL) *iw += (long int)(sp->Kcol.ncolors + 1 + mem->nv);
  if (sp->Ccol.ptr != NULL) *iw += (long int)(sp->Ccol.ncolors + 1 + mem->nv);
}
