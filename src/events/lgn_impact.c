/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * LGNApplyImpact: an impulse on a constrained system, and the restart.
 *
 * At the current state (t_n, q_n, v- = v_n), with the constraint rows B
 * (the kept ones, lgn_redundancy.c), the contact rows G (nc x nv, the
 * user's callback) and the restitution coefficient e, the velocity jump
 * dv = v+ - v- and the impulses Lambda (constraints), P (contacts) solve
 * the impulse saddle-point problem (Newton's impact law at every contact)
 *
 *   [ M  B^T  G^T ] [ dv     ]   [ 0                 ]
 *   [ B  0    0   ] [ Lambda ] = [ -(B v- + Phi_t)   ]    B v+ + Phi_t = 0
 *   [ G  0    0   ] [ P      ]   [ -(1 + e) G v-     ]    G v+ = -e G v-
 *
 * with M = M(q_n): the momentum balance M (v+ - v-) + B^T Lambda + G^T P = 0.
 * A dense model's matrix is factored by LAPACK (dgesv), a sparse one's by
 * KLU. The integrator then restarts from (t_n, q_n, v+), as after
 * LGNReInit (consistent accelerations and multipliers at the next step).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"
#if defined(LGN_HAVE_KLU)
#include <klu.h>
#endif

/* LAPACK: LU with partial pivoting and solve (32-bit integers). */
extern void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv,
                   double *b, const int *ldb, int *info);

#define LGN_IMPACT_MAX_DENSE 4000 /* a dense K of at most 128 MB */

/* K being assembled: dense (n x n, column-major) or triplets (for KLU). */
typedef struct {
  sunindextype n, nnz, cap;
  sunindextype *ti, *tj;
  sunrealtype *tx;
  sunrealtype *dense; /* n x n column-major, or NULL: triplets */
} KAssembly;

static int Add(KAssembly *K, sunindextype i, sunindextype j, sunrealtype x)
{
  if (K->dense != NULL) {
    K->dense[i + j * K->n] += x;
    return 0;
  }
  if (K->nnz == K->cap) {
    const sunindextype cap = 2 * K->cap + 64;
    sunindextype *ti = (sunindextype *)realloc(K->ti, (size_t)cap * sizeof *ti);
    sunindextype *tj = ti != NULL ? (sunindextype *)realloc(K->tj, (size_t)cap * sizeof *tj) : NULL;
    sunrealtype *tx  = tj != NULL ? (sunrealtype *)realloc(K->tx, (size_t)cap * sizeof *tx) : NULL;
    if (ti != NULL) K->ti = ti;
    if (tj != NULL) K->tj = tj;
    if (tx == NULL) return -1;
    K->tx  = tx;
    K->cap = cap;
  }
  K->ti[K->nnz] = i;
  K->tj[K->nnz] = j;
  K->tx[K->nnz] = x;
  K->nnz++;
  return 0;
}

/* A at (r0, c0), and its transpose at (c0, r0) when both. */
static int AddBlock(KAssembly *K, SUNMatrix A, sunindextype r0, sunindextype c0,
                    sunbooleantype both)
{
  sunindextype i, j, p;
  int fail = 0;
  if (lgnMatIsSparse(A)) {
    const sunindextype np = SUNSparseMatrix_NP(A);
    const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A);
    const sunindextype *ind = SUNSparseMatrix_IndexValues(A);
    const sunrealtype *val = SUNSparseMatrix_Data(A);
    const sunbooleantype csc = SUNSparseMatrix_SparseType(A) == CSC_MAT;
    for (j = 0; j < np; j++)
      for (p = ptr[j]; p < ptr[j + 1]; p++) {
        const sunindextype r = csc ? ind[p] : j, c = csc ? j : ind[p];
        fail = fail || Add(K, r0 + r, c0 + c, val[p]);
        if (both) fail = fail || Add(K, c0 + c, r0 + r, val[p]);
      }
    return fail;
  }
  for (j = 0; j < SM_COLUMNS_D(A); j++)
    for (i = 0; i < SM_ROWS_D(A); i++) {
      const sunrealtype x = SM_ELEMENT_D(A, i, j);
      if (x == SUN_RCONST(0.0)) continue;
      fail = fail || Add(K, r0 + i, c0 + j, x);
      if (both) fail = fail || Add(K, c0 + j, r0 + i, x);
    }
  return fail;
}

/* K x = b, x over b: 0, 1 singular, -1 memory. */
static int SolveK(KAssembly *K, sunrealtype *b)
{
  if (K->dense != NULL) {
    const int n = (int)K->n, one = 1;
    int info = 0, *ipiv = (int *)malloc((size_t)K->n * sizeof(int));
    if (ipiv == NULL) return -1;
    dgesv_(&n, &one, K->dense, &n, ipiv, b, &n, &info);
    free(ipiv);
    return info == 0 ? 0 : 1;
  }
#if defined(LGN_HAVE_KLU)
  {
    const sunindextype n = K->n;
    sunindextype *Ap = (sunindextype *)calloc((size_t)(n + 1), sizeof(sunindextype));
    sunindextype *Ai = (sunindextype *)malloc((size_t)SUNMAX(K->nnz, 1) * sizeof(sunindextype));
    sunrealtype *Ax  = (sunrealtype *)malloc((size_t)SUNMAX(K->nnz, 1) * sizeof(sunrealtype));
    klu_l_symbolic *S = NULL;
    klu_l_numeric *N  = NULL;
    klu_l_common c;
    sunindextype k;
    int flag = -1;
    if (Ap == NULL || Ai == NULL || Ax == NULL) goto done;
    /* triplets to compressed columns, then duplicates summed (KLU needs
     * each entry once) */
    for (k = 0; k < K->nnz; k++) Ap[K->tj[k] + 1]++;
    for (k = 0; k < n; k++) Ap[k + 1] += Ap[k];
    for (k = 0; k < K->nnz; k++) {
      const sunindextype q = Ap[K->tj[k]]++;
      Ai[q] = K->ti[k];
      Ax[q] = K->tx[k];
    }
    for (k = n; k > 0; k--) Ap[k] = Ap[k - 1];
    Ap[0] = 0;
    {
      /* sum duplicate (i, j) entries within each column */
      sunindextype *last = (sunindextype *)malloc((size_t)n * sizeof(sunindextype));
      sunindextype j, p, w = 0, start;
      if (last == NULL) goto done;
      for (k = 0; k < n; k++) last[k] = -1;
      for (j = 0; j < n; j++) {
        start = w;
        for (p = Ap[j]; p < Ap[j + 1]; p++) {
          if (last[Ai[p]] >= start) {
            Ax[last[Ai[p]]] += Ax[p];
          } else {
            last[Ai[p]] = w;
            Ai[w]       = Ai[p];
            Ax[w++]     = Ax[p];
          }
        }
        Ap[j] = start;
      }
      Ap[n] = w;
      free(last);
    }
    klu_l_defaults(&c);
    S = klu_l_analyze(n, Ap, Ai, &c);
    N = S != NULL ? klu_l_factor(Ap, Ai, Ax, S, &c) : NULL;
    if (N == NULL) {
      flag = c.status == KLU_OUT_OF_MEMORY ? -1 : 1;
      goto done;
    }
    flag = (klu_l_solve(S, N, n, 1, b, &c) && c.status == KLU_OK) ? 0 : 1;
  done:
    if (N != NULL) klu_l_free_numeric(&N, &c);
    if (S != NULL) klu_l_free_symbolic(&S, &c);
    free(Ap);
    free(Ai);
    free(Ax);
    return flag;
  }
#else
  return -1;
#endif
}

static int CheckImpactArgs(LGNMem mem, sunindextype nc, LGNContactJacFn G, sunrealtype e,
                           N_Vector v, N_Vector P)
{
  if (!mem->work_done || !mem->mat_done) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The integrator is not set up: call LGNApplyImpact after LGNSolve or "
              "LGNCalcIC (at a root: LGNReInit at the root's state first).");
    return LGN_ILL_INPUT;
  }
  if (mem->par != NULL || mem->halo != NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "LGNApplyImpact runs on one process only.");
    return LGN_ILL_INPUT;
  }
  if (nc <= 0 || G == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "%s illegal: give nc > 0 contact rows and their function.",
              G == NULL ? "G = NULL" : "nc <= 0");
    return LGN_ILL_INPUT;
  }
  if (!(e >= SUN_RCONST(0.0) && e <= SUN_RCONST(1.0))) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "e = %g illegal: the restitution coefficient lies in [0, 1].",
              (double)e);
    return LGN_ILL_INPUT;
  }
  if (v != NULL && lgnCheckVector(mem, v, mem->nv, "v", "LGNApplyImpact") != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (P != NULL) return lgnCheckVector(mem, P, nc, "P", "LGNApplyImpact");
  return LGN_SUCCESS;
}

int LGNApplyImpact(void *lgn_mem, sunindextype nc, LGNContactJacFn G, sunrealtype e,
                   N_Vector v, N_Vector P)
{
  LGNMem mem;
  KAssembly K;
  SUNMatrix Gm = NULL;
  sunrealtype *rhs = NULL, *gv = NULL;
  sunindextype nv, m, n, i;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem), ret;
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  flag = CheckImpactArgs(mem, nc, G, e, v, P);
  if (flag != LGN_SUCCESS) return flag;
  nv = mem->nv;
  m  = mem->m;
  n  = nv + m + nc;
  memset(&K, 0, sizeof K);
  K.n = n;
#if defined(LGN_HAVE_KLU)
  if (!mem->sparse || n <= 200) { /* small or dense: LAPACK; else KLU */
#else
  { /* LAPACK (no KLU in this build) */
#endif
    if (n > LGN_IMPACT_MAX_DENSE) {
      LGN_ERROR(mem, LGN_ILL_INPUT,
                "The impulse system has %lld unknowns: too many for a dense solve (use "
                "sparse matrices with a Lignum built with KLU).", (long long)n);
      return LGN_ILL_INPUT;
    }
    K.dense = (sunrealtype *)calloc((size_t)(n * n), sizeof(sunrealtype));
  }
  rhs = (sunrealtype *)calloc((size_t)n, sizeof(sunrealtype));
  gv  = (sunrealtype *)calloc((size_t)nc, sizeof(sunrealtype));
  Gm  = mem->sparse ? SUNSparseMatrix(nc, nv, 12 * nc, mem->sparsetype, mem->sunctx)
                    : SUNDenseMatrix(nc, nv, mem->sunctx);
  if (rhs == NULL || gv == NULL || Gm == NULL || (K.dense == NULL && !mem->sparse)) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    flag = LGN_MEM_FAIL;
    goto done;
  }
  /* M(q_n), B(q_n) and B v- + Phi_t; G(q_n) */
  flag = lgnEvalModelAt(mem, mem->tn, mem->q, mem->v, mem->Mmat, mem->g, mem->Bmat, m > 0);
  if (flag == LGN_SUCCESS && m > 0)
    flag = lgnConstraintVelocity(mem, mem->tn, mem->q, mem->Bmat, lgnData(mem->v), rhs + nv);
  if (flag == LGN_SUCCESS) {
    lgnMatClear(Gm);
    ret  = G(mem->tn, mem->q, Gm, mem->user_data);
    flag = ret < 0 ? LGN_CONSTR_JAC_FAIL : (ret > 0 ? LGN_REPTD_CALLBACK_ERR : LGN_SUCCESS);
    if (flag != LGN_SUCCESS)
      LGN_ERROR(mem, flag, MSG_TIME "the contact Jacobian function failed (%d).",
                (double)mem->tn, ret);
  }
  if (flag == LGN_SUCCESS &&
      !(mem->sparse ? lgnAllFinite(SUNSparseMatrix_Data(Gm),
                                   SUNSparseMatrix_IndexPointers(Gm)[SUNSparseMatrix_NP(Gm)])
                    : lgnAllFinite(SM_DATA_D(Gm), nc * nv))) {
    LGN_ERROR(mem, LGN_NONFINITE, MSG_TIME "the contact Jacobian G has a NaN or Inf entry.",
              (double)mem->tn);
    flag = LGN_NONFINITE;
  }
  if (flag != LGN_SUCCESS) goto done;
  for (i = 0; i < m; i++) rhs[nv + i] = -rhs[nv + i];  /* B dv = -(B v- + Phi_t) */
  lgnMatvec(Gm, lgnData(mem->v), gv, SUNFALSE);
  for (i = 0; i < nc; i++) rhs[nv + m + i] = -(SUN_RCONST(1.0) + e) * gv[i];
  /* K = [[M, B^T, G^T], [B, 0, 0], [G, 0, 0]] */
  if (AddBlock(&K, mem->Mmat, 0, 0, SUNFALSE) ||
      (m > 0 && AddBlock(&K, mem->Bmat, nv, 0, SUNTRUE)) || AddBlock(&K, Gm, nv + m, 0, SUNTRUE)) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    flag = LGN_MEM_FAIL;
    goto done;
  }
  ret = SolveK(&K, rhs);
  if (ret != 0) {
    flag = ret < 0 ? LGN_MEM_FAIL : LGN_LSETUP_FAIL;
    LGN_ERROR(mem, flag,
              ret < 0 ? MSG_TIME "a memory request failed in the impulse solve."
                      : MSG_TIME "the impulse system [[M, B^T, G^T], [B, 0, 0], [G, 0, 0]] is "
                                 "singular: contact rows depend on each other or on the "
                                 "constraints (or M is singular). Nothing was changed.",
              (double)mem->tn);
    goto done;
  }
  if (!lgnAllFinite(rhs, n)) {
    LGN_ERROR(mem, LGN_NONFINITE, MSG_TIME "the impulse solve gave NaN or Inf.",
              (double)mem->tn);
    flag = LGN_NONFINITE;
    goto done;
  }
  /* v+ = v- + dv; the impulses; a new start at t_n */
  for (i = 0; i < nv; i++) lgnData(mem->v)[i] += rhs[i];
  if (v != NULL) N_VScale(SUN_RCONST(1.0), mem->v, v);
  if (P != NULL) memcpy(N_VGetArrayPointer(P), rhs + nv + m, (size_t)nc * sizeof(sunrealtype));
  mem->user_vdot0 = SUNFALSE;
  mem->user_a0    = SUNFALSE;
  lgnInvalidate(mem, LGN_CHANGE_STATE);
done:
  free(K.dense);
  free(K.ti);
  free(K.tj);
  free(K.tx);
  free(rhs);
  free(gv);
  if (Gm != NULL) SUNMatDestroy(Gm);
  return flag;
}
