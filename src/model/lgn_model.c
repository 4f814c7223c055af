/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Evaluation of the model at the current iterate (q1, v1, vdot1, lambda1):
 * mass matrix, forces, constraint Jacobian, and the scaled Newton residual
 *
 *   r = [ beta h^2 (M vdot + g + B^T lambda) ;  Phi(q)          ]   (index 3)
 *       [                                    ;  (B(q) v + Phi_t) / gamma' ]  (index 2)
 *       [ ... ; Phi(q) ; (B(q) v + Phi_t) / gamma' ]                        (GGL)
 *
 * (doc/theory.md §6, scaling), plus the matrix-vector kernels.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"

/* Is B(q) needed? For the iteration matrix (for_matrix), for B v at index
 * 2 and GGL, and for B^T lambda unless an LGNConstrForceFn gives it. Not
 * under BDF's GGL: its iterate has evaluated it already (v = T(x) xdot -
 * B^T mu, lgn_kinematics.c); the Newmark family's GGL corrects with
 * B(q_n) and needs B(q1) here. */
sunbooleantype lgnNeedsConstraintJacobian(LGNMem mem, sunbooleantype for_matrix)
{
  if (mem->m == 0) return SUNFALSE;
  if (mem->constr_index == LGN_CONSTR_GGL) return mem->family != LGN_FAMILY_BDF;
  return for_matrix || mem->constr_force == NULL || mem->constr_index == LGN_CONSTR_INDEX2;
}

/* Is M diagonal (no stored entry off the diagonal)? Its diagonal to d. */
static sunbooleantype DiagonalOf(SUNMatrix M, sunrealtype *d)
{
  sunindextype i, j, p;
  if (lgnMatIsSparse(M)) {
    const sunindextype *ptr = SUNSparseMatrix_IndexPointers(M);
    const sunindextype *ind = SUNSparseMatrix_IndexValues(M);
    const sunrealtype *val  = SUNSparseMatrix_Data(M);
    for (j = 0; j < SUNSparseMatrix_NP(M); j++) {
      d[j] = SUN_RCONST(0.0);
      for (p = ptr[j]; p < ptr[j + 1]; p++) {
        if (ind[p] != j) return SUNFALSE;
        d[j] = val[p];
      }
    }
    return SUNTRUE;
  }
  for (j = 0; j < SM_COLUMNS_D(M); j++) {
    const sunrealtype *col = SM_COLUMN_D(M, j);
    for (i = 0; i < SM_ROWS_D(M); i++)
      if (i != j && col[i] != SUN_RCONST(0.0)) return SUNFALSE;
    d[j] = col[j];
  }
  return SUNTRUE;
}

/* M(q), g(q, v, t) and, when with_B and m > 0, B(q) into the given
 * storage. A constant mass matrix (LGNSetMassConstant) is evaluated once,
 * into mem->Mmat, and kept: callers pass mem->Mmat as M then; if it is
 * diagonal (rigid bodies in principal axes), its diagonal is kept too, for
 * M vdot without the sparse matrix-vector loop. */
int lgnEvalModelAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v,
                   SUNMatrix M, N_Vector g, SUNMatrix B, sunbooleantype with_B)
{
  int ret;
  if (!(mem->mass_constant && mem->mass_current && M == mem->Mmat)) {
    lgnMatClear(M);
    ret = lgnCallbackMatrix(mem, LGN_CB_MASS, mem->mass(t, q, M, mem->user_data), M,
                            "LGNSolve");
    if (ret != LGN_SUCCESS) return ret;
    ret = lgnGhostsCheckMass(mem, M); /* ghosts: no mass of their own */
    if (ret != LGN_SUCCESS) return ret;
    mem->mass_current  = mem->mass_constant && M == mem->Mmat;
    mem->mass_diagonal = mem->mass_current && DiagonalOf(M, mem->mass_diag);
  }
  memset(lgnData(g), 0, (size_t)mem->nv * sizeof(sunrealtype));
  ret = lgnCallbackVector(mem, LGN_CB_FORCE, mem->force(t, q, v, g, mem->user_data),
                          g, "LGNSolve");
  if (ret != LGN_SUCCESS) return ret;
  if (with_B && mem->m > 0) return lgnEvalConstraintJacobian(mem, t, q, B);
  return LGN_SUCCESS;
}

/* B(q, t) into B: emptied, the callback, its output checked. */
int lgnEvalConstraintJacobian(LGNMem mem, sunrealtype t, N_Vector q, SUNMatrix B)
{
  lgnMatClear(B);
  return lgnCallbackMatrix(mem, LGN_CB_CONSTR_JAC, lgnUserConstrJac(mem, t, q, B),
                           B, "LGNSolve");
}

/* out = B v + Phi_t(q, t) (length m), the velocity constraint, from the B
 * already evaluated at (q, t); Phi_t only for rheonomic constraints
 * (LGNSetConstraintTimeFn). out may not alias v. */
int lgnConstraintVelocity(LGNMem mem, sunrealtype t, N_Vector q, SUNMatrix B,
                          const sunrealtype *v, sunrealtype *out)
{
  sunindextype i;
  const sunrealtype *pt;
  int ret;
  lgnMatvec(B, v, out, SUNFALSE);
  if (mem->constr_time == NULL) return LGN_SUCCESS;
  N_VConst(SUN_RCONST(0.0), mem->phit);
  ret = lgnCallbackVector(mem, LGN_CB_CONSTR_TIME,
                          lgnUserConstrTime(mem, t, q, mem->phit),
                          mem->phit, "LGNSolve");
  if (ret != LGN_SUCCESS) return ret;
  pt = lgnData(mem->phit);
  for (i = 0; i < mem->m; i++) out[i] += pt[i];
  return LGN_SUCCESS;
}

/* M(q1), g(q1, v1, t) and (with_B) B(q1): one "residual evaluation". */
int lgnEvalModel(LGNMem mem, sunrealtype t, sunbooleantype with_B)
{
  mem->nre++;
  return lgnEvalModelAt(mem, t, mem->q1, mem->v1, mem->Mmat, mem->g, mem->Bmat,
                        with_B);
}

/* r = B(q)^T lambda1 + M vdot1 + g, the unscaled dynamic residual, with
 * B^T lambda1 from the LGNConstrForceFn if there is one (else from B).
 * The constraint force goes first, so that the callback writes straight
 * into r (no extra vector) and both ways sum in the same order. */
int lgnDynamicResidual(LGNMem mem, sunrealtype t, N_Vector q, SUNMatrix M,
                       N_Vector g, SUNMatrix B, N_Vector r)
{
  sunindextype i, nv = mem->nv;
  const sunrealtype *gd = lgnData(g);
  sunrealtype *rd = lgnData(r);
  int ret;
  if (mem->m > 0 && mem->constr_force != NULL) {
    memset(rd, 0, (size_t)nv * sizeof(sunrealtype));
    ret = lgnCallbackVector(mem, LGN_CB_CONSTR_FORCE,
                            lgnUserConstrForce(mem, t, q, mem->lambda1, r),
                            r, "LGNSolve");
    if (ret != LGN_SUCCESS) return ret;
  } else if (mem->m > 0) {
    lgnMatTvec(B, lgnData(mem->lambda1), rd, SUNFALSE);
  }
  if (M == mem->Mmat && mem->mass_current && mem->mass_diagonal) {
    /* the same products and sums as the matrix-vector loop, and g, in one
     * pass */
    const sunrealtype *d = mem->mass_diag, *x = lgnData(mem->vdot1);
    if (mem->m > 0)
      for (i = 0; i < nv; i++) rd[i] = (rd[i] + d[i] * x[i]) + gd[i];
    else
      for (i = 0; i < nv; i++) rd[i] = d[i] * x[i] + gd[i];
  } else {
    lgnMatvec(M, lgnData(mem->vdot1), rd, mem->m > 0);
    for (i = 0; i < nv; i++) rd[i] += gd[i];
  }
  return LGN_SUCCESS;
}

/* The scaled residual into mem->rhs, negated (the Newton right-hand side);
 * the unscaled dynamic residual stays in mem->rdyn for difference quotients.
 * for_matrix: the iteration matrix is built next (B is needed). */
int lgnNewtonResidual(LGNMem mem, sunrealtype t, sunrealtype scale,
                      sunrealtype cv, sunbooleantype for_matrix)
{
  sunindextype i, nv = mem->nv, m = mem->m;
  sunrealtype *rdyn = lgnData(mem->rdyn), *rhs = lgnData(mem->rhs);
  int ret, flag;

  flag = lgnEvalModel(mem, t, lgnNeedsConstraintJacobian(mem, for_matrix));
  if (flag == LGN_SUCCESS)
    flag = lgnDynamicResidual(mem, t, mem->q1, mem->Mmat, mem->g, mem->Bmat, mem->rdyn);
  if (flag != LGN_SUCCESS) return flag;
  if (m > 0) {
    sunrealtype *phi = lgnData(mem->phi);
    if (mem->constr_index != LGN_CONSTR_INDEX2) { /* index 3 and GGL: Phi(q) */
      memset(phi, 0, (size_t)m * sizeof(sunrealtype));
      ret = lgnCallbackVector(mem, LGN_CB_CONSTR,
                              lgnUserConstr(mem, t, mem->q1, mem->phi),
                              mem->phi, "LGNSolve");
      if (ret != LGN_SUCCESS) return ret;
      for (i = 0; i < m; i++) rhs[nv + i] = -phi[i];
    }
    if (mem->constr_index != LGN_CONSTR_INDEX3) { /* index 2 and GGL: B v + Phi_t */
      sunrealtype *bv = mem->constr_index == LGN_CONSTR_GGL ? rhs + nv + m : rhs + nv;
      ret = lgnConstraintVelocity(mem, t, mem->q1, mem->Bmat, lgnData(mem->v1), bv);
      if (ret != LGN_SUCCESS) return ret;
      for (i = 0; i < m; i++) bv[i] /= -cv;
    }
  }
  for (i = 0; i < nv; i++) rhs[i] = -scale * rdyn[i];

  if (!lgnAllFinite(rhs, nv + mem->nalg)) {
    LGN_ERROR(mem, LGN_NONFINITE,
              MSG_TIME "the %s residual has a NaN or Inf component "
              "(mass, force or constraint callback output).",
              (double)mem->tn,
              lgnAllFinite(rhs, nv) ? "constraint" : "dynamic");
    return LGN_NONFINITE;
  }
  return LGN_SUCCESS;
}
