/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Assembly of the (scaled) iteration matrix into the user's matrix A and its
 * factorisation; dense here, sparse in lgn_assemble_sparse.c (spec numerics.md §2, modified-kinematics.md §2):
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

#include "lgn_sparse.h"

/* K and C at the current iterate: the user's callbacks, or difference
 * quotients (column by column for dense matrices, by column colours for
 * sparse ones). Shared by both assemblers. */
int lgnEvalTangents(LGNMem mem, sunrealtype t, sunrealtype cC, sunrealtype cK)
{
  int ret;
  if (cK != SUN_RCONST(0.0)) {
    if (mem->stiffness != NULL) {
      lgnMatClear(mem->Kmat);
      ret = mem->stiffness(t, mem->q1, mem->v1, mem->vdot1, mem->lambda1,
                           mem->Kmat, mem->user_data);
      if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_STIFFNESS, ret, __func__);
    } else {
      ret = mem->sparse ? lgnStiffnessDQColored(mem, t) : lgnStiffnessDQ(mem, t);
      if (ret != LGN_SUCCESS) return ret;
    }
  }
  if (cC != SUN_RCONST(0.0)) {
    if (mem->damping != NULL) {
      lgnMatClear(mem->Cmat);
      ret = mem->damping(t, mem->q1, mem->v1, mem->Cmat, mem->user_data);
      if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_DAMPING, ret, __func__);
    } else {
      ret = mem->sparse ? lgnDampingDQColored(mem, t) : lgnDampingDQ(mem, t);
      if (ret != LGN_SUCCESS) return ret;
    }
  }
  return LGN_SUCCESS;
}

/* A = the dense iteration matrix (header comment), T block diagonal. */
static int AssembleDense(LGNMem mem, sunrealtype t, sunrealtype cM,
                         sunrealtype cC, sunrealtype cK,
                         sunbooleantype use_tangent)
{
  sunindextype i, j, nv = mem->nv, m = mem->m, n = nv + m;
  sunrealtype *A = SUNDenseMatrix_Data(mem->A);
  const sunrealtype *M = SUNDenseMatrix_Data(mem->Mmat);
  const sunrealtype *C = SUNDenseMatrix_Data(mem->Cmat);
  const sunrealtype *K = SUNDenseMatrix_Data(mem->Kmat);
  const sunbooleantype exact = use_tangent && mem->kinematics == LGN_KINEMATICS_EXACT;
  const sunbooleantype idx2 = mem->constr_index == LGN_CONSTR_INDEX2;
  /* NULL stands for T = I */
  const sunrealtype *Tk = use_tangent ? mem->Tm : NULL;
  const sunrealtype *Tb = !use_tangent ? NULL : (idx2 ? (exact ? mem->Tv : NULL) : mem->Tm);
  sunrealtype *W = SUNDenseMatrix_Data(mem->Mdq); /* nv x nv scratch */
  int flag;

  flag = lgnEvalTangents(mem, t, cC, cK);
  if (flag != LGN_SUCCESS) return flag;
  mem->nje++;

  /* top left: cM M Ta + cC C Tv + cK K T */
  lgnDenseTimesTangent(mem, M, nv, nv, exact ? mem->Ta : NULL, W, nv);
  for (j = 0; j < nv; j++)
    for (i = 0; i < nv; i++) A[i + j * n] = cM * W[i + j * nv];
  if (cC != SUN_RCONST(0.0)) {
    lgnDenseTimesTangent(mem, C, nv, nv, exact ? mem->Tv : NULL, W, nv);
    for (j = 0; j < nv; j++)
      for (i = 0; i < nv; i++) A[i + j * n] += cC * W[i + j * nv];
  }
  if (cK != SUN_RCONST(0.0)) {
    lgnDenseTimesTangent(mem, K, nv, nv, Tk, W, nv);
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
    /* bottom left: B T_c (simplified) or B T_e (exact) */
    lgnDenseTimesTangent(mem, B, m, m, Tb, A + nv, n);
    /* index 2: + (1/gamma') D_q(B v) T, with 1/gamma' = cK/cC */
    if (use_tangent && idx2 && cC != SUN_RCONST(0.0)) {
      const sunrealtype f = cK / cC;
      flag = lgnConstraintVelocityDQ(mem, t);
      if (flag != LGN_SUCCESS) return flag;
      lgnDenseTimesTangent(mem, mem->Bvq, m, m, Tk, W, m);
      for (j = 0; j < nv; j++)
        for (i = 0; i < m; i++) A[nv + i + j * n] += f * W[i + j * m];
    }
  }
  return LGN_SUCCESS;
}

int lgnAssembleAndFactor(LGNMem mem, sunrealtype t, sunrealtype cM,
                         sunrealtype cC, sunrealtype cK,
                         sunbooleantype use_tangent)
{
  int flag = mem->sparse ? lgnAssembleSparse(mem, t, cM, cC, cK, use_tangent)
                         : AssembleDense(mem, t, cM, cC, cK, use_tangent);
  if (flag != LGN_SUCCESS) return flag;
  return lgnLsSetup(mem);
}
