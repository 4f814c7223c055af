/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Sparse assembly of the scaled iteration matrix from the table of terms
 * of lgn_matrix.c (the same terms as the dense assembly):
 *
 *   [[ cM M TM + cC C TC + cK K TK ,  B^T ],  [ B TB + cBv D_q(B v) TK , 0 ]]
 *
 * The T-like factors are block diagonal (lgn_tangent.c), so column j of X T combines
 * the columns of X in j's block only (lgnTangentColumnRange: in R^3 x SO(3)
 * only those of its translation or its rotation part). The pattern of A is
 * the union of the closed patterns of M, K, C and B (column j gets the rows
 * of all the columns it combines) and B^T. It
 * is built at the first assembly and then fixed, so KLU refactors with the
 * symbolic analysis of the first factorisation. An entry outside the pattern
 * (a model whose pattern grows) extends it and triggers a new analysis, as
 * does LGNResetSparsityPattern; LGNGetNumSparsityAnalyses counts them.
 *
 * Two paths. Building: once per pattern -- of A, or of a model matrix, as
 * its callback wrote it (compared with the one seen last, lgnCscViewSeen) --
 * a scatter map records where each entry of M, C, K and B lands in A; an
 * entry outside A's pattern is found here. Filling, at every assembly: the
 * terms go through the maps, with the same operations in the same order as
 * a search of each entry's row would give. Assembly works in compressed
 * columns; a CSR matrix A receives the values through a fixed permutation.
 * ---------------------------------------------------------------------------*/

#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h" /* first: lignum_config.h says whether KLU is there */
#include "lgn_sparse.h"
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

/* Invalidate the maps of the matrices whose pattern changed. */
static void Forget(struct LGNSparseWorkRec *sp, int s, sunbooleantype changed)
{
  if (changed) sp->map[s].valid = SUNFALSE;
}

/* Views of M, B and B^T as evaluated at the current iterate (B^T transposed
 * again only when B's pattern changed; the assembly reads B's values), and
 * the patterns and colourings of the difference quotients (built once): for
 * K_t or C_t when the model gives none, and at index 2 for D_q(B v), whose
 * quotients use the colouring of K_t's pattern. */
static int RefreshViews(LGNMem mem)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  sunbooleantype changed = SUNFALSE;
  int flag = lgnCscViewSeen(mem->Mmat, &sp->M, &sp->Mseen, &changed);
  Forget(sp, LGN_MAP_M, changed);
  if (flag == LGN_SUCCESS && mem->m > 0) {
    flag = lgnCscViewSeen(mem->Bmat, &sp->B, &sp->Bseen, &changed);
    Forget(sp, LGN_MAP_B, changed);
    Forget(sp, LGN_MAP_BT, changed);
    if (flag == LGN_SUCCESS && changed) flag = lgnCscTranspose(&sp->B, &sp->Bt);
    if (flag != LGN_SUCCESS) sp->Bseen.seen = SUNFALSE; /* transpose next time */
  }
  if (flag != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return flag;
  }
  if (!sp->have_dq_patterns &&
      (mem->stiffness == NULL || mem->damping == NULL ||
       (mem->m > 0 && mem->constr_index == LGN_CONSTR_INDEX2))) {
    Forget(sp, LGN_MAP_K, SUNTRUE);
    Forget(sp, LGN_MAP_C, SUNTRUE);
    return lgnBuildDQPatterns(mem);
  }
  return LGN_SUCCESS;
}

/* K and C as evaluated: views of the user's matrices, or the DQ storage. */
static int TangentViews(LGNMem mem, const LGNCsc **K, const LGNCsc **C)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  sunbooleantype changed = SUNFALSE;
  int flag = LGN_SUCCESS;
  if (mem->stiffness != NULL) {
    flag = lgnCscViewSeen(mem->Kmat, &sp->K, &sp->Kseen, &changed);
    Forget(sp, LGN_MAP_K, changed);
  }
  if (flag == LGN_SUCCESS && mem->damping != NULL) {
    flag = lgnCscViewSeen(mem->Cmat, &sp->C, &sp->Cseen, &changed);
    Forget(sp, LGN_MAP_C, changed);
  }
  if (flag != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return flag;
  }
  *K = mem->stiffness != NULL ? &sp->K : &sp->Kdq;
  *C = mem->damping != NULL ? &sp->C : &sp->Cdq;
  return LGN_SUCCESS;
}

/* The columns of A that combine the same columns of the model matrices
 * hold the same rows (BuildPattern gives them the same union): for j < nv,
 * every column k in j's range has j's rows. The maps rely on it. */
static sunbooleantype RangesAlike(LGNMem mem, const LGNCsc *P)
{
  sunindextype j, k, k0, k1, len;
  for (j = 0; j < mem->nv; j++) {
    len = P->colptr[j + 1] - P->colptr[j];
    lgnTangentColumnRange(mem, j, &k0, &k1);
    for (k = k0; k < k1; k++)
      if (k != j && (P->colptr[k + 1] - P->colptr[k] != len ||
                     memcmp(P->rowind + P->colptr[k], P->rowind + P->colptr[j],
                            (size_t)len * sizeof(sunindextype)) != 0))
        return SUNFALSE;
  }
  return SUNTRUE;
}

/* The pattern of A (keeping the old one's entries when extending it), its
 * CSR permutation, and A's index arrays; the maps into the old one go. */
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
  if (flag == LGN_SUCCESS && !RangesAlike(mem, &P)) {
    lgnCscFree(&P);
    return LGN_LSETUP_FAIL; /* cannot happen */
  }
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
  if (SUNSparseMatrix_SparseType(mem->A) == CSC_MAT) { /* filled in place */
    free(P.val);
    P.val = NULL;
  }
  lgnCscFree(&sp->A);
  sp->A = P;
  for (s = 0; s < LGN_NMAPS; s++) sp->map[s].valid = SUNFALSE;

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
    /* KLU only: a Krylov solver has no factorisation, another sparse
     * solver (LGNLinSol_PETSc) sees the new pattern itself */
    if (SUNLinSolGetID(mem->LS) == SUNLINEARSOLVER_KLU)
      SUNLinSol_KLUReInit(mem->LS, mem->A, nnz, SUNKLU_REINIT_PARTIAL);
#endif
    sp->analysed = SUNFALSE;
  }
  return LGN_SUCCESS;
}

/* One term of A's left block columns: coef (X T)(:, j), with the values val
 * on the pattern of X, whose entries go where map says. */
typedef struct {
  const LGNCsc *X;
  const sunrealtype *val;
  const sunrealtype *T;     /* block diagonal, packed (NULL: I)           */
  sunrealtype coef;
  int map;                  /* LGN_MAP_*                                  */
} Term;

static int AddTerm(LGNMem mem, Term *t, int nt, const LGNCsc *X,
                   const sunrealtype *val, const sunrealtype *T,
                   sunrealtype coef, int map)
{
  if (coef == SUN_RCONST(0.0) || X->colptr == NULL || X->ncols != mem->nv) return nt;
  t[nt].X    = X;
  t[nt].val  = val != NULL ? val : X->val;
  t[nt].T    = T;
  t[nt].coef = coef;
  t[nt].map  = map;
  return nt + 1;
}

/* The terms of A (lgn_matrix.c), in the order of their additions into an
 * entry. */
static int Terms(LGNMem mem, const LGNCsc *K, const LGNCsc *C,
                 const LGNMatrixTerms *x, Term *t)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  int nt = 0;
  nt = AddTerm(mem, t, nt, &sp->M, NULL, x->TM, x->cM, LGN_MAP_M);
  nt = AddTerm(mem, t, nt, C, NULL, x->TC, x->cC, LGN_MAP_C);
  nt = AddTerm(mem, t, nt, K, NULL, x->TK, x->cK, LGN_MAP_K);
  if (mem->m > 0) {
    nt = AddTerm(mem, t, nt, &sp->B, NULL, x->TB, SUN_RCONST(1.0), LGN_MAP_B);
    /* index 2: + cBv D_q(B v) TK */
    if (x->cBv != SUN_RCONST(0.0))
      nt = AddTerm(mem, t, nt, &sp->B, sp->Bvq, x->TK, x->cBv, LGN_MAP_B);
  }
  return nt;
}

/* Position of row r in column j of A (rows sorted), or -1. */
static sunindextype FindRow(const LGNCsc *A, sunindextype j, sunindextype r)
{
  sunindextype lo = A->colptr[j], hi = A->colptr[j + 1], mid;
  while (lo < hi) {
    mid = lo + (hi - lo) / 2;
    if (A->rowind[mid] < r) lo = mid + 1;
    else hi = mid;
  }
  return lo < A->colptr[j + 1] && A->rowind[lo] == r ? lo : -1;
}

/* Map s of X: entry p of column k (row r) is row r of column k of A, rows
 * shifted by nv for B; for the B^T block, row k of column nv + r. An entry
 * outside A's pattern sets *miss and leaves the map invalid. */
static int BuildMap(LGNMem mem, int s, const LGNCsc *X, sunbooleantype *miss)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  LGNScatterMap *map = &sp->map[s];
  const sunindextype nnz = X->colptr[X->ncols], shift = s == LGN_MAP_B ? mem->nv : 0;
  sunindextype k, p, q;

  map->valid = SUNFALSE;
  if (nnz > map->cap) {
    sunindextype *off = (sunindextype *)realloc(map->off, (size_t)nnz * sizeof *off);
    if (off == NULL) {
      LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
      return LGN_MEM_FAIL;
    }
    map->off = off;
    map->cap = nnz;
  }
  for (k = 0; k < X->ncols; k++)
    for (p = X->colptr[k]; p < X->colptr[k + 1]; p++) {
      if (s == LGN_MAP_BT) {
        q = FindRow(&sp->A, mem->nv + X->rowind[p], k);
      } else {
        q = FindRow(&sp->A, k, X->rowind[p] + shift);
        if (q >= 0) q -= sp->A.colptr[k];
      }
      if (q < 0) {
        *miss = SUNTRUE;
        return LGN_SUCCESS;
      }
      map->off[p] = q;
    }
  map->src   = X;
  map->valid = SUNTRUE;
  sp->nmapped++;
  return LGN_SUCCESS;
}

/* Map s of X unless it is there for the current patterns. */
static int NeedMap(LGNMem mem, int s, const LGNCsc *X, sunbooleantype *miss)
{
  const LGNScatterMap *map = &mem->sp->map[s];
  return map->valid && map->src == X ? LGN_SUCCESS : BuildMap(mem, s, X, miss);
}

/* The build path: the maps that the terms (and B^T) need. *miss: an entry
 * is outside A's pattern. */
static int MapTerms(LGNMem mem, const Term *t, int nt, sunbooleantype *miss)
{
  int i, flag = LGN_SUCCESS;
  *miss = SUNFALSE;
  for (i = 0; i < nt && flag == LGN_SUCCESS && !*miss; i++)
    flag = NeedMap(mem, t[i].map, t[i].X, miss);
  if (flag == LGN_SUCCESS && !*miss && mem->m > 0)
    flag = NeedMap(mem, LGN_MAP_BT, &mem->sp->B, miss);
  return flag;
}

/* acol += coef (X T)(:, j) for a term, acol being column j of A's values;
 * T's block of j (from o, size nb) combines columns k0 <= k < k1 of X. */
static void AddTimesTangent(const Term *t, const sunindextype *off,
                            sunindextype j, sunindextype o, sunindextype nb,
                            sunindextype k0, sunindextype k1,
                            const sunrealtype *Tb, sunrealtype *acol)
{
  const LGNCsc *X = t->X;
  const sunrealtype *xval = t->val;
  sunindextype k, p;
  sunrealtype f;

  if (Tb == NULL) {
    k0 = j;
    k1 = j + 1;
  }
  for (k = k0; k < k1; k++) {
    f = t->coef * (Tb != NULL ? Tb[(k - o) + (j - o) * nb] : SUN_RCONST(1.0));
    if (f == SUN_RCONST(0.0)) continue;
    for (p = X->colptr[k]; p < X->colptr[k + 1]; p++) acol[off[p]] += f * xval[p];
  }
}

/* The fill path: A's values (CSC, into val) from the terms through the maps.
 * Column j < nv: the terms in order, each over the columns k of its block
 * and their entries p in order; B^T: B's entries in order. */
static void FillValues(LGNMem mem, const Term *t, int nt, sunrealtype *val)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  const sunindextype nv = mem->nv, n = nv + mem->m;
  const sunindextype *colptr = sp->A.colptr, *bt = sp->map[LGN_MAP_BT].off;
  sunindextype j, p, k0, k1, o, nb;
  sunrealtype *acol;
  int b, i;

  memset(val, 0, (size_t)colptr[n] * sizeof *val);
  for (j = 0; j < nv; j++) {
    b  = (int)mem->blk_of[j];
    o  = mem->blk_voff[b];
    nb = mem->blk_voff[b + 1] - o;
    lgnTangentColumnRange(mem, j, &k0, &k1);
    acol = val + colptr[j];
    for (i = 0; i < nt; i++)
      AddTimesTangent(&t[i], sp->map[t[i].map].off, j, o, nb, k0, k1,
                      t[i].T != NULL && !lgnBlockIsIdentity(mem, b) ? t[i].T + mem->blk_toff[b] : NULL,
                      acol);
  }
  if (mem->m > 0)
    for (p = 0; p < sp->B.colptr[nv]; p++) val[bt[p]] += sp->B.val[p];
}

int lgnAssembleSparse(LGNMem mem, sunrealtype t, const LGNMatrixTerms *x)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  const LGNCsc *K, *C;
  Term terms[5];
  sunindextype p, nnz;
  sunrealtype *data;
  sunbooleantype miss;
  int nt, flag;

  flag = RefreshViews(mem);
  if (flag == LGN_SUCCESS) flag = lgnEvalTangents(mem, t, x->cC, x->cK);
  if (flag == LGN_SUCCESS) flag = TangentViews(mem, &K, &C);
  if (flag == LGN_SUCCESS && mem->m > 0 && x->cBv != SUN_RCONST(0.0))
    flag = lgnConstraintVelocityDQColored(mem, t);
  if (flag != LGN_SUCCESS) return flag;
  mem->nje++;

  nt = Terms(mem, K, C, x, terms);
  if (!sp->have_pattern) flag = BuildPattern(mem, K, C);
  if (flag == LGN_SUCCESS) flag = MapTerms(mem, terms, nt, &miss);
  if (flag == LGN_SUCCESS && miss) {
    /* the model's pattern grew: extend A's (which drops the maps) and map again */
    flag = BuildPattern(mem, K, C);
    if (flag == LGN_SUCCESS) flag = MapTerms(mem, terms, nt, &miss);
    if (flag == LGN_SUCCESS && miss)
      flag = LGN_LSETUP_FAIL; /* cannot happen: the new pattern holds every entry */
  }
  if (flag != LGN_SUCCESS) return flag;

  nnz  = sp->A.colptr[mem->nv + mem->m];
  data = SUNSparseMatrix_Data(mem->A);
  if (SUNSparseMatrix_SparseType(mem->A) == CSC_MAT) {
    FillValues(mem, terms, nt, data); /* A's indices are sp->A's */
  } else {
    FillValues(mem, terms, nt, sp->A.val);
    for (p = 0; p < nnz; p++) data[sp->csr_perm[p]] = sp->A.val[p];
  }
  sp->analysed = SUNTRUE; /* the setup below analyses if needed */
  return LGN_SUCCESS;
}
