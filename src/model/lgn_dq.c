/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The derivatives of the model the iteration matrix and the initial values
 * need, from the user's callbacks or by difference quotients along the group:
 *
 *   K_t = d/dq (M vdot + g + B^T lambda) . (q w~)   (stiffness)
 *   C_t = d/dv g                                   (damping)
 *   D_q(B v + Phi_t) . (q w~)                       (index 2)
 *   z = D_q(B v + Phi_t) . (q v~) + d/dt(B v + Phi_t)  (curvature, initial values)
 *
 * lgnEvalTangents is the one entry point for K_t and C_t: the callback if
 * the model gives one, else quotients column by column (dense matrices) or
 * by column colours (sparse ones).
 *
 * Colouring (Curtis, Powell and Reid 1974): columns that share no row are
 * displaced together, so one evaluation gives a whole group of columns and
 * the cost is (number of colours) evaluations, independent of the number of
 * bodies. The patterns are structural, from what the model already tells
 * Lignum:
 *   K_t:  blocks of T  u  M  u  B^T B      C_t:  blocks of T  u  M
 * (each symmetrised). The blocks of T are the factors of the group: a body's
 * forces may depend on all of its own coordinates; M and B^T B add the
 * couplings through inertia and joints. Forces coupling bodies that share no
 * joint (e.g. a spring between distant bodies) are outside these patterns:
 * such a model must give K_t and C_t itself (LGNSetStiffnessFn/DampingFn).
 * D_q(B v) has the pattern of B and uses the colouring of K_t, which is valid
 * for it because B^T B is part of that pattern.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>

#include "lgn_impl.h"
#include "lgn_sparse.h"

/* =============================================================================
 * Dense matrices: column by column
 * ===========================================================================*/

/* r(q) = M(q) vdot1 + g(q, v1, t) + B(q)^T lambda1 at q = dq_q, into dq_r
 * (B only for B^T lambda1, so not evaluated with an LGNConstrForceFn). */
static int DQResidualAt(LGNMem mem, sunrealtype t)
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

static int StiffnessDQ(LGNMem mem, sunrealtype t)
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
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
    flag = DQResidualAt(mem, t);
    if (flag != LGN_SUCCESS) return flag;
    col = SUNDenseMatrix_Column(mem->Kmat, j);
    for (i = 0; i < nv; i++) col[i] = (r[i] - r0[i]) / eps;
  }
  return LGN_SUCCESS;
}

static int DampingDQ(LGNMem mem, sunrealtype t)
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
    ret = lgnCallbackVector(mem, LGN_CB_FORCE,
                            mem->force(t, mem->q1, mem->dq_v, mem->dq_g, mem->user_data),
                            mem->dq_g, "LGNSolve");
    if (ret != LGN_SUCCESS) return ret;
    col = SUNDenseMatrix_Column(mem->Cmat, j);
    for (i = 0; i < nv; i++) col[i] = (g[i] - g0[i]) / eps;
    vp[j] = v1[j];
  }
  return LGN_SUCCESS;
}

/* z = B(q', t) v + Phi_t(q', t) at q' = q o exp(w) (length m), using dq_q
 * and Bdq: one constraint Jacobian evaluation at a point displaced along
 * the group. */
static int ConstraintVelocityAt(LGNMem mem, sunrealtype t, N_Vector q,
                                const sunrealtype *w, N_Vector v, sunrealtype *z)
{
  int ret = mem->G->ops.compose_exp(mem->G, lgnData(q), w, lgnData(mem->dq_q));
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
  mem->ndq++;
  ret = lgnEvalConstraintJacobian(mem, t, mem->dq_q, mem->Bdq);
  if (ret != LGN_SUCCESS) return ret;
  return lgnConstraintVelocity(mem, t, mem->dq_q, mem->Bdq, lgnData(v), z);
}

int lgnCurvatureDQ(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v,
                   N_Vector z)
{
  sunindextype i, nv = mem->nv, m = mem->m;
  sunrealtype vmax = SUN_RCONST(0.0), eps;
  sunrealtype *zd = lgnData(z), *zm = lgnData(mem->dq_z), *w = mem->work_nv;
  const sunrealtype *vd = lgnData(v);
  int flag;

  /* |v|_inf of this rank's part: the quotient is local, and N_VMaxNorm
   * of an MPI vector would be a collective on the ranks without a
   * curvature callback only */
  for (i = 0; i < nv; i++) vmax = SUNMAX(vmax, fabs(vd[i]));

  if (vmax == SUN_RCONST(0.0) && mem->constr_time == NULL) {
    N_VConst(SUN_RCONST(0.0), z);
    return LGN_SUCCESS;
  }
  /* central difference along the motion (q exp(s v), t + s) of the
   * velocity constraint: step of size cbrt(uround) in the group, scaled by
   * max(|v|, 1/|t|) when the constraints depend on t */
  if (mem->constr_time != NULL)
    vmax = SUNMAX(vmax, SUN_RCONST(1.0) / SUNMAX(SUN_RCONST(1.0), fabs(t)));
  eps = cbrt(SUN_UNIT_ROUNDOFF) / vmax;
  for (i = 0; i < nv; i++) w[i] = eps * vd[i];
  flag = ConstraintVelocityAt(mem, mem->constr_time != NULL ? t + eps : t, q, w, v, zd);
  for (i = 0; i < nv; i++) w[i] = -eps * vd[i];
  if (flag == LGN_SUCCESS)
    flag = ConstraintVelocityAt(mem, mem->constr_time != NULL ? t - eps : t, q, w, v, zm);
  if (flag != LGN_SUCCESS) return flag;
  for (i = 0; i < m; i++) zd[i] = (zd[i] - zm[i]) / (SUN_RCONST(2.0) * eps);
  return LGN_SUCCESS;
}

/* Bvq = D_q(B(q) v1 + Phi_t(q)).(q w~) at q1 by forward differences, m x nv
 * column-major: the change of the index-2 constraint B(q) v with the
 * configuration, which the iteration matrix needs next to B dv. */
int lgnConstraintVelocityDQ(LGNMem mem, sunrealtype t)
{
  sunindextype i, j, nv = mem->nv, m = mem->m;
  const sunrealtype srur = sqrt(SUN_UNIT_ROUNDOFF);
  sunrealtype *w = mem->work_nv, *z0 = lgnData(mem->dq_z), eps;
  int flag;

  flag = lgnConstraintVelocity(mem, t, mem->q1, mem->Bmat, lgnData(mem->v1), z0);
  if (flag != LGN_SUCCESS) return flag;
  for (j = 0; j < nv; j++) {
    sunrealtype *col = mem->Bvq + j * m;
    eps = srur * SUNMAX(SUN_RCONST(1.0), fabs(mem->sigma[j]));
    memset(w, 0, (size_t)nv * sizeof(sunrealtype));
    w[j] = eps;
    flag = ConstraintVelocityAt(mem, t, mem->q1, w, mem->v1, col);
    if (flag != LGN_SUCCESS) return flag;
    for (i = 0; i < m; i++) col[i] = (col[i] - z0[i]) / eps;
  }
  return LGN_SUCCESS;
}

/* =============================================================================
 * Sparse matrices: by column colours
 * ===========================================================================*/

/* Symmetric pattern blocks u M u M^T u B^T B of size nv x nv into P. */
static int BuildPattern(LGNMem mem, const LGNCsc *Mt, LGNCsc *P)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  const sunindextype nv = mem->nv;
  LGNColumnBuilder cb;
  sunindextype i, j, p, q;
  int b, flag;

  flag = lgnCscReserve(P, nv, nv, 2 * (sp->M.colptr[nv] + nv) + mem->tlen);
  if (flag != LGN_SUCCESS) return flag;
  P->colptr[0] = 0;
  cb.mark      = sp->mark;
  cb.list      = sp->list;
  for (j = 0; j < nv && flag == LGN_SUCCESS; j++) {
    cb.col = j;
    cb.cnt = 0;
    b = (int)mem->blk_of[j];
    for (i = mem->blk_voff[b]; i < mem->blk_voff[b + 1]; i++) lgnColumnAddRow(&cb, i);
    for (p = sp->M.colptr[j]; p < sp->M.colptr[j + 1]; p++) lgnColumnAddRow(&cb, sp->M.rowind[p]);
    for (p = Mt->colptr[j]; p < Mt->colptr[j + 1]; p++) lgnColumnAddRow(&cb, Mt->rowind[p]);
    if (mem->m > 0)
      for (p = sp->B.colptr[j]; p < sp->B.colptr[j + 1]; p++) {
        const sunindextype r = sp->B.rowind[p];
        for (q = sp->Bt.colptr[r]; q < sp->Bt.colptr[r + 1]; q++)
          lgnColumnAddRow(&cb, sp->Bt.rowind[q]);
      }
    flag = lgnCscAppendColumn(P, &cb);
  }
  for (j = 0; j < nv; j++) sp->mark[j] = -1;
  if (flag != LGN_SUCCESS) return flag;
  for (p = 0; p < P->colptr[nv]; p++) P->val[p] = SUN_RCONST(0.0);
  return LGN_SUCCESS;
}

/* The DQ patterns and colourings, from the current views of M and B. */
int lgnBuildDQPatterns(LGNMem mem)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  LGNCsc Mt;
  int flag;
  memset(&Mt, 0, sizeof Mt);
  flag = lgnCscTranspose(&sp->M, &Mt);
  if (flag == LGN_SUCCESS) flag = BuildPattern(mem, &Mt, &sp->Kdq);
  /* C_t too on B^T B: a damper between two jointed bodies couples them (a
   * pattern of blocks u M alone mixed its columns into other colours) */
  if (flag == LGN_SUCCESS) flag = BuildPattern(mem, &Mt, &sp->Cdq);
  if (flag == LGN_SUCCESS) flag = lgnColorColumns(&sp->Kdq, sp->mark, &sp->Kcol);
  if (flag == LGN_SUCCESS) flag = lgnColorColumns(&sp->Cdq, sp->mark, &sp->Ccol);
  lgnCscFree(&Mt);
  if (flag != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return flag;
  }
  sp->have_dq_patterns = SUNTRUE;
  return LGN_SUCCESS;
}

/* Increment of column j: the same rule as the dense quotients above. */
static sunrealtype Increment(sunrealtype x)
{
  return sqrt(SUN_UNIT_ROUNDOFF) * SUNMAX(SUN_RCONST(1.0), fabs(x));
}

/* The quotients of one colour: P(:, j) = (f - f0)(rows of column j) / eps_j. */
static void ScatterColor(const LGNCsc *P, sunrealtype *val,
                         const LGNColoring *col, sunindextype c,
                         const sunrealtype *f, const sunrealtype *f0,
                         const sunrealtype *x)
{
  sunindextype k, p, j;
  sunrealtype eps;
  for (k = col->ptr[c]; k < col->ptr[c + 1]; k++) {
    j   = col->cols[k];
    eps = Increment(x[j]);
    for (p = P->colptr[j]; p < P->colptr[j + 1]; p++)
      val[p] = (f[P->rowind[p]] - f0[P->rowind[p]]) / eps;
  }
}

/* w = eps_j e_j summed over the columns of colour c. */
static void ColorDisplacement(LGNMem mem, const LGNColoring *col,
                              sunindextype c, const sunrealtype *x,
                              sunrealtype *w)
{
  sunindextype k;
  memset(w, 0, (size_t)mem->nv * sizeof(sunrealtype));
  for (k = col->ptr[c]; k < col->ptr[c + 1]; k++)
    w[col->cols[k]] = Increment(x[col->cols[k]]);
}

static int StiffnessDQColored(LGNMem mem, sunrealtype t)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  sunindextype c;
  int ret, flag;
  for (c = 0; c < sp->Kcol.ncolors; c++) {
    ColorDisplacement(mem, &sp->Kcol, c, mem->sigma, mem->work_nv);
    ret = mem->G->ops.compose_exp(mem->G, lgnData(mem->q1), mem->work_nv,
                                  lgnData(mem->dq_q));
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
    flag = DQResidualAt(mem, t);
    if (flag != LGN_SUCCESS) return flag;
    ScatterColor(&sp->Kdq, sp->Kdq.val, &sp->Kcol, c, lgnData(mem->dq_r),
                 lgnData(mem->rdyn), mem->sigma);
  }
  return LGN_SUCCESS;
}

static int DampingDQColored(LGNMem mem, sunrealtype t)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  const sunrealtype *v1 = lgnData(mem->v1);
  sunrealtype *vp = lgnData(mem->dq_v), *w = mem->work_nv;
  sunindextype c, i;
  int ret;
  for (c = 0; c < sp->Ccol.ncolors; c++) {
    ColorDisplacement(mem, &sp->Ccol, c, v1, w);
    for (i = 0; i < mem->nv; i++) vp[i] = v1[i] + w[i];
    mem->ndq++;
    N_VConst(SUN_RCONST(0.0), mem->dq_g);
    ret = lgnCallbackVector(mem, LGN_CB_FORCE,
                            mem->force(t, mem->q1, mem->dq_v, mem->dq_g, mem->user_data),
                            mem->dq_g, "LGNSolve");
    if (ret != LGN_SUCCESS) return ret;
    ScatterColor(&sp->Cdq, sp->Cdq.val, &sp->Ccol, c, lgnData(mem->dq_g),
                 lgnData(mem->g), v1);
  }
  return LGN_SUCCESS;
}

/* D_q(B(q) v1 + Phi_t(q)) at q1 on the pattern of B (the CSC view sp->B;
 * Phi_t depends on the coordinates Phi does). */
int lgnConstraintVelocityDQColored(LGNMem mem, sunrealtype t)
{
  struct LGNSparseWorkRec *sp = mem->sp;
  const sunindextype nnzB = sp->B.colptr[mem->nv];
  sunrealtype *z0 = mem->work_m, *z = lgnData(mem->dq_z);
  sunindextype c;
  int flag;

  if (nnzB > sp->Bvq_cap) {
    sunrealtype *p = (sunrealtype *)realloc(sp->Bvq, (size_t)nnzB * sizeof *p);
    if (p == NULL) {
      LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
      return LGN_MEM_FAIL;
    }
    sp->Bvq     = p;
    sp->Bvq_cap = nnzB;
  }
  flag = lgnConstraintVelocity(mem, t, mem->q1, mem->Bmat, lgnData(mem->v1), z0);
  if (flag != LGN_SUCCESS) return flag;
  for (c = 0; c < sp->Kcol.ncolors; c++) {
    ColorDisplacement(mem, &sp->Kcol, c, mem->sigma, mem->work_nv);
    flag = ConstraintVelocityAt(mem, t, mem->q1, mem->work_nv, mem->v1, z);
    if (flag != LGN_SUCCESS) return flag;
    ScatterColor(&sp->B, sp->Bvq, &sp->Kcol, c, z, z0, mem->sigma);
  }
  return LGN_SUCCESS;
}

/* =============================================================================
 * K_t and C_t: the entry point
 * ===========================================================================*/

/* K and C at the current iterate: the user's callbacks, or difference
 * quotients (column by column for dense matrices, by column colours for
 * sparse ones). Shared by both assemblers. */
int lgnEvalTangents(LGNMem mem, sunrealtype t, sunrealtype cC, sunrealtype cK)
{
  int ret;
  if (cK != SUN_RCONST(0.0)) {
    if (mem->stiffness != NULL) {
      lgnMatClear(mem->Kmat);
      ret = lgnUserStiffness(mem, t, mem->q1, mem->v1, mem->vdot1, mem->lambda1,
                           mem->Kmat);
      ret = lgnCallbackMatrix(mem, LGN_CB_STIFFNESS, ret, mem->Kmat, "LGNSolve");
      if (ret != LGN_SUCCESS) return ret;
    } else {
      ret = mem->sparse ? StiffnessDQColored(mem, t) : StiffnessDQ(mem, t);
      if (ret != LGN_SUCCESS) return ret;
    }
  }
  if (cC != SUN_RCONST(0.0)) {
    if (mem->damping != NULL) {
      lgnMatClear(mem->Cmat);
      ret = mem->damping(t, mem->q1, mem->v1, mem->Cmat, mem->user_data);
      ret = lgnCallbackMatrix(mem, LGN_CB_DAMPING, ret, mem->Cmat, "LGNSolve");
      if (ret != LGN_SUCCESS) return ret;
    } else {
      ret = mem->sparse ? DampingDQColored(mem, t) : DampingDQ(mem, t);
      if (ret != LGN_SUCCESS) return ret;
    }
  }
  return LGN_SUCCESS;
}

