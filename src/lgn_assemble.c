/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Assembly of the (scaled) iteration matrix into the user's dense matrix A and
 * its factorisation (spec numerics.md §2, modified-kinematics.md §2):
 *
 *   simplified:  A = [[ cM M + cC C + cK K T ,        B^T ],  [ B T_c , 0 ]]
 *   exact:       A = [[ cM M Ta + cC C Tv + cK K T,  B^T ],  [ B T_e , 0 ]]
 *
 * with cM = beta h^2 beta', cC = beta h^2 gamma', cK = beta h^2, T = T(sigma),
 * and Ta, Tv the normalised derivatives of vdot and v (lgn_step.c; Ta = Tv = T
 * in the spec's simpler matrix). T_c = T at index 3 and I at index 2 (the row
 * B v / gamma' varies as B dv / gamma'); T_e = T at index 3, Tv at index 2.
 * The same routine with (cM, cC, cK) = (1, 0, 0) and no tangent gives the
 * saddle-point matrix [[M, B^T], [B, 0]] of the consistent initial values.
 * ---------------------------------------------------------------------------*/

#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>

#include "lgn_impl.h"

/* K and C at the current iterate: the user's callbacks or difference quotients. */
static int EvalTangents(LGNMem mem, sunrealtype t, sunrealtype cC,
                        sunrealtype cK)
{
  int ret, flag;
  if (cK != SUN_RCONST(0.0)) {
    if (mem->stiffness != NULL) {
      SUNMatZero(mem->Kmat);
      ret = mem->stiffness(t, mem->q1, mem->v1, mem->vdot1, mem->lambda1,
                           mem->Kmat, mem->user_data);
      if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_STIFFNESS, ret, __func__);
    } else {
      flag = lgnStiffnessDQ(mem, t);
      if (flag != LGN_SUCCESS) return flag;
    }
  }
  if (cC != SUN_RCONST(0.0)) {
    if (mem->damping != NULL) {
      SUNMatZero(mem->Cmat);
      ret = mem->damping(t, mem->q1, mem->v1, mem->Cmat, mem->user_data);
      if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_DAMPING, ret, __func__);
    } else {
      flag = lgnDampingDQ(mem, t);
      if (flag != LGN_SUCCESS) return flag;
    }
  }
  return LGN_SUCCESS;
}

/* Y(:, j) = X T(:, j) summed over the columns of T, for an nrow x nv block
 * X with leading dimension ldx, into Y with leading dimension ldy. */
static void MultiplyByTangent(const sunrealtype *X, sunindextype ldx,
                              sunindextype nrow, const sunrealtype *Tm,
                              sunindextype nv, sunrealtype *Y, sunindextype ldy)
{
  sunindextype i, j, k;
  sunrealtype tkj;
  for (j = 0; j < nv; j++) {
    for (i = 0; i < nrow; i++) Y[i + j * ldy] = SUN_RCONST(0.0);
    for (k = 0; k < nv; k++) {
      tkj = Tm[k + j * nv];
      if (tkj == SUN_RCONST(0.0)) continue;
      for (i = 0; i < nrow; i++) Y[i + j * ldy] += X[i + k * ldx] * tkj;
    }
  }
}

int lgnAssembleAndFactor(LGNMem mem, sunrealtype t, sunrealtype cM,
                         sunrealtype cC, sunrealtype cK,
                         sunbooleantype use_tangent)
{
  sunindextype i, j, nv = mem->nv, m = mem->m, n = nv + m;
  sunrealtype *A = SUNDenseMatrix_Data(mem->A);
  const sunrealtype *M = SUNDenseMatrix_Data(mem->Mmat);
  const sunrealtype *C = SUNDenseMatrix_Data(mem->Cmat);
  const sunrealtype *K = SUNDenseMatrix_Data(mem->Kmat);
  const sunrealtype *Tm = mem->Tm;
  const sunbooleantype exact = use_tangent && mem->kinematics == LGN_KINEMATICS_EXACT;
  const sunbooleantype identity_T = !use_tangent || (!exact && mem->G->kind == LGN_GROUP_RN);
  sunrealtype *W = SUNDenseMatrix_Data(mem->Mdq); /* nv x nv scratch */
  int flag;

  flag = EvalTangents(mem, t, cC, cK);
  if (flag != LGN_SUCCESS) return flag;
  mem->nje++;

  memset(A, 0, (size_t)(n * n) * sizeof(sunrealtype));

  /* top left */
  if (exact) {
    MultiplyByTangent(M, nv, nv, mem->Ta, nv, W, nv);
    for (j = 0; j < nv; j++)
      for (i = 0; i < nv; i++) A[i + j * n] = cM * W[i + j * nv];
    if (cC != SUN_RCONST(0.0)) {
      MultiplyByTangent(C, nv, nv, mem->Tv, nv, W, nv);
      for (j = 0; j < nv; j++)
        for (i = 0; i < nv; i++) A[i + j * n] += cC * W[i + j * nv];
    }
    if (cK != SUN_RCONST(0.0)) {
      MultiplyByTangent(K, nv, nv, Tm, nv, W, nv);
      for (j = 0; j < nv; j++)
        for (i = 0; i < nv; i++) A[i + j * n] += cK * W[i + j * nv];
    }
  } else {
    for (j = 0; j < nv; j++)
      for (i = 0; i < nv; i++) {
        A[i + j * n] = cM * M[i + j * nv];
        if (cC != SUN_RCONST(0.0)) A[i + j * n] += cC * C[i + j * nv];
        if (cK != SUN_RCONST(0.0) && identity_T) A[i + j * n] += cK * K[i + j * nv];
      }
    if (cK != SUN_RCONST(0.0) && !identity_T) {
      MultiplyByTangent(K, nv, nv, Tm, nv, W, nv);
      for (j = 0; j < nv; j++)
        for (i = 0; i < nv; i++) A[i + j * n] += cK * W[i + j * nv];
    }
  }

  if (m > 0) {
    const sunrealtype *B = SUNDenseMatrix_Data(mem->Bmat);
    /* top right: B^T */
    for (j = 0; j < m; j++)
      for (i = 0; i < nv; i++) A[i + (nv + j) * n] = B[j + i * m];
    /* bottom left: B T_c (simplified) or B T_e (exact) */
    if (exact && mem->constr_index == LGN_CONSTR_INDEX2) {
      MultiplyByTangent(B, m, m, mem->Tv, nv, A + nv, n);
    } else if (identity_T || mem->constr_index == LGN_CONSTR_INDEX2) {
      for (j = 0; j < nv; j++)
        for (i = 0; i < m; i++) A[nv + i + j * n] = B[i + j * m];
    } else {
      MultiplyByTangent(B, m, m, Tm, nv, A + nv, n);
    }
    /* index 2: + (1/gamma') D_q(B v) T, with 1/gamma' = cK/cC */
    if (use_tangent && mem->constr_index == LGN_CONSTR_INDEX2 && cC != SUN_RCONST(0.0)) {
      const sunrealtype f = cK / cC;
      flag = lgnConstraintVelocityDQ(mem, t);
      if (flag != LGN_SUCCESS) return flag;
      if (identity_T) {
        for (j = 0; j < nv; j++)
          for (i = 0; i < m; i++) A[nv + i + j * n] += f * mem->Bvq[i + j * m];
      } else {
        MultiplyByTangent(mem->Bvq, m, m, Tm, nv, W, m);
        for (j = 0; j < nv; j++)
          for (i = 0; i < m; i++) A[nv + i + j * n] += f * W[i + j * m];
      }
    }
  }
  return lgnLsSetup(mem);
}
