/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Difference-quotient tangent matrices along the group (the analogue of IDA's
 * DQ Jacobian), used when the user gives no callback:
 *
 *   K_t e_j = [ r(q o exp(eps e_j)) - r(q) ] / eps,   r = M(q) vdot + g(q,v,t) + B(q)^T lambda
 *   C_t e_j = [ g(q, v + eps e_j, t) - g(q, v, t) ] / eps
 *   Z(q)(v,v) = [ B(q o exp(eps v)) v - B(q o exp(-eps v)) v ] / (2 eps)
 *   Bvq e_j   = [ B(q o exp(eps e_j)) v - B(q) v ] / eps   (index-2 Newton row)
 *
 * (definitions of K_t, C_t and Z: spec numerics.md §1). Forward differences
 * suffice for Newton; Z enters the initial values, so it gets a central one.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>

#include "lgn_impl.h"

/* r(q) = M(q) vdot1 + g(q, v1, t) + B(q)^T lambda1 at q = dq_q, into dq_r
 * (B only for B^T lambda1, so not evaluated with an LGNConstrForceFn). */
int lgnDQResidualAt(LGNMem mem, sunrealtype t)
{
  int flag;
  SUNMatrix M = mem->mass_constant ? mem->Mmat : mem->Mdq;
  mem->ndq++;
  flag = lgnEvalModelAt(mem, t, mem->dq_q, mem->v1, M, mem->dq_g, mem->Bdq,
                        mem->constr_force == NULL);
  if (flag == LGN_SUCCESS)
    flag = lgnDynamicResidual(mem, t, mem->dq_q, M, mem->dq_g, mem->Bdq, mem->dq_r);
  return flag;
}

int lgnStiffnessDQ(LGNMem mem, sunrealtype t)
{
  sunindextype i, j, nv = mem->nv;
  const sunrealtype srur = sqrt(SUN_UNIT_ROUNDOFF);
  const sunrealtype *r0 = lgnData(mem->rdyn), *r = lgnData(mem->dq_r);
  sunrealtype *w = mem->work_nv, *col, eps;
  int ret, flag;

  for (j = 0; j < nv; j++) {
    eps = srur * SUNMAX(SUN_RCONST(1.0), fabs(mem->sigma[j]));
    memset(w, 0, (size_t)nv * sizeof(sunrealtype));
    w[j] = eps;
    ret  = mem->G->ops.compose_exp(mem->G, lgnData(mem->q1), w,
                                   lgnData(mem->dq_q));
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, __func__);
    flag = lgnDQResidualAt(mem, t);
    if (flag != LGN_SUCCESS) return flag;
    col = SUNDenseMatrix_Column(mem->Kmat, j);
    for (i = 0; i < nv; i++) col[i] = (r[i] - r0[i]) / eps;
  }
  return LGN_SUCCESS;
}

int lgnDampingDQ(LGNMem mem, sunrealtype t)
{
  sunindextype i, j, nv = mem->nv;
  const sunrealtype srur = sqrt(SUN_UNIT_ROUNDOFF);
  const sunrealtype *v1 = lgnData(mem->v1), *g0 = lgnData(mem->g);
  sunrealtype *vp = lgnData(mem->dq_v), *g = lgnData(mem->dq_g), *col, eps;
  int ret;

  N_VScale(SUN_RCONST(1.0), mem->v1, mem->dq_v);
  for (j = 0; j < nv; j++) {
    eps   = srur * SUNMAX(SUN_RCONST(1.0), fabs(v1[j]));
    vp[j] = v1[j] + eps;
    mem->ndq++;
    N_VConst(SUN_RCONST(0.0), mem->dq_g);
    ret = mem->force(t, mem->q1, mem->dq_v, mem->dq_g, mem->user_data);
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_FORCE, ret, __func__);
    col = SUNDenseMatrix_Column(mem->Cmat, j);
    for (i = 0; i < nv; i++) col[i] = (g[i] - g0[i]) / eps;
    vp[j] = v1[j];
  }
  return LGN_SUCCESS;
}

/* z = B(q o exp(w)) v (length m), using dq_q and Bdq: one constraint
 * Jacobian evaluation at a point displaced along the group. */
int lgnConstraintVelocityAt(LGNMem mem, sunrealtype t, N_Vector q,
                            const sunrealtype *w, N_Vector v, sunrealtype *z)
{
  int ret = mem->G->ops.compose_exp(mem->G, lgnData(q), w, lgnData(mem->dq_q));
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, __func__);
  mem->ndq++;
  lgnMatClear(mem->Bdq);
  ret = mem->constr_jac(t, mem->dq_q, mem->Bdq, mem->user_data);
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_CONSTR_JAC, ret, __func__);
  lgnMatvec(mem->Bdq, lgnData(v), z, SUNFALSE);
  return LGN_SUCCESS;
}

int lgnCurvatureDQ(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v,
                   N_Vector z)
{
  sunindextype i, nv = mem->nv, m = mem->m;
  sunrealtype vmax = N_VMaxNorm(v), eps;
  sunrealtype *zd = lgnData(z), *zm = lgnData(mem->dq_z), *w = mem->work_nv;
  const sunrealtype *vd = lgnData(v);
  int flag;

  if (vmax == SUN_RCONST(0.0)) {
    N_VConst(SUN_RCONST(0.0), z);
    return LGN_SUCCESS;
  }
  /* central difference: step of size cbrt(uround) in the group */
  eps = cbrt(SUN_UNIT_ROUNDOFF) / vmax;
  for (i = 0; i < nv; i++) w[i] = eps * vd[i];
  flag = lgnConstraintVelocityAt(mem, t, q, w, v, zd);
  for (i = 0; i < nv; i++) w[i] = -eps * vd[i];
  if (flag == LGN_SUCCESS) flag = lgnConstraintVelocityAt(mem, t, q, w, v, zm);
  if (flag != LGN_SUCCESS) return flag;
  for (i = 0; i < m; i++) zd[i] = (zd[i] - zm[i]) / (SUN_RCONST(2.0) * eps);
  return LGN_SUCCESS;
}

/* Bvq = D_q(B(q) v1).(q w~) at q1 by forward differences, m x nv
 * column-major: the change of the index-2 constraint B(q) v with the
 * configuration, which the iteration matrix needs next to B dv. */
int lgnConstraintVelocityDQ(LGNMem mem, sunrealtype t)
{
  sunindextype i, j, nv = mem->nv, m = mem->m;
  const sunrealtype srur = sqrt(SUN_UNIT_ROUNDOFF);
  sunrealtype *w = mem->work_nv, *z0 = lgnData(mem->dq_z), eps;
  int flag;

  lgnMatvec(mem->Bmat, lgnData(mem->v1), z0, SUNFALSE);
  for (j = 0; j < nv; j++) {
    sunrealtype *col = mem->Bvq + j * m;
    eps = srur * SUNMAX(SUN_RCONST(1.0), fabs(mem->sigma[j]));
    memset(w, 0, (size_t)nv * sizeof(sunrealtype));
    w[j] = eps;
    flag = lgnConstraintVelocityAt(mem, t, mem->q1, w, mem->v1, col);
    if (flag != LGN_SUCCESS) return flag;
    for (i = 0; i < m; i++) col[i] = (col[i] - z0[i]) / eps;
  }
  return LGN_SUCCESS;
}
