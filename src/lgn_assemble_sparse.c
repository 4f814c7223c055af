/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Sparse assembly of the scaled iteration matrix (the same blocks as the
 * dense lgn_assemble.c, spec numerics.md §2, modified-kinematics.md §2):
 *
 *   [[ cM M Ta + cC C Tv + cK K T ,  B^T ],  [ B T_c (+ f D_q(Bv) T) , 0 ]]
 *
 * T, Tv, Ta are block diagonal (lgn_tangent.c), so column j of X T combines
 * the columns of X in j's block only (lgnTangentColumnRange: in R^3 x SO(3)
 * only those of its translation or its rotation part). The pattern of A is
 * the union of the closed patterns of M, K, C and B (column j gets the rows
 * of all the columns it combines) and B^T. It
 * is built at the first assembly and then fixed, so KLU refactors with the
 * symbolic analysis of the first factorisation. An entry outside the pattern
 * (a model whose pattern grows) extends it and triggers a new analysis, as
 * does LGNResetSparsityPattern; LGNGetNumSparsityAnalyses counts them.
 * Assembly works in compressed columns; a CSR matrix A receives the values
 * through a fixed permutation.
 * ---------------------------------------------------------------------------*/

#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_sparse.h" /* first: lignum_config.h says whether KLU is there */
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

/* Views of M, B and B^T as evaluated at the current iterate, and the
 * patterns and colourings of the difference quotients (built once): for
 * K_t or C_t when the model gives none, and at index 2 for D_q(B v), whose
 * quotients use the colouring of K_t's pattern. */
static int RefreshViews(LGNMem mem)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  int flag = lgnCscView(mem->Mmat, &sp->M);
  if (flag == LGN_SUCCESS && mem->m > 0) flag = lgnCscView(mem->Bmat, &sp->B);
  if (flag == LGN_SUCCESS && mem->m > 0) flag = lgnCscTranspose(&sp->B, &sp->Bt);
  if (flag != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return flag;
  }
  if (!sp->have_dq_patterns &&
      (mem->stiffness == NULL || mem->damping == NULL ||
       (mem->m > 0 && mem->constr_index == LGN_CONSTR_INDEX2)))
    return lgnBuildDQPatterns(mem);
  return LGN_SUCCESS;
}

/* K and C as evaluated: views of the user's matrices, or the DQ storage. */
static int TangentViews(LGNMem mem, const LGNCsc **K, const LGNCsc **C)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  int flag = LGN_SUCCESS;
  if (mem->stiffness != NULL) flag = lgnCscView(mem->Kmat, &sp->K);
  if (flag == LGN_SUCCESS && mem->damping != NULL) flag = lgnCscView(mem->Cmat, &sp->C);
  if (flag != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return flag;
  }
  *K = mem->stiffness != NULL ? &sp->K : &sp->Kdq;
  *C = mem->damping != NULL ? &sp->C : &sp->Cdq;
  return LGN_SUCCESS;
}

/* The pattern of A (keeping the old one's entries when extending it), its
 * CSR permutation, and A's index arrays. */
static int BuildPattern(LGNMem mem, const LGNCsc *K, const LGNCsc *C)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  const sunindextype nv = mem->nv, m = mem->m, n = nv + m;
  const LGNCsc *src[3];
  LGNCsc P;
  sunindextype *mark = sp->mark, *list = sp->list;
  LGNColumnBuilder cb;
  sunindextype i, j, k, k0, k1, p, nnz;
  int s, flag;

  memset(&P, 0, sizeof P);
  src[0] = &sp->M;
  src[1] = K;
  src[2] = C;
  cb.mark = sp->mark;
  cb.list = sp->list;
  flag = lgnCscReserve(&P, n, n, SUNMAX(sp->A.cap, 4 * (sp->M.colptr[nv] + nv)));
  if (flag == LGN_SUCCESS) P.colptr[0] = 0;
  for (j = 0; j < n && flag == LGN_SUCCESS; j++) {
    cb.col = j;
    cb.cnt = 0;
    if (j < nv) {
      lgnTangentColumnRange(mem, j, &k0, &k1);
      for (k = k0; k < k1; k++) {
        for (s = 0; s < 3; s++)
          if (src[s]->colptr != NULL && src[s]->ncols == nv)
            for (p = src[s]->colptr[k]; p < src[s]->colptr[k + 1]; p++)
              lgnColumnAddRow(&cb, src[s]->rowind[p]);
        if (m > 0)
          for (p = sp->B.colptr[k]; p < sp->B.colptr[k + 1]; p++)
            lgnColumnAddRow(&cb, nv + sp->B.rowind[p]);
      }
    } else {
      for (p = sp->Bt.colptr[j - nv]; p < sp->Bt.colptr[j - nv + 1]; p++)
        lgnColumnAddRow(&cb, sp->Bt.rowind[p]);
    }
    if (sp->have_pattern)
      for (p = sp->A.colptr[j]; p < sp->A.colptr[j + 1]; p++) lgnColumnAddRow(&cb, sp->A.rowind[p]);
    flag = lgnCscAppendColumn(&P, &cb);
  }
  for (i = 0; i < n; i++) mark[i] = -1;
  nnz = flag == LGN_SUCCESS ? P.colptr[n] : 0;
  if (flag == LGN_SUCCESS && SUNSparseMatrix_NNZ(mem->A) < nnz)
    flag = SUNSparseMatrix_Reallocate(mem->A, nnz) == 0 ? LGN_SUCCESS : LGN_MEM_FAIL;
  if (flag == LGN_SUCCESS && SUNSparseMatrix_SparseType(mem->A) == CSR_MAT) {
    sunindextype *perm = (sunindextype *)realloc(sp->csr_perm, (size_t)SUNMAX(nnz, 1) * sizeof *perm);
    if (perm == NULL) flag = LGN_MEM_FAIL;
    else sp->csr_perm = perm;
  }
  if (flag != LGN_SUCCESS) {
    lgnCscFree(&P);
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  lgnCscFree(&sp->A);
  sp->A = P;

  if (SUNSparseMatrix_SparseType(mem->A) == CSC_MAT) {
    memcpy(SUNSparseMatrix_IndexPointers(mem->A), P.colptr, (size_t)(n + 1) * sizeof(sunindextype));
    memcpy(SUNSparseMatrix_IndexValues(mem->A), P.rowind, (size_t)nnz * sizeof(sunindextype));
  } else {
    /* CSR of A = CSC of A^T: count rows, then place entries column by column */
    sunindextype *rowptr = SUNSparseMatrix_IndexPointers(mem->A);
    sunindextype *colind = SUNSparseMatrix_IndexValues(mem->A);
    memset(rowptr, 0, (size_t)(n + 1) * sizeof(sunindextype));
    for (p = 0; p < nnz; p++) rowptr[P.rowind[p] + 1]++;
    for (i = 0; i < n; i++) rowptr[i + 1] += rowptr[i];
    for (i = 0; i < n; i++) list[i] = rowptr[i];
    for (j = 0; j < n; j++)
      for (p = P.colptr[j]; p < P.colptr[j + 1]; p++) {
        sunindextype q   = list[P.rowind[p]]++;
        colind[q]        = j;
        sp->csr_perm[p]  = q;
      }
  }
  sp->have_pattern = SUNTRUE;
  sp->npattern++;
  if (sp->analysed) {
#if defined(LGN_HAVE_KLU)
    SUNLinSol_KLUReInit(mem->LS, mem->A, nnz, SUNKLU_REINIT_PARTIAL);
#endif
    sp->analysed = SUNFALSE;
  }
  return LGN_SUCCESS;
}

/* Column accumulation: rows outside the pattern of the current column are
 * reported as a miss. */
typedef struct {
  sunindextype col;          /* current column of A (the mark stamp) */
  const sunindextype *mark, *pos;
  sunrealtype *val;
  sunbooleantype miss;
} Column;

/* y(:, j) += coef * (X Tb)(:, j) with rows shifted by `shift`; Tb NULL is I.
 * xval overrides X's values (D_q(B v) lives on the pattern of B). */
static void AddTimesTangent(LGNMem mem, Column *col, const LGNCsc *X,
                            const sunrealtype *xval, sunindextype j,
                            const sunrealtype *T, sunrealtype coef,
                            sunindextype shift)
{
  const int b = (int)mem->blk_of[j];
  const sunindextype o = mem->blk_voff[b], nb = mem->blk_voff[b + 1] - o;
  const sunrealtype *Tb = T;
  sunindextype k, k0 = j, k1 = j + 1, p, r;
  sunrealtype f;

  if (X->colptr == NULL || X->ncols != mem->nv) return;
  if (xval == NULL) xval = X->val;
  if (Tb != NULL && !lgnBlockIsIdentity(mem, b)) {
    Tb += mem->blk_toff[b];
    lgnTangentColumnRange(mem, j, &k0, &k1);
  } else {
    Tb = NULL;
  }
  for (k = k0; k < k1; k++) {
    f = coef * (Tb != NULL ? Tb[(k - o) + (j - o) * nb] : SUN_RCONST(1.0));
    if (f == SUN_RCONST(0.0)) continue;
    for (p = X->colptr[k]; p < X->colptr[k + 1]; p++) {
      r = X->rowind[p] + shift;
      if (col->mark[r] != col->col) {
        col->miss = SUNTRUE;
        continue;
      }
      col->val[col->pos[r]] += f * xval[p];
    }
  }
}

static sunbooleantype FillValues(LGNMem mem, const LGNCsc *K, const LGNCsc *C,
                                 sunrealtype cM, sunrealtype cC, sunrealtype cK,
                                 sunbooleantype use_tangent)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  const sunindextype nv = mem->nv, m = mem->m, n = nv + m;
  const sunbooleantype exact = use_tangent && mem->kinematics == LGN_KINEMATICS_EXACT;
  const sunbooleantype idx2 = mem->constr_index == LGN_CONSTR_INDEX2;
  const sunrealtype *Tk = use_tangent ? mem->Tm : NULL;
  const sunrealtype *Tb = !use_tangent ? NULL : (idx2 ? (exact ? mem->Tv : NULL) : mem->Tm);
  Column col;
  sunindextype j, p;

  col.mark = sp->mark;
  col.pos  = sp->pos;
  col.val  = sp->A.val;
  col.miss = SUNFALSE;
  for (j = 0; j < n; j++) {
    col.col = j;
    for (p = sp->A.colptr[j]; p < sp->A.colptr[j + 1]; p++) {
      sp->mark[sp->A.rowind[p]] = j;
      sp->pos[sp->A.rowind[p]]  = p;
      sp->A.val[p]              = SUN_RCONST(0.0);
    }
    if (j >= nv) { /* B^T */
      for (p = sp->Bt.colptr[j - nv]; p < sp->Bt.colptr[j - nv + 1]; p++) {
        if (sp->mark[sp->Bt.rowind[p]] != j) col.miss = SUNTRUE;
        else sp->A.val[sp->pos[sp->Bt.rowind[p]]] += sp->Bt.val[p];
      }
      continue;
    }
    AddTimesTangent(mem, &col, &sp->M, NULL, j, exact ? mem->Ta : NULL, cM, 0);
    if (cC != SUN_RCONST(0.0)) AddTimesTangent(mem, &col, C, NULL, j, exact ? mem->Tv : NULL, cC, 0);
    if (cK != SUN_RCONST(0.0)) AddTimesTangent(mem, &col, K, NULL, j, Tk, cK, 0);
    if (m > 0) {
      AddTimesTangent(mem, &col, &sp->B, NULL, j, Tb, SUN_RCONST(1.0), nv);
      /* index 2: + (1/gamma') D_q(B v) T, with 1/gamma' = cK/cC */
      if (use_tangent && idx2 && cC != SUN_RCONST(0.0))
        AddTimesTangent(mem, &col, &sp->B, sp->Bvq, j, Tk, cK / cC, nv);
    }
  }
  for (j = 0; j < n; j++) sp->mark[j] = -1;
  return !col.miss;
}

int lgnAssembleSparse(LGNMem mem, sunrealtype t, sunrealtype cM,
                      sunrealtype cC, sunrealtype cK, sunbooleantype use_tangent)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  const LGNCsc *K, *C;
  sunindextype p, nnz;
  int flag;

  flag = RefreshViews(mem);
  if (flag == LGN_SUCCESS) flag = lgnEvalTangents(mem, t, cC, cK);
  if (flag == LGN_SUCCESS) flag = TangentViews(mem, &K, &C);
  if (flag == LGN_SUCCESS && use_tangent && mem->constr_index == LGN_CONSTR_INDEX2 &&
      mem->m > 0 && cC != SUN_RCONST(0.0))
    flag = lgnConstraintVelocityDQColored(mem, t);
  if (flag != LGN_SUCCESS) return flag;
  mem->nje++;

  if (!sp->have_pattern) flag = BuildPattern(mem, K, C);
  if (flag == LGN_SUCCESS && !FillValues(mem, K, C, cM, cC, cK, use_tangent)) {
    /* the model's pattern grew: extend A's and fill again */
    flag = BuildPattern(mem, K, C);
    if (flag == LGN_SUCCESS && !FillValues(mem, K, C, cM, cC, cK, use_tangent))
      flag = LGN_LSETUP_FAIL; /* cannot happen: the new pattern holds every entry */
  }
  if (flag != LGN_SUCCESS) return flag;

  nnz = sp->A.colptr[mem->nv + mem->m];
  if (SUNSparseMatrix_SparseType(mem->A) == CSC_MAT) {
    memcpy(SUNSparseMatrix_Data(mem->A), sp->A.val, (size_t)nnz * sizeof(sunrealtype));
  } else {
    sunrealtype *data = SUNSparseMatrix_Data(mem->A);
    for (p = 0; p < nnz; p++) data[sp->csr_perm[p]] = sp->A.val[p];
  }
  sp->analysed = SUNTRUE; /* the setup below analyses if needed */
  return LGN_SUCCESS;
}
