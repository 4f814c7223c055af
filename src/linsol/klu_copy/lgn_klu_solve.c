/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Lignum's own solves with KLU's factors (LGNSetOwnKLUSolves: opt-in, and
 * only for the versions of KLU and SUNDIALS whose unpublished layouts this
 * file reads, lgnKluCopySupported in lgn_ls.c). When a
 * factorisation by SUNLinSol_KLU is solved with a second time (lgn_ls.c),
 * lgnKluCopyRefresh copies the factors out of KLU's Numeric object
 * (klu_l_extract) into compressed columns with 32-bit indices, and
 * lgnKluCopySolve solves with them. After a refactorisation (klu_l_refactor:
 * the same pivots, so the same pattern) the refresh takes only the new
 * values, straight from KLU's packed columns, once it has checked that the
 * pattern is the copy's. KLU keeps its
 * factors in one packed array per block, with 64-bit indices: 16 bytes per
 * entry against 12 here. For klu_l_solve (a CSC matrix) the copy holds L
 * and U by rows (BuildRows; Lmap and Umap say where each of KLU's entries
 * went): each X[i] then takes its updates, in klu_l_solve's order, in a
 * register and is stored once, the permutation and scaling of b and x
 * fold into the row sweeps, and the values of the two rows before (L; the
 * two after in U), on the chain of dependences that limits a sparse
 * triangular solve on a banded matrix, are carried in registers. On the
 * 10000-body chain of the examples (n = 90000, 0.88 M entries in L + U
 * besides the diagonal) a solve took 0.64 ms with the factors in cache
 * (0.91 by columns), 0.88 ms from memory (1.02), before U's rows were kept
 * divided by its diagonal (ScaleRowsOfU), which takes the division out of
 * that chain (U's sweep 0.34 -> 0.27 ms on the chain); and
 * lgnKluCopyRefactor refactors into the copy by rows with KLU's pivots.
 *
 * By columns (klu_l_tsolve's), the solve does klu_l_tsolve's operations
 * (one right-hand side) on each entry in the same order, so it gives the
 * same result to the last bit when both are compiled without contractions
 * (fused multiply-add); by rows, L's sweep does klu_l_solve's operations
 * in its order too, U's takes its terms in klu_l_solve's order but divides
 * first, and agrees to round-off.
 *
 *   lgnKluCopyRefresh  copy the factors now in a SUNLinSol_KLU
 *   lgnKluCopySolve    solve A x = b with the copy
 *   lgnKluCopyFree, lgnKluCopySpace
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sundials/sundials_math.h>

#include "lgn_matops.h"
#include "lgn_klu_solve.h"

#if defined(LGN_KLU_COPY) /* else the stubs of lgn_klu_solve.h */

#include <sunlinsol/sunlinsol_klu.h>

/* =============================================================================
 * Storage
 * ===========================================================================*/

void lgnKluCopyFree(LGNKluCopy **copy)
{
  LGNKluCopy *c = *copy;
  if (c == NULL) return;
  free(c->Lp); free(c->Li); free(c->Lx);
  free(c->Up); free(c->Ui); free(c->Ux);
  free(c->Fp); free(c->Fi); free(c->Fx);
  free(c->P);  free(c->Q);  free(c->R);
  free(c->Lswap); free(c->Uswap);
  free(c->Udiag); free(c->Rs); free(c->X);
  free(c->Lrp); free(c->Urp); free(c->Lmap); free(c->Umap);
  free(c->Arp); free(c->Acol); free(c->Apos); free(c->Fpos);
  free(c->tmp);
  free(c);
  *copy = NULL;
}

/* Reals and integers held (32-bit indices count as half an integer of
 * sunindextype, the unit of LGNGetWorkSpace). */
void lgnKluCopySpace(const LGNKluCopy *c, long int *rw, long int *iw)
{
  size_t i32;
  if (c == NULL) return;
  *rw += (long int)(c->cap_l + c->cap_u + c->cap_f + 3 * c->cap_n);
  i32 = 8 * c->cap_n + 4 + c->cap_l + c->cap_u + c->cap_f;
  i32 += 2 * (c->cap_rn + 1) + c->cap_lmap + c->cap_umap;
  i32 += c->cap_arp + c->cap_acol + c->cap_apos + c->cap_fpos;
  *iw += (long int)((i32 + 1) / 2 + c->cap_tmp);
}

/* A new array of count items of `size` bytes in place of p (its contents
 * are not needed: cheaper than realloc). */
static void *Renew(void *p, size_t count, size_t size)
{
  free(p);
  return malloc((count > 0 ? count : 1) * size);
}

#define RENEW(a, count) (((a) = Renew((a), (count), sizeof *(a))) != NULL)

/* The capacity for `need` entries: as it is, or need + 1/8 when it grows
 * (a factorisation with new pivots usually changes the fill a little). */
static size_t NewCap(size_t cap, size_t need)
{
  if (need <= cap) return cap;
  return cap == 0 ? need : need + need / 8;
}

/* Values x and 32-bit indices i with room for `need` entries, kept while
 * the capacity *cap suffices (*cap is 0 after a failure). */
static int ReserveEntries(double **x, int32_t **i, size_t *cap, size_t need)
{
  size_t c;
  if (need <= *cap && *x != NULL) return LGN_SUCCESS;
  c    = NewCap(*cap, need);
  *cap = 0;
  if (!(RENEW(*x, c) && RENEW(*i, c))) return LGN_MEM_FAIL;
  *cap = c;
  return LGN_SUCCESS;
}

/* Arrays for n rows (and up to n blocks) and lnz, unz, nzoff entries
 * (klu_l_extract's sizes: L and U with their diagonals), kept while they
 * are large enough. On failure some arrays may be gone: free the copy. */
static int Reserve(LGNKluCopy *c, size_t n, size_t lnz, size_t unz,
                   size_t nzoff)
{
  size_t cap, ntmp;
  if (n > c->cap_n || c->P == NULL) {
    cap      = NewCap(c->cap_n, n);
    c->cap_n = 0;
    if (!(RENEW(c->Lp, cap + 1) && RENEW(c->Up, cap + 1) &&
          RENEW(c->Fp, cap + 1) && RENEW(c->P, cap) && RENEW(c->Q, cap) &&
          RENEW(c->R, cap + 1) && RENEW(c->Lswap, cap) &&
          RENEW(c->Uswap, cap) && RENEW(c->Udiag, cap) && RENEW(c->Rs, cap) &&
          RENEW(c->X, cap)))
      return LGN_MEM_FAIL;
    c->cap_n = cap;
  }
  /* L and U: the values are extracted in place, diagonals included, and
   * then compacted; the indices go through tmp */
  if (ReserveEntries(&c->Lx, &c->Li, &c->cap_l, lnz) != LGN_SUCCESS ||
      ReserveEntries(&c->Ux, &c->Ui, &c->cap_u, unz) != LGN_SUCCESS ||
      ReserveEntries(&c->Fx, &c->Fi, &c->cap_f, nzoff) != LGN_SUCCESS)
    return LGN_MEM_FAIL;
  /* tmp: pointers and indices of one of L, U, F; or P, Q and R */
  ntmp = SUNMAX(n + 1 + SUNMAX(SUNMAX(lnz, unz), nzoff), 3 * n + 1);
  if (ntmp > c->cap_tmp || c->tmp == NULL) {
    cap        = NewCap(c->cap_tmp, ntmp);
    c->cap_tmp = 0;
    if (!RENEW(c->tmp, cap)) return LGN_MEM_FAIL;
    c->cap_tmp = cap;
  }
  return LGN_SUCCESS;
}

/* An int32_t array of `need` entries in *a, kept while *cap suffices. */
static int ReserveInt32(int32_t **a, size_t *cap, size_t need)
{
  size_t c;
  if (need <= *cap && *a != NULL) return LGN_SUCCESS;
  c    = NewCap(*cap, need);
  *cap = 0;
  if (!RENEW(*a, c)) return LGN_MEM_FAIL;
  *cap = c;
  return LGN_SUCCESS;
}

/* The row pointers and entry maps of a copy by rows, for n rows and lnz,
 * unz entries (the strictly lower and upper parts), kept while large
 * enough. */
static int ReserveRows(LGNKluCopy *c, size_t n, size_t lnz, size_t unz)
{
  size_t cap;
  if (n > c->cap_rn || c->Lrp == NULL) {
    cap       = NewCap(c->cap_rn, n);
    c->cap_rn = 0;
    if (!(RENEW(c->Lrp, cap + 1) && RENEW(c->Urp, cap + 1))) return LGN_MEM_FAIL;
    c->cap_rn = cap;
  }
  if (ReserveInt32(&c->Lmap, &c->cap_lmap, lnz) != LGN_SUCCESS ||
      ReserveInt32(&c->Umap, &c->cap_umap, unz) != LGN_SUCCESS)
    return LGN_MEM_FAIL;
  return LGN_SUCCESS;
}

/* =============================================================================
 * The copy
 * ===========================================================================*/

/* Column pointers and indices of an extracted triangular factor, as 32-bit
 * integers without the diagonal entries; the values x are compacted in
 * place (the diagonal of U goes to diag, that of L, all ones, is dropped).
 * The other entries keep KLU's order, except that with next = +1 (L) or -1
 * (U) the entry in row k + next of column k comes first: the column solves
 * then carry that row's value to the next column in a register. (Each
 * entry of a column updates another row, so their order does not change
 * the result; in the transposed solves it is the order of a sum, kept.)
 * swap[k] is the place of that entry in KLU's column k, or 0. Returns 0,
 * or -1 if a column has no diagonal entry. */
static int CompactFactor(int32_t n, const int64_t *Tp, const int64_t *Ti,
                         double *x, int32_t *p32, int32_t *i32, double *diag,
                         int32_t *swap, int next)
{
  int32_t k, cnt = 0, first, q, t;
  int64_t p, d;
  double v;
  for (k = 0; k < n; k++) {
    p32[k] = first = cnt;
    for (d = Tp[k]; d < Tp[k + 1] && Ti[d] != k; d++) {}
    if (d == Tp[k + 1]) return -1;
    if (diag != NULL) diag[k] = x[d];
    q = -1;
    for (p = Tp[k]; p < Tp[k + 1]; p++) { /* cnt <= p: in place is safe */
      if (p == d) continue;
      if (Ti[p] == k + next) q = cnt;
      i32[cnt] = (int32_t)Ti[p];
      x[cnt++] = x[p];
    }
    swap[k] = 0;
    if (next != 0 && q > first) { /* to the front */
      swap[k]    = q - first;
      t          = i32[q];
      i32[q]     = i32[first];
      i32[first] = t;
      v          = x[q];
      x[q]       = x[first];
      x[first]   = v;
    }
  }
  p32[n] = cnt;
  return 0;
}

/* A compacted factor T (column pointers Tp, row indices Ti, values Tx, in
 * KLU's order) by rows, in place: Ti and Tx then hold the columns and
 * values of the rows, row i from Rp[i] on, its entries in the order of
 * the columns, increasing (ascending != 0, L) or decreasing (U); map[p]
 * is the new place of the entry at p of the columns. work: room for Tp[n]
 * doubles. */
static void BuildRows(int32_t n, const int32_t *Tp, int32_t *Ti, double *Tx,
                      int32_t *Rp, int32_t *map, double *work, int ascending)
{
  const int32_t nz = Tp[n];
  int32_t i, k, p, t;
  memset(Rp, 0, ((size_t)n + 1) * sizeof *Rp);
  for (p = 0; p < nz; p++) Rp[Ti[p] + 1]++;
  for (i = 0; i < n; i++) Rp[i + 1] += Rp[i];
  /* Rp[i] as the cursor of row i: then it is where row i + 1 starts */
  for (t = 0; t < n; t++) {
    k = ascending ? t : n - 1 - t;
    for (p = Tp[k]; p < Tp[k + 1]; p++) map[p] = Rp[Ti[p]]++;
  }
  memmove(Rp + 1, Rp, (size_t)n * sizeof *Rp);
  Rp[0] = 0;
  for (p = 0; p < nz; p++) work[map[p]] = Tx[p];
  memcpy(Tx, work, (size_t)nz * sizeof *Tx);
  for (k = 0; k < n; k++)
    for (p = Tp[k]; p < Tp[k + 1]; p++) Ti[map[p]] = k;
}

/* U's rows divided by its diagonal, Ux[q] = U(i, j) / U(i, i) for the
 * entries q of row i (the storage of U by rows). */
static void ScaleRowsOfU(LGNKluCopy *c)
{
  int32_t i, q;
  for (i = 0; i < c->n; i++) {
    const double d = c->Udiag[i];
    for (q = c->Urp[i]; q < c->Urp[i + 1]; q++) c->Ux[q] /= d;
  }
}

/* Which solve SUNLinSolSolve calls: klu_l_solve (A CSC: KLU has A) or
 * klu_l_tsolve (A CSR: KLU has A^T); -1 if neither. */
static int SundialsTranspose(SUNLinearSolver LS)
{
  const KLUSolveFn f = ((SUNLinearSolverContent_KLU)LS->content)->klu_solver;
  if (f == (KLUSolveFn)klu_l_solve) return 0;
  if (f == (KLUSolveFn)klu_l_tsolve) return 1;
  return -1;
}

/* =============================================================================
 * A refresh of the values only
 * ===========================================================================*/

/* Whether KLU's factorisation has the copy's permutations, blocks, sizes
 * and off-diagonal blocks F (pointers and row indices). klu_l_refactor
 * keeps them all; klu_l_factor (new pivots, or a new pattern after a new
 * analysis) may not. The patterns of L and U are compared column by column
 * in GatherFactors. */
static int SameLayout(const LGNKluCopy *c, const klu_l_symbolic *S,
                      const klu_l_numeric *N, int transpose)
{
  const int32_t n = c->n;
  int64_t k;
  if (!c->complete || c->transpose != (transpose ? SUNTRUE : SUNFALSE) ||
      S->n != n || S->nblocks != c->nblocks || N->lnz - n != c->Lp[n] ||
      N->unz - n != c->Up[n] || N->nzoff != c->Fp[n])
    return 0;
  for (k = 0; k <= c->nblocks; k++)
    if (S->R[k] != c->R[k]) return 0;
  for (k = 0; k < n; k++)
    if (N->Pnum[k] != c->P[k] || S->Q[k] != c->Q[k]) return 0;
  for (k = 0; k <= n; k++)
    if (N->Offp[k] != c->Fp[k]) return 0;
  for (k = 0; k < N->nzoff; k++)
    if (N->Offi[k] != c->Fi[k]) return 0;
  return 1;
}

/* Column k of L or U from its block's packed array LU, where KLU keeps it
 * as Xlen row indices (64-bit, local to the block, which starts at row
 * k1) from Xip on, and then its Xlen values (one unit, a double, each;
 * klu_version.h: GET_POINTER): the values into the copy's column p1 <=
 * p < p2 (Ti, Tx), whose entries are in KLU's order, but for its first
 * and its entry q, exchanged (CompactFactor). Returns nonzero if the
 * column's length or a row index is not the copy's. */
static inline int GatherColumn(const double *LU, int64_t Xip, int64_t Xlen,
                               int64_t k1, int32_t p1, int32_t p2, int32_t q,
                               const int32_t *Ti, double *Tx)
{
  const int64_t *ki = (const int64_t *)(const void *)(LU + Xip);
  const double *kx  = LU + Xip + Xlen;
  const int32_t *ti = Ti + p1;
  double *tx        = Tx + p1;
  int64_t j, differ; /* nonzero bits: a row index differs */
  if (Xlen != p2 - p1) return 1;
  if (Xlen == 0) return 0;
  differ = (ti[0] ^ (k1 + ki[q])) | (ti[q] ^ (k1 + ki[0]));
  tx[0]  = kx[q];
  tx[q]  = kx[0];
  for (j = 1; j < q; j++) {
    differ |= ti[j] ^ (k1 + ki[j]);
    tx[j] = kx[j];
  }
  for (j = q + 1; j < Xlen; j++) {
    differ |= ti[j] ^ (k1 + ki[j]);
    tx[j] = kx[j];
  }
  return differ != 0;
}

/* GatherColumn for a copy by rows: KLU's entry j of the column, in row
 * r = k1 + ki[j], goes to Tx[q], q = map[p1 + j], which must be in row r
 * (Rp[r] <= q < Rp[r + 1]). It is in the column: BuildRows makes the map
 * and the columns of the places together. So with the lengths of the
 * columns equal, the pattern is the copy's if every entry passes. */
static inline int GatherColumnRows(const double *LU, int64_t Xip, int64_t Xlen,
                                   int64_t k1, int32_t p1, int32_t p2,
                                   const int32_t *map, const int32_t *Rp,
                                   int32_t n, double *Tx)
{
  const int64_t *ki = (const int64_t *)(const void *)(LU + Xip);
  const double *kx  = LU + Xip + Xlen;
  int64_t j, r, differ = 0;
  int32_t q;
  if (Xlen != p2 - p1) return 1;
  for (j = 0; j < Xlen; j++) {
    q = map[p1 + j];
    r = k1 + ki[j];
    if (r < 0 || r >= n) return 1;
    differ |= (q < Rp[r]) | (q >= Rp[r + 1]);
    Tx[q] = kx[j];
  }
  return differ != 0;
}

/* The values of L and U into the copy, if their patterns are the copy's,
 * in one pass over the packed array of each block (KLU stores U(:, k)
 * right after L(:, k)). Returns 0, or -1 if the pattern changed (some
 * values are then replaced). */
static int GatherFactors(LGNKluCopy *c, const klu_l_numeric *N)
{
  const int32_t *Lp = c->Lp, *Up = c->Up;
  const double *LU;
  int32_t blk, k, k1, k2;
  int differ = 0;
  for (blk = 0; blk < c->nblocks; blk++) {
    k1 = c->R[blk];
    k2 = c->R[blk + 1];
    if (k2 - k1 == 1) { /* a singleton: U(k1, k1) only */
      differ |= (Lp[k1 + 1] != Lp[k1]) | (Up[k1 + 1] != Up[k1]);
      continue;
    }
    LU = (const double *)N->LUbx[blk];
    if (c->rows) {
      for (k = k1; k < k2; k++) {
        differ |= GatherColumnRows(LU, N->Lip[k], N->Llen[k], k1, Lp[k],
                                   Lp[k + 1], c->Lmap, c->Lrp, c->n, c->Lx);
        differ |= GatherColumnRows(LU, N->Uip[k], N->Ulen[k], k1, Up[k],
                                   Up[k + 1], c->Umap, c->Urp, c->n, c->Ux);
      }
      if (differ) return -1;
      continue;
    }
    for (k = k1; k < k2; k++) {
      differ |= GatherColumn(LU, N->Lip[k], N->Llen[k], k1, Lp[k], Lp[k + 1],
                             c->Lswap[k], c->Li, c->Lx);
      differ |= GatherColumn(LU, N->Uip[k], N->Ulen[k], k1, Up[k], Up[k + 1],
                             c->Uswap[k], c->Ui, c->Ux);
    }
    if (differ) return -1;
  }
  return 0;
}

/* The new values of the factorisation into the copy, if it has the copy's
 * pattern (SameLayout, GatherFactors); the values of F, U's diagonal and
 * the scale factors follow F's pattern, the blocks and the permutations.
 * Returns 0, or -1 if the pattern changed (the values are then partly
 * replaced: copy the whole factorisation). */
static int RefreshValues(LGNKluCopy *c, const klu_l_symbolic *S,
                         const klu_l_numeric *N, int transpose)
{
  const size_t n = (size_t)c->n;
  size_t k;
  if (!SameLayout(c, S, N, transpose) || GatherFactors(c, N) != 0) return -1;
  memcpy(c->Udiag, N->Udiag, n * sizeof(double));
  if (c->rows) ScaleRowsOfU(c);
  memcpy(c->Fx, N->Offx, (size_t)N->nzoff * sizeof(double));
  c->scaled = N->Rs != NULL;
  if (c->scaled) memcpy(c->Rs, N->Rs, n * sizeof(double));
  else
    for (k = 0; k < n; k++) c->Rs[k] = 1.0;
  return 0;
}

/* =============================================================================
 * The refresh
 * ===========================================================================*/

/* Copy the factors now in the SUNLinSol_KLU LS (again after every
 * SUNLinSolSetup: KLU refactors in place, and SUNDIALS replaces the
 * Numeric object when it factors with new pivots; after a refactorisation
 * only the values are taken, RefreshValues). Returns LGN_SUCCESS,
 * LGN_KLU_NO_COPY (no factors, sizes beyond 32-bit indices, an unknown
 * solve function: *copy is left as it is, to be used no more), or
 * LGN_MEM_FAIL (*copy freed). */
int lgnKluCopyRefresh(LGNKluCopy **copy, SUNLinearSolver LS)
{
  klu_l_symbolic *S = SUNLinSol_KLUGetSymbolic(LS);
  klu_l_numeric *N  = SUNLinSol_KLUGetNumeric(LS);
  klu_l_common *Cm  = SUNLinSol_KLUGetCommon(LS);
  const int transpose = SundialsTranspose(LS);
  LGNKluCopy *c = *copy;
  int64_t *tmp, n, nb, lnz, unz, nzoff, k;
  int flag;

  if (S == NULL || N == NULL || transpose < 0) return LGN_KLU_NO_COPY;
  n     = S->n;
  nb    = S->nblocks;
  lnz   = N->lnz;
  unz   = N->unz;
  nzoff = N->nzoff;
  if (n < 1 || nb < 1 || nb > n || lnz < n || unz < n || nzoff < 0 ||
      n >= INT32_MAX || lnz > INT32_MAX || unz > INT32_MAX || nzoff > INT32_MAX)
    return LGN_KLU_NO_COPY;

  if (c != NULL && RefreshValues(c, S, N, transpose) == 0) {
    c->nvalues++;
    return LGN_SUCCESS;
  }

  if (c == NULL) {
    c = (LGNKluCopy *)calloc(1, sizeof *c);
    if (c == NULL) return LGN_MEM_FAIL;
    *copy = c;
  }
  c->complete = SUNFALSE; /* until the end of this copy */
  c->pattern  = -1;       /* new pivots: the maps of A are rebuilt */
  flag = Reserve(c, (size_t)n, (size_t)lnz, (size_t)unz, (size_t)nzoff);
  if (flag == LGN_SUCCESS && !transpose)
    flag = ReserveRows(c, (size_t)n, (size_t)(lnz - n), (size_t)(unz - n));
  if (flag != LGN_SUCCESS) {
    lgnKluCopyFree(copy);
    return LGN_MEM_FAIL;
  }
  tmp          = c->tmp;
  c->n         = (int32_t)n;
  c->nblocks   = (int32_t)nb;
  c->transpose = transpose ? SUNTRUE : SUNFALSE;
  c->rows      = transpose ? SUNFALSE : SUNTRUE;
  c->scaled    = N->Rs != NULL; /* else klu_l_extract gives ones */

  /* permutations, scale factors, block boundaries */
  if (!klu_l_extract(N, S, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
                     NULL, tmp, tmp + n, c->Rs, tmp + 2 * n, Cm))
    return LGN_KLU_NO_COPY;
  for (k = 0; k < n; k++) {
    c->P[k] = (int32_t)tmp[k];
    c->Q[k] = (int32_t)tmp[n + k];
  }
  for (k = 0; k <= nb; k++) c->R[k] = (int32_t)tmp[2 * n + k];

  /* L, U and F, one at a time through tmp */
  if (!klu_l_extract(N, S, tmp, tmp + n + 1, c->Lx, NULL, NULL, NULL, NULL,
                     NULL, NULL, NULL, NULL, NULL, NULL, Cm))
    return LGN_KLU_NO_COPY;
  if (CompactFactor(c->n, tmp, tmp + n + 1, c->Lx, c->Lp, c->Li, NULL,
                    c->Lswap, 0) != 0)
    return LGN_KLU_NO_COPY;
  if (c->rows) /* tmp, free again, holds lnz doubles */
    BuildRows(c->n, c->Lp, c->Li, c->Lx, c->Lrp, c->Lmap,
              (double *)(void *)tmp, 1);
  if (!klu_l_extract(N, S, NULL, NULL, NULL, tmp, tmp + n + 1, c->Ux, NULL,
                     NULL, NULL, NULL, NULL, NULL, NULL, Cm))
    return LGN_KLU_NO_COPY;
  if (CompactFactor(c->n, tmp, tmp + n + 1, c->Ux, c->Up, c->Ui, c->Udiag,
                    c->Uswap, 0) != 0)
    return LGN_KLU_NO_COPY;
  if (c->rows) {
    BuildRows(c->n, c->Up, c->Ui, c->Ux, c->Urp, c->Umap,
              (double *)(void *)tmp, 0);
    ScaleRowsOfU(c);
  }
  if (!klu_l_extract(N, S, NULL, NULL, NULL, NULL, NULL, NULL, tmp,
                     tmp + n + 1, c->Fx, NULL, NULL, NULL, NULL, Cm))
    return LGN_KLU_NO_COPY;
  for (k = 0; k <= n; k++) c->Fp[k] = (int32_t)tmp[k];
  for (k = 0; k < nzoff; k++) c->Fi[k] = (int32_t)tmp[n + 1 + k];
  c->complete = SUNTRUE;
  c->nfull++;
  return LGN_SUCCESS;
}

/* =============================================================================
 * Lignum's refactorisation: KLU's pivots, pattern and scaling, new values
 * ===========================================================================*/

/* The maps from A (CSC, n x n, nnz entries) to the rows of S = Rs^{-1}
 * A(P, Q) in the diagonal blocks (Arp, Acol, Apos: for each pivot row, the
 * place of each of its entries in A's data and its column in S) and to the
 * entries of F (Fpos), for the copy's permutations and blocks. Returns
 * LGN_SUCCESS, LGN_MEM_FAIL, or LGN_KLU_NO_COPY if A does not fit them (an
 * entry below the block diagonal, or one that F does not hold). */
static int BuildRefactorMaps(LGNKluCopy *c, const sunindextype *Ap,
                             const sunindextype *Ai, sunindextype nnz)
{
  const int32_t n = c->n;
  int32_t *Pinv = (int32_t *)(void *)c->tmp, *Qinv = Pinv + n, *Bend = Qinv + n;
  int32_t *cursor = Bend + n; /* 4 n int32 within tmp's 3 n + 1 int64 */
  int32_t i, k, kc, b, f;
  sunindextype p;

  if (nnz > INT32_MAX ||
      ReserveInt32(&c->Arp, &c->cap_arp, (size_t)n + 1) != LGN_SUCCESS ||
      ReserveInt32(&c->Acol, &c->cap_acol, (size_t)nnz) != LGN_SUCCESS ||
      ReserveInt32(&c->Apos, &c->cap_apos, (size_t)nnz) != LGN_SUCCESS ||
      ReserveInt32(&c->Fpos, &c->cap_fpos, (size_t)c->Fp[n] + 1) != LGN_SUCCESS)
    return nnz > INT32_MAX ? LGN_KLU_NO_COPY : LGN_MEM_FAIL;
  for (k = 0; k < n; k++) {
    Pinv[c->P[k]] = k;
    Qinv[c->Q[k]] = k;
  }
  for (b = 0; b < c->nblocks; b++)
    for (k = c->R[b]; k < c->R[b + 1]; k++) Bend[k] = c->R[b + 1];

  /* count the entries of each row in its block; place those of F */
  memset(c->Arp, 0, ((size_t)n + 1) * sizeof *c->Arp);
  for (f = 0; f < c->Fp[n]; f++) c->Fpos[f] = -1;
  for (p = 0; p < (sunindextype)n; p++) { /* p: a column of A */
    sunindextype q;
    kc = Qinv[p];
    for (q = Ap[p]; q < Ap[p + 1]; q++) {
      if (Ai[q] < 0 || Ai[q] >= n) return LGN_KLU_NO_COPY;
      i = Pinv[Ai[q]];
      if (Bend[kc] == Bend[i]) { /* in i's diagonal block */
        c->Arp[i + 1]++;
        continue;
      }
      if (kc < Bend[i]) return LGN_KLU_NO_COPY; /* below the blocks */
      for (f = c->Fp[kc]; f < c->Fp[kc + 1] && c->Fi[f] != i; f++) {}
      if (f == c->Fp[kc + 1] || c->Fpos[f] >= 0) return LGN_KLU_NO_COPY;
      c->Fpos[f] = (int32_t)q;
    }
  }
  for (f = 0; f < c->Fp[n]; f++)
    if (c->Fpos[f] < 0) return LGN_KLU_NO_COPY;
  for (i = 0; i < n; i++) c->Arp[i + 1] += c->Arp[i];
  for (i = 0; i < n; i++) cursor[i] = c->Arp[i];
  for (p = 0; p < (sunindextype)n; p++) {
    sunindextype q;
    kc = Qinv[p];
    for (q = Ap[p]; q < Ap[p + 1]; q++) {
      i = Pinv[Ai[q]];
      if (Bend[kc] != Bend[i]) continue;
      c->Acol[cursor[i]]   = kc;
      c->Apos[cursor[i]++] = (int32_t)q;
    }
  }
  return LGN_SUCCESS;
}

/* KLU's row scale factors of A (klu_scale: scale 1, the sums of |a_ij| of
 * each row, 2 or more, their maxima; an empty row 1) in pivot order into
 * Rs; work: n doubles. */
static void ScaleFactors(LGNKluCopy *c, const sunindextype *Ap,
                         const sunindextype *Ai, const double *Ax, int scale,
                         double *work)
{
  const int32_t n = c->n;
  int32_t k;
  sunindextype col, p;
  for (k = 0; k < n; k++) work[k] = 0.0;
  for (col = 0; col < (sunindextype)n; col++)
    for (p = Ap[col]; p < Ap[col + 1]; p++) {
      const double a = fabs(Ax[p]);
      if (scale == 1) work[Ai[p]] += a;
      else if (a > work[Ai[p]]) work[Ai[p]] = a;
    }
  for (k = 0; k < n; k++) {
    const double r = work[c->P[k]];
    c->Rs[k] = r == 0.0 ? 1.0 : r;
  }
}

/* Rows k1 <= i < k2 of L and U (by rows, in place of the copy's values,
 * U's divided by its diagonal) and U's diagonal from the rows of S in the
 * block, by the row-oriented elimination with the copy's pivots:
 * W = S(i, :); for the columns j < i of L's row i, in increasing order,
 * L(i, j) = W[j] / U(j, j) and W -= W[j] U(j, :) / U(j, j) (the stored
 * row); then U(i, i) = W[i] and U's row i is W / U(i, i). W (the solve's
 * X) is zero before and after each row. Returns the smallest |U(i, i)| of
 * the rows, and their largest in *umax. */
static double EliminateRows(LGNKluCopy *c, int32_t k1, int32_t k2,
                            const double *Ax, double *umax)
{
  const int32_t *Lrp = c->Lrp, *Li = c->Li, *Urp = c->Urp, *Ui = c->Ui;
  const int32_t *Arp = c->Arp, *Acol = c->Acol, *Apos = c->Apos;
  double *Lx = c->Lx, *Ux = c->Ux, *Udiag = c->Udiag, *W = c->X;
  double umin = HUGE_VAL, w, d;
  int32_t i, j, p, q;
  for (i = k1; i < k2; i++) {
    const double rs = c->scaled ? c->Rs[i] : 1.0;
    for (q = Arp[i]; q < Arp[i + 1]; q++) W[Acol[q]] = Ax[Apos[q]] / rs;
    for (p = Lrp[i]; p < Lrp[i + 1]; p++) {
      j     = Li[p];
      w     = W[j];
      W[j]  = 0.0;
      Lx[p] = w / Udiag[j];
      for (q = Urp[j]; q < Urp[j + 1]; q++) W[Ui[q]] -= w * Ux[q];
    }
    d        = W[i];
    W[i]     = 0.0;
    Udiag[i] = d;
    for (q = Urp[i]; q < Urp[i + 1]; q++) {
      Ux[q]     = W[Ui[q]] / d;
      W[Ui[q]]  = 0.0;
    }
    d = fabs(d);
    if (!(d >= umin)) umin = d; /* a NaN is the smallest */
    if (d > *umax) *umax = d;
  }
  return umin;
}

/* Refactor with the values now in the CSC matrix A (whose pattern is A's
 * pattern number `pattern` and was analysed and factored by the KLU whose
 * factors the copy holds) with the copy's pivots, blocks and pattern, and
 * KLU's row scaling `scale` (klu_common.scale): the values of L, U and F
 * in the copy become those of A. This is what klu_l_refactor does, by rows
 * instead of by columns (the same factors up to roundoff), without the
 * copy out of KLU afterwards. As SUNLinSolSetup does after klu_l_refactor,
 * it checks KLU's cheap reciprocal condition number min |U(i, i)| / max
 * |U(i, i)|: below eps^(2/3) (or a zero, Inf or NaN) it returns
 * LGN_KLU_PIVOT and the copy is no longer complete, so the caller factors
 * with KLU (which may pivot anew) and copies again. LGN_KLU_NO_COPY: not a
 * copy by rows, or A does not fit the copy's factors; LGN_MEM_FAIL. */
int lgnKluCopyRefactor(LGNKluCopy *c, SUNMatrix A, long int pattern, int scale)
{
  const sunindextype *Ap, *Ai;
  const double *Ax;
  double umin = HUGE_VAL, umax = 0.0, u;
  int32_t b, f;
  int flag;

  if (c == NULL || !c->complete || !c->rows || lgnMatID(A) != SUNMATRIX_SPARSE ||
      SUNSparseMatrix_SparseType(A) != CSC_MAT || SUNSparseMatrix_NP(A) != c->n)
    return LGN_KLU_NO_COPY;
  Ap = SUNSparseMatrix_IndexPointers(A);
  Ai = SUNSparseMatrix_IndexValues(A);
  Ax = SUNSparseMatrix_Data(A);
  if (c->pattern != pattern) {
    c->pattern = -1;
    flag = BuildRefactorMaps(c, Ap, Ai, Ap[c->n]);
    if (flag != LGN_SUCCESS) return flag;
    c->pattern = pattern;
  }

  c->scaled = scale > 0 ? SUNTRUE : SUNFALSE;
  if (c->scaled) ScaleFactors(c, Ap, Ai, Ax, scale, (double *)(void *)c->tmp);
  for (b = 0; b < c->nblocks; b++) {
    u = EliminateRows(c, c->R[b], c->R[b + 1], Ax, &umax);
    if (!(u >= umin)) umin = u;
  }
  for (f = 0; f < c->Fp[c->n]; f++)
    c->Fx[f] = c->scaled ? Ax[c->Fpos[f]] / c->Rs[c->Fi[f]] : Ax[c->Fpos[f]];
  c->nrefactor++;
  /* KLU's rcond, and SUNDIALS' threshold for it */
  if (!(umin > 0.0) || !(umax <= SUN_BIG_REAL) ||
      umin / umax < pow(SUN_UNIT_ROUNDOFF, 2.0 / 3.0)) {
    c->complete = SUNFALSE;
    return LGN_KLU_PIVOT;
  }
  return LGN_SUCCESS;
}

/* =============================================================================
 * The solves: klu_l_solve and klu_l_tsolve for one right-hand side
 * ===========================================================================*/

/* Each kernel works on the columns k1 <= k < k2 of one factor; kept out of
 * line so that the few pointers of its loop stay in registers. */
#if defined(__GNUC__)
#define LGN_NOINLINE __attribute__((noinline))
#else
#define LGN_NOINLINE
#endif

/* A hint to fetch the cache line `bytes` after (before, if negative) the
 * address a: the row sweeps ask for their streams of values and indices
 * LGN_AHEAD bytes ahead (stand-alone on the 10000-body chain with the
 * factors not in cache: 0.84-0.96 -> 0.70-0.83 ms a solve; 2, 3 and 4 kB
 * ahead alike, 1 kB less good). Integer arithmetic: the address may be outside the
 * array, which a prefetch does not mind. */
#if defined(__GNUC__)
#define LGN_PREFETCH(a, bytes) \
  __builtin_prefetch((const void *)((uintptr_t)(a) + (uintptr_t)(intptr_t)(bytes)))
#else
#define LGN_PREFETCH(a, bytes) ((void)0)
#endif
#define LGN_AHEAD 3072

/* X(Fi(:, k)) -= F(:, k) X[k], for k = k1, ..., k2 - 1: the columns of a
 * block of F into the rows of earlier blocks. */
static LGN_NOINLINE void ScatterColumns(int32_t k1, int32_t k2,
                                        const int32_t *restrict Tp,
                                        const int32_t *restrict Ti,
                                        const double *restrict Tx,
                                        double *restrict X)
{
  int32_t k, p;
  double xk;
  for (k = k1; k < k2; k++) {
    xk = X[k];
    for (p = Tp[k]; p < Tp[k + 1]; p++) X[Ti[p]] -= Tx[p] * xk;
  }
}

/* L by rows (no diagonal stored), for i = k1, ..., k2 - 1:
 * X[i] = X[i] - L(i, j1) X[j1] - L(i, j2) X[j2] - ... with j1 < j2 < ...:
 * the subtractions klu_l_solve's sweep by columns does on X[i], in its
 * order. X[i] starts as b[P[i]] / Rs[i] when b is given (b[P[i]] if Rs is
 * NULL), else as it is. The last entries of a row, in columns i - 2 and
 * i - 1 on a banded matrix, are the chain of dependences of the solve:
 * their values are carried from row to row in registers (x2, x1), not
 * stored and loaded again. */
static LGN_NOINLINE void LowerByRows(int32_t k1, int32_t k2,
                                     const int32_t *restrict Rp,
                                     const int32_t *restrict Ci,
                                     const double *restrict Tx,
                                     const sunrealtype *restrict b,
                                     const int32_t *restrict P,
                                     const double *restrict Rs,
                                     double *restrict X)
{
  int32_t i, p, pend;
  double xi, x1 = SUN_RCONST(0.0), x2 = SUN_RCONST(0.0); /* X[i-1], X[i-2] */
  for (i = k1; i < k2; i++) {
    if (b == NULL) xi = X[i];
    else if (Rs != NULL) xi = b[P[i]] / Rs[i];
    else xi = b[P[i]];
    p    = Rp[i];
    pend = Rp[i + 1];
    LGN_PREFETCH(Tx + p, LGN_AHEAD);
    LGN_PREFETCH(Ci + p, LGN_AHEAD);
    if (pend - p >= 2 && Ci[pend - 1] == i - 1 && Ci[pend - 2] == i - 2) {
      for (; p < pend - 2; p++) xi -= Tx[p] * X[Ci[p]];
      xi -= Tx[p] * x2;
      xi -= Tx[p + 1] * x1;
    } else if (p < pend && Ci[pend - 1] == i - 1) {
      for (; p < pend - 1; p++) xi -= Tx[p] * X[Ci[p]];
      xi -= Tx[p] * x1;
    } else {
      for (; p < pend; p++) xi -= Tx[p] * X[Ci[p]];
    }
    X[i] = xi;
    x2   = x1;
    x1   = xi;
  }
}

/* U by rows from the last, for i = k2 - 1, ..., k1, with the rows divided
 * by the diagonal (Tx = U(i, j) / U(i, i)): X[i] = X[i] / U(i, i) -
 * Tx(i, j1) X[j1] - Tx(i, j2) X[j2] - ... with j1 > j2 > ...
 * (klu_l_solve's order), and x[Q[i]] = X[i]; the columns i + 2, i + 1,
 * last in a row, carried as in LowerByRows. The division waits only for
 * X[i], so the chain from row to row is a multiplication and a
 * subtraction. */
static LGN_NOINLINE void UpperByRows(int32_t k1, int32_t k2,
                                     const int32_t *restrict Rp,
                                     const int32_t *restrict Ci,
                                     const double *restrict Tx,
                                     const double *restrict Udiag,
                                     const int32_t *restrict Q,
                                     double *restrict X,
                                     sunrealtype *restrict x)
{
  int32_t i, p, pend;
  double xi, x1 = SUN_RCONST(0.0), x2 = SUN_RCONST(0.0); /* X[i+1], X[i+2] */
  for (i = k2 - 1; i >= k1; i--) {
    xi   = X[i] / Udiag[i];
    p    = Rp[i];
    pend = Rp[i + 1];
    LGN_PREFETCH(Tx + p, -LGN_AHEAD);
    LGN_PREFETCH(Ci + p, -LGN_AHEAD);
    if (pend - p >= 2 && Ci[pend - 1] == i + 1 && Ci[pend - 2] == i + 2) {
      for (; p < pend - 2; p++) xi -= Tx[p] * X[Ci[p]];
      xi -= Tx[p] * x2;
      xi -= Tx[p + 1] * x1;
    } else if (p < pend && Ci[pend - 1] == i + 1) {
      for (; p < pend - 1; p++) xi -= Tx[p] * X[Ci[p]];
      xi -= Tx[p] * x1;
    } else {
      for (; p < pend; p++) xi -= Tx[p] * X[Ci[p]];
    }
    X[i]    = xi;
    x[Q[i]] = xi;
    x2      = x1;
    x1      = xi;
  }
}

/* X[k] -= T(:, k)^T X(Ti(:, k)), for k = k2 - 1, ..., k1: L^T by rows (no
 * diagonal stored), or F^T from the rows of earlier blocks. */
static LGN_NOINLINE void GatherColumns(int32_t k1, int32_t k2,
                                       const int32_t *restrict Tp,
                                       const int32_t *restrict Ti,
                                       const double *restrict Tx,
                                       double *restrict X)
{
  int32_t k, p;
  double xk;
  for (k = k2 - 1; k >= k1; k--) {
    xk = X[k];
    for (p = Tp[k]; p < Tp[k + 1]; p++) xk -= Tx[p] * X[Ti[p]];
    X[k] = xk;
  }
}

/* U^T by rows from the first: X[k] = (X[k] - U(:, k)^T X) / U(k, k). */
static LGN_NOINLINE void UpperRows(int32_t k1, int32_t k2,
                                   const int32_t *restrict Up,
                                   const int32_t *restrict Ui,
                                   const double *restrict Ux,
                                   const double *restrict Udiag,
                                   double *restrict X)
{
  int32_t k, p;
  double xk;
  for (k = k1; k < k2; k++) {
    xk = X[k];
    for (p = Up[k]; p < Up[k + 1]; p++) xk -= Ux[p] * X[Ui[p]];
    X[k] = xk / Udiag[k];
  }
}

/* S x = b (KLU's klu_solve): X = Rs^{-1} P b; for the blocks from the last
 * to the first, X_b = U_b^{-1} L_b^{-1} X_b and the earlier rows minus
 * F(:, b) X_b (a singleton block is X[k1] / Udiag[k1]); x = Q X. With L
 * and U by rows: the last block takes its rows of Rs^{-1} P b in
 * LowerByRows, before x is written (x may be b), the others here; x = Q X
 * is done in UpperByRows, as each X[i] is final. */
static void Solve(LGNKluCopy *c, const sunrealtype *b, sunrealtype *x)
{
  const int32_t *P = c->P;
  const double *Rs = c->scaled ? c->Rs : NULL;
  double *X = c->X;
  int32_t blk, k, k1, k2;
  const int32_t klast = c->R[c->nblocks - 1];

  if (Rs != NULL)
    for (k = 0; k < klast; k++) X[k] = b[P[k]] / Rs[k];
  else
    for (k = 0; k < klast; k++) X[k] = b[P[k]];
  for (blk = c->nblocks - 1; blk >= 0; blk--) {
    k1 = c->R[blk];
    k2 = c->R[blk + 1];
    LowerByRows(k1, k2, c->Lrp, c->Li, c->Lx, blk == c->nblocks - 1 ? b : NULL,
                P, Rs, X);
    UpperByRows(k1, k2, c->Urp, c->Ui, c->Ux, c->Udiag, c->Q, X, x);
    if (blk > 0) ScatterColumns(k1, k2, c->Fp, c->Fi, c->Fx, X);
  }
}

/* S^T x = b (KLU's klu_tsolve): X = Q^T b; for the blocks from the first to
 * the last, X_b minus F(:, b)^T X (earlier rows), then
 * X_b = L_b^{-T} U_b^{-T} X_b; x = P^T Rs^{-1} X. (The order of the rows of
 * F^T does not matter: they read only earlier blocks.) */
static void SolveTransposed(LGNKluCopy *c, const sunrealtype *b, sunrealtype *x)
{
  const int32_t n = c->n, *P = c->P, *Q = c->Q;
  double *X = c->X;
  int32_t blk, k, k1, k2;

  for (k = 0; k < n; k++) X[k] = b[Q[k]];
  for (blk = 0; blk < c->nblocks; blk++) {
    k1 = c->R[blk];
    k2 = c->R[blk + 1];
    if (blk > 0) GatherColumns(k1, k2, c->Fp, c->Fi, c->Fx, X);
    UpperRows(k1, k2, c->Up, c->Ui, c->Ux, c->Udiag, X);
    GatherColumns(k1, k2, c->Lp, c->Li, c->Lx, X);
  }
  if (c->scaled)
    for (k = 0; k < n; k++) x[P[k]] = X[k] / c->Rs[k];
  else
    for (k = 0; k < n; k++) x[P[k]] = X[k];
}

/* Solve A x = b for the A of the last refresh (x and b may be the same). */
void lgnKluCopySolve(LGNKluCopy *c, const sunrealtype *b, sunrealtype *x)
{
  if (c->transpose) SolveTransposed(c, b, x);
  else Solve(c, b, x);
}

#else
typedef int lgnKluCopyUnavailable; /* ISO C: no empty translation unit */
#endif
