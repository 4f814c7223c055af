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
 * ---------------------------------------------------------------------------*/

#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"

/* A = the dense iteration matrix (header comment). */
static int AssembleDense(LGNMem mem, sunrealtype t, const LGNMatrixTerms *x)
{
  sunindextype i, j, nv = mem->nv, m = mem->m, n = nv + m;
  sunrealtype *A = SUNDenseMatrix_Data(mem->A);
  const sunrealtype *M = SUNDenseMatrix_Data(mem->Mmat);
  const sunrealtype *C = SUNDenseMatrix_Data(mem->Cmat);
  const sunrealtype *K = SUNDenseMatrix_Data(mem->Kmat);
  const sunrealtype cM = x->cM, cC = x->cC, cK = x->cK;
  sunrealtype *W = SUNDenseMatrix_Data(mem->Mdq); /* nv x nv scratch */
  int flag;

  flag = lgnEvalTangents(mem, t, cC, cK);
  if (flag != LGN_SUCCESS) return flag;
  mem->nje++;

  /* top left: cM M TM + cC C TC + cK K TK */
  lgnDenseTimesTangent(mem, M, nv, nv, x->TM, W, nv);
  for (j = 0; j < nv; j++)
    for (i = 0; i < nv; i++) A[i + j * n] = cM * W[i + j * nv];
  if (cC != SUN_RCONST(0.0)) {
    lgnDenseTimesTangent(mem, C, nv, nv, x->TC, W, nv);
    for (j = 0; j < nv; j++)
      for (i = 0; i < nv; i++) A[i + j * n] += cC * W[i + j * nv];
  }
  if (cK != SUN_RCONST(0.0)) {
    lgnDenseTimesTangent(mem, K, nv, nv, x->TK, W, nv);
    for (j = 0; j < nv; j++)
      for (i = 0; i < nv; i++) A[i + j * n] += cK * W[i + j * nv];
  }
  for (j = nv; j < n; j++)
    for (i = 0; i < n; i++) A[i + j * n] = SUN_RCONST(0.0);

  if (m > 0) {
    const sunrealtype *B = SUNDenseMatrix_Data(mem->Bmat);
    /* top right: B^T */
    for (j = 0; j < m; j++)
      for (i = 0; i < nv; i++) A[i + (nv + j) * n] = B[j + i * m];
    /* bottom left: B TB */
    lgnDenseTimesTangent(mem, B, m, m, x->TB, A + nv, n);
    /* index 2: + cBv D_q(B v) TK */
    if (x->cBv != SUN_RCONST(0.0)) {
      flag = lgnConstraintVelocityDQ(mem, t);
      if (flag != LGN_SUCCESS) return flag;
      lgnDenseTimesTangent(mem, mem->Bvq, m, m, x->TK, W, m);
      for (j = 0; j < nv; j++)
        for (i = 0; i < m; i++) A[nv + i + j * n] += x->cBv * W[i + j * m];
    }
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
