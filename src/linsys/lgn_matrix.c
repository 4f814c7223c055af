/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The scaled iteration matrix, assembled into the user's matrix A from its
 * table of terms (LGNMatrixTerms, filled by the kinematics variant in
 * lgn_kinematics.c):
 *
 *   A = [[ cM M TM + cC C TC + cK K TK ,  B^T ],
 *        [ B TB + cBv D_q(B v) TK      ,  0   ]]
 *
 * with T-like factors block diagonal by the leaves of the group (NULL: I).
 * Dense matrices are filled here, sparse ones in lgn_matrix_sparse.c from
 * the same table, so both see the same matrix term by term. The variants'
 * tables (cM = beta h^2 beta', cC = beta h^2 gamma', cK = beta h^2):
 *
 *   simplified:  TM = TC = I,   TK = T,  TB = T (index 3) or I (index 2)
 *   exact:       TM = Ta, TC = Tv, TK = T, TB = T (index 3) or Tv (index 2)
 *   sigma:       all I, no D_q(B v) term
 *
 * where T = T(sigma) and Ta, Tv are the normalised derivatives of vdot and
 * v (lgn_tangent.c). At index 2, cBv = 1/gamma' = cK/cC (the row B v /
 * gamma' varies as B dv / gamma' plus its change with q). The saddle-point
 * matrix [[M, B^T], [B, 0]] of the consistent initial values is the table
 * (cM, cC, cK) = (1, 0, 0) with no T (lgnSaddlePointTerms).
 *
 * GGL (LGN_CONSTR_GGL, dense A only) has nv + 2m unknowns (sigma, the
 * scaled lambda, nu) and rows (dynamics, Phi, (B v + Phi_t) / gamma'):
 *
 *   BDF (nu = mu / c0, v = T(x) xdot - B(q1)^T mu):
 *   [[ cM M T + cC C T + cK K T ,  B^T ,  -(cM M + cC C) B^T ],
 *    [ B T                      ,  0   ,   0                 ],
 *    [ B T + cBv D_q(B v) T     ,  0   ,  -B B^T             ]]
 *
 *   Newmark family (nu = h eta, s = sigma + B_n^T nu the Newmark increment,
 *   B_n = B(q_n); UA = UV = I simplified, UA = Ta, UV = T exact):
 *   [[ cM M TM + cC C TC + cK K T ,  B^T ,  (cM M UA + cC C UV) B_n^T ],
 *    [ B T                        ,  0   ,   0                         ],
 *    [ B TB + cBv D_q(B v) T      ,  0   ,   B UV B_n^T                ]]
 *
 * and its saddle-point matrix [[M, B^T, 0], [B, 0, 0], [0, 0, I]].
 * ---------------------------------------------------------------------------*/

#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"

/* Column j of a block diagonal T-like factor in packed storage: the rows
 * k0 <= k < k1 it can have nonzero and tj with tj[k] = T(k, j); tj = NULL
 * when the column is e_j (T = NULL standing for I, or an R^n leaf). */
typedef struct {
  const sunrealtype *tj;
  sunindextype k0, k1;
} TangentColumn;

static inline TangentColumn ColumnOf(LGNMem mem, const sunrealtype *T,
                                     sunindextype j)
{
  TangentColumn c = {NULL, j, j + 1};
  const int b = (int)mem->blk_of[j];
  sunindextype o, n;
  if (T == NULL || lgnBlockIsIdentity(mem, b)) return c;
  o    = mem->blk_voff[b];
  n    = mem->blk_voff[b + 1] - o;
  c.tj = T + mem->blk_toff[b] + (j - o) * n - o;
  lgnTangentColumnRange(mem, j, &c.k0, &c.k1);
  return c;
}

/* (X T)(i, j) = sum_k X(i, k) T(k, j) over the column's range, in the
 * order of k; one and three terms (R^3 x SO(3)'s translation and any
 * rotation) as straight-line code. */
static inline sunrealtype RowTimesColumn(const sunrealtype *X, sunindextype ldx,
                                         sunindextype i, sunindextype j,
                                         const TangentColumn *c)
{
  const sunrealtype *x = X + i, *t = c->tj;
  sunrealtype s;
  sunindextype k;
  if (t == NULL) return x[j * ldx];
  switch (c->k1 - c->k0) {
  case 1: return x[c->k0 * ldx] * t[c->k0];
  case 3:
    k = c->k0;
    return x[k * ldx] * t[k] + x[(k + 1) * ldx] * t[k + 1] + x[(k + 2) * ldx] * t[k + 2];
  default:
    s = SUN_RCONST(0.0);
    for (k = c->k0; k < c->k1; k++) s += x[k * ldx] * t[k];
    return s;
  }
}

/* Column j of X T as three column pointers and weights, y = (x0 t0 + x1 t1)
 * + x2 t2, when the column has at most three rows in its range (a column
 * of I or of an R^3 x SO(3) leaf's translation part: x0 = X e_j, t0 = 1 or
 * T(j, j), the other weights 0; a rotation: its three columns). Returns
 * SUNFALSE for a longer range (a user-supplied or SE(3) leaf). */
static inline sunbooleantype ThreeColumns(const sunrealtype *X, sunindextype ldx,
                                          sunindextype j, const TangentColumn *c,
                                          const sunrealtype *x[3], sunrealtype t[3])
{
  sunindextype k;
  if (c->tj == NULL) {
    x[0] = x[1] = x[2] = X + j * ldx;
    t[0] = SUN_RCONST(1.0);
    t[1] = t[2] = SUN_RCONST(0.0);
    return SUNTRUE;
  }
  if (c->k1 - c->k0 == 1) {
    x[0] = x[1] = x[2] = X + c->k0 * ldx;
    t[0] = c->tj[c->k0];
    t[1] = t[2] = SUN_RCONST(0.0);
    return SUNTRUE;
  }
  if (c->k1 - c->k0 != 3) return SUNFALSE;
  for (k = 0; k < 3; k++) {
    x[k] = X + (c->k0 + k) * ldx;
    t[k] = c->tj[c->k0 + k];
  }
  return SUNTRUE;
}

/* y = T x for a block diagonal T-like factor in packed storage (NULL: I). */
static void PackedApply(LGNMem mem, const sunrealtype *T, const sunrealtype *x,
                        sunrealtype *y)
{
  sunindextype j, k, nv = mem->nv;
  for (k = 0; k < nv; k++) y[k] = SUN_RCONST(0.0);
  for (j = 0; j < nv; j++) {
    const TangentColumn c = ColumnOf(mem, T, j);
    if (c.tj == NULL) {
      y[j] += x[j];
      continue;
    }
    for (k = c.k0; k < c.k1; k++) y[k] += c.tj[k] * x[j];
  }
}

/* Column j of GGL's nu into a (n rows; the Phi rows stay 0): with b the
 * j-th column of GB^T (GB = B(q1) when NULL),
 *   dynamic rows  gsign (cM M UA + cC C UV) b,   velocity rows  gsign B UV b.
 * BDF (v = T(x) xdot - B(q1)^T mu, UA = UV = I): -(cM M + cC C) B^T and
 * -B B^T. Newmark family (s = sigma + B(q_n)^T nu): +(cM M UA + cC C UV)
 * B_n^T and +B UV B_n^T. */
static void GGLColumn(LGNMem mem, const LGNMatrixTerms *x, sunindextype j,
                      sunrealtype *a)
{
  sunindextype i, k, nv = mem->nv, m = mem->m;
  const sunrealtype *M = SM_DATA_D(mem->Mmat), *C = SM_DATA_D(mem->Cmat);
  const sunrealtype *B = SM_DATA_D(mem->Bmat);
  const sunrealtype *GB = x->GB != NULL ? x->GB : B;
  const sunrealtype cM = x->cM, cC = x->cC;
  /* scratch: free once the tangents are formed (lgnEvalTangents) */
  sunrealtype *b = mem->work_nv, *w = mem->work2_nv, *u = b, s;
  for (k = 0; k < nv; k++) b[k] = GB[j + k * m];
  if (x->UA != NULL || x->UV != NULL) { /* w = UA b, u = UV b */
    u = lgnData(mem->dq_g);
    PackedApply(mem, x->UA, b, w);
    PackedApply(mem, x->UV, b, u);
    for (i = 0; i < nv; i++) {
      s = SUN_RCONST(0.0);
      for (k = 0; k < nv; k++) s += cM * M[i + k * nv] * w[k] + cC * C[i + k * nv] * u[k];
      a[i] = x->gsign * s;
    }
  } else {
    for (i = 0; i < nv; i++) {
      s = SUN_RCONST(0.0);
      for (k = 0; k < nv; k++) s += (cM * M[i + k * nv] + cC * C[i + k * nv]) * u[k];
      a[i] = x->gsign * s;
    }
  }
  for (i = 0; i < m; i++) {
    s = SUN_RCONST(0.0);
    for (k = 0; k < nv; k++) s += B[i + k * m] * u[k];
    a[nv + m + i] = x->gsign * s;
  }
}

/* A = the dense iteration matrix (header comment), column by column in one
 * pass: each entry of the top left is cM (M TM)_ij + cC (C TC)_ij +
 * cK (K TK)_ij formed in a register from the few columns of M, C, K that
 * the block structure of the T-like factors lets in (no products with the
 * zeros of T, no scratch matrices, no second pass to scale and add). With
 * at most three columns per factor (R^n, SO(3), R^3 x SO(3) leaves) the
 * loop over the rows is branch-free; otherwise entry by entry. */
static int AssembleDense(LGNMem mem, sunrealtype t, const LGNMatrixTerms *x)
{
  sunindextype i, j, nv = mem->nv, m = mem->m, n = nv + mem->nalg;
  /* GGL: the Phi rows come first, the velocity rows (B v + Phi_t)/gamma'
   * at vrow; under GGL the saddle-point matrix has an identity for mu */
  const sunindextype vrow = x->ggl ? nv + m : nv;
  sunrealtype *A = SM_DATA_D(mem->A); /* all dense on this path */
  const sunrealtype *M = SM_DATA_D(mem->Mmat);
  const sunrealtype *C = SM_DATA_D(mem->Cmat);
  const sunrealtype *K = SM_DATA_D(mem->Kmat);
  const sunrealtype *B = m > 0 ? SM_DATA_D(mem->Bmat) : NULL;
  const sunrealtype cM = x->cM, cC = x->cC, cK = x->cK, cBv = x->cBv;
  int flag;

  flag = lgnEvalTangents(mem, t, cC, cK);
  if (flag != LGN_SUCCESS) return flag;
  mem->nje++;
  if (m > 0 && cBv != SUN_RCONST(0.0)) {
    flag = lgnConstraintVelocityDQ(mem, t);
    if (flag != LGN_SUCCESS) return flag;
  }

  for (j = 0; j < nv; j++) {
    const TangentColumn tm = ColumnOf(mem, x->TM, j), tc = ColumnOf(mem, x->TC, j);
    const TangentColumn tk = ColumnOf(mem, x->TK, j), tb = ColumnOf(mem, x->TB, j);
    const sunrealtype *pm[3], *pc[3], *pk[3], *pb[3], *pq[3];
    sunrealtype wm[3], wc[3], wk[3], wb[3], wq[3];
    sunrealtype *restrict a = A + j * n, s;
    /* top left: cM M TM + cC C TC + cK K TK */
    if (cC != SUN_RCONST(0.0) && cK != SUN_RCONST(0.0) &&
        ThreeColumns(M, nv, j, &tm, pm, wm) && ThreeColumns(C, nv, j, &tc, pc, wc) &&
        ThreeColumns(K, nv, j, &tk, pk, wk)) {
      for (i = 0; i < nv; i++)
        a[i] = cM * ((pm[0][i] * wm[0] + pm[1][i] * wm[1]) + pm[2][i] * wm[2])
             + cC * ((pc[0][i] * wc[0] + pc[1][i] * wc[1]) + pc[2][i] * wc[2])
             + cK * ((pk[0][i] * wk[0] + pk[1][i] * wk[1]) + pk[2][i] * wk[2]);
    } else {
      for (i = 0; i < nv; i++) {
        s = cM * RowTimesColumn(M, nv, i, j, &tm);
        if (cC != SUN_RCONST(0.0)) s += cC * RowTimesColumn(C, nv, i, j, &tc);
        if (cK != SUN_RCONST(0.0)) s += cK * RowTimesColumn(K, nv, i, j, &tk);
        a[i] = s;
      }
    }
    /* bottom left: B TB (+ cBv D_q(B v) TK at index 2 and in GGL's
     * velocity rows) */
    if (m == 0) continue;
    if (cBv == SUN_RCONST(0.0) && ThreeColumns(B, m, j, &tb, pb, wb)) {
      for (i = 0; i < m; i++)
        a[vrow + i] = (pb[0][i] * wb[0] + pb[1][i] * wb[1]) + pb[2][i] * wb[2];
    } else if (cBv != SUN_RCONST(0.0) && ThreeColumns(B, m, j, &tb, pb, wb) &&
               ThreeColumns(mem->Bvq, m, j, &tk, pq, wq)) {
      for (i = 0; i < m; i++)
        a[vrow + i] = ((pb[0][i] * wb[0] + pb[1][i] * wb[1]) + pb[2][i] * wb[2])
                    + cBv * ((pq[0][i] * wq[0] + pq[1][i] * wq[1]) + pq[2][i] * wq[2]);
    } else {
      for (i = 0; i < m; i++) {
        s = RowTimesColumn(B, m, i, j, &tb);
        if (cBv != SUN_RCONST(0.0)) s += cBv * RowTimesColumn(mem->Bvq, m, i, j, &tk);
        a[vrow + i] = s;
      }
    }
    if (x->ggl) { /* GGL's Phi rows: B TP */
      const TangentColumn tp = ColumnOf(mem, x->TP, j);
      for (i = 0; i < m; i++) a[nv + i] = RowTimesColumn(B, m, i, j, &tp);
    }
    else /* the saddle-point matrix under GGL: no mu in these rows */
      for (i = nv + m; i < n; i++) a[i] = SUN_RCONST(0.0);
  }
  /* right: B^T over zeros */
  for (j = 0; j < m; j++) {
    sunrealtype *a = A + (nv + j) * n;
    for (i = 0; i < nv; i++) a[i] = B[j + i * m];
    for (i = nv; i < n; i++) a[i] = SUN_RCONST(0.0);
  }
  /* GGL: the column of nu (header comment); the saddle-point matrix has I
   * there (mu = 0 at the start) */
  for (j = 0; j < mem->nalg - m; j++) {
    sunrealtype *a = A + (nv + m + j) * n;
    for (i = nv; i < n; i++) a[i] = SUN_RCONST(0.0);
    if (!x->ggl) {
      for (i = 0; i < nv; i++) a[i] = SUN_RCONST(0.0);
      a[nv + m + j] = SUN_RCONST(1.0);
      continue;
    }
    GGLColumn(mem, x, j, a);
  }
  return LGN_SUCCESS;
}

/* The iteration matrix, never with a NaN or Inf: the callbacks' outputs
 * are checked where they are called, and this catches what their products
 * may still produce (overflow, difference quotients), so that no
 * non-finite entry reaches a factorisation that modified Newton would then
 * reuse. */
int lgnAssembleIterationMatrix(LGNMem mem, sunrealtype t,
                               const LGNMatrixTerms *terms)
{
  const sunrealtype *data;
  sunindextype len;
  int flag = mem->sparse ? lgnAssembleSparse(mem, t, terms)
                         : AssembleDense(mem, t, terms);
  if (flag != LGN_SUCCESS) return flag;
  mem->asm_t  = t; /* for a preconditioner's setup (lgn_krylov.c) */
  mem->asm_cM = terms->cM;
  mem->asm_cC = terms->cC;
  mem->asm_cK = terms->cK;
  if (mem->sparse) {
    data = SUNSparseMatrix_Data(mem->A);
    len  = SUNSparseMatrix_IndexPointers(mem->A)[SUNSparseMatrix_NP(mem->A)];
  } else {
    data = SM_DATA_D(mem->A);
    len  = SM_LDATA_D(mem->A);
  }
  if (lgnAllFinite(data, len)) return LGN_SUCCESS;
  LGN_ERROR(mem, LGN_NONFINITE,
            MSG_TIME "the iteration matrix has a NaN or Inf entry (from the "
            "products of M, K_t, C_t and B at the iterate; the callbacks' own "
            "outputs were finite).", (double)mem->tn);
  return LGN_NONFINITE;
}
