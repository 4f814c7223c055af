/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Planar joints (include/lignum/lignum_planar.h): the part of a joint set
 * on SE(2) or R^2 x SO(2) bodies. Every joint is made of rows of three
 * kinds, each evaluated on its two bodies with its gradient and Hessian
 * (lgn_planar.h), p = x + R s:
 *   POINT: e_i . (p_a - p_b)                 (revolute, i = 0, 1)
 *   ANGLE: theta_b - theta_a - theta0 - f(t)  (prismatic, rotation driver)
 *   LINE:  (R_a n) . (p_b - p_a) - f(t)       (prismatic: n perpendicular
 *                                             to the axis; translation
 *                                             driver: n the axis)
 * With r = R_a n, d = p_b - p_a, Dr = dr/dw = R_a J n at theta_a and
 * Dd = [-H_a, H_b], the LINE row has gradient r^T Dd + d^T Dr and Hessian
 * Dr^T Dd + Dd^T Dr - (r . d) e_th_a e_th_a^T + r . (E_b - E_a) terms.
 * Time terms (drivers): Phi_t = -f'(t), curvature v^T Hs v - f''(t).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "groups/lgn_group_impl.h"
#include "lgn_argcheck.h"
#include "lgn_matops.h"
#include "lgn_planar.h"

typedef enum { ROW_POINT = 0, ROW_ANGLE, ROW_LINE } RowKind;

typedef struct {
  RowKind kind;
  int a, b;
  int joint, jrow, jrows;       /* joint number, row in it, its row count */
  const char *jkind;            /* e.g. "planar revolute"                 */
  sunrealtype sa[2], sb[2], n[2];
  sunrealtype theta0;
  LGNDriveFn drive;
  void *drive_data;
  sunrealtype f[3];             /* f, f', f'' at the last evaluation      */
} Row;

struct lgnPlanarJointsRec {
  const LGNErrSink *err;
  LGNGroup G;
  int nb;
  sunindextype *qoff, *voff;
  sunbooleantype *se2;
  Row *row;
  sunindextype m, cap;
  int njoints, ndrivers;
  lgnPlanarPattern patB, patK;
};

lgnPlanarJoints *lgnPlanarJointsCreate(LGNGroup G, const LGNErrSink *err, const char *func)
{
  lgnPlanarJoints *P = (lgnPlanarJoints *)calloc(1, sizeof *P);
  const int nb = lgnGroupPlanarBodies(G, NULL, NULL, NULL);
  if (P != NULL) {
    P->qoff = (sunindextype *)malloc((size_t)nb * sizeof *P->qoff);
    P->voff = (sunindextype *)malloc((size_t)nb * sizeof *P->voff);
    P->se2  = (sunbooleantype *)malloc((size_t)nb * sizeof *P->se2);
  }
  if (P == NULL || P->qoff == NULL || P->voff == NULL || P->se2 == NULL) {
    lgnPlanarJointsDestroy(P);
    lgnReport(err, LGN_MEM_FAIL, func, "A memory request failed.");
    return NULL;
  }
  P->err = err;
  P->G   = G;
  P->nb  = nb;
  lgnGroupPlanarBodies(G, P->qoff, P->voff, P->se2);
  P->patB.fmt = P->patK.fmt = -1;
  return P;
}

void lgnPlanarJointsDestroy(lgnPlanarJoints *P)
{
  if (P == NULL) return;
  free(P->qoff);
  free(P->voff);
  free(P->se2);
  free(P->row);
  lgnPlanarPatternFree(&P->patB);
  lgnPlanarPatternFree(&P->patK);
  free(P);
}

sunindextype lgnPlanarJointsNumConstraints(const lgnPlanarJoints *P) { return P->m; }
int lgnPlanarJointsNumDrivers(const lgnPlanarJoints *P) { return P->ndrivers; }

/* ---------------------------------------------------------------------------
 * Adding joints
 * ------------------------------------------------------------------------ */

static int CheckBodies(const lgnPlanarJoints *P, int a, int b, const char *func)
{
  if (a < LGN_GROUND || a >= P->nb || b < LGN_GROUND || b >= P->nb || a == b) {
    lgnReport(P->err, LGN_ILL_INPUT, func,
              "bodies a = %d, b = %d illegal (0..%d or LGN_GROUND, a != b).", a, b,
              P->nb - 1);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

static int CheckVec2(const lgnPlanarJoints *P, const sunrealtype *x, const char *name,
                     sunbooleantype nonzero, const char *func)
{
  if (x == NULL) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "%s = NULL illegal.", name);
    return LGN_ILL_INPUT;
  }
  if (!isfinite(x[0]) || !isfinite(x[1]) || (nonzero && x[0] == 0 && x[1] == 0)) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "%s = (%g, %g) illegal: %s.", name,
              (double)x[0], (double)x[1], nonzero ? "not finite or zero" : "not finite");
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

/* Room for n more rows. */
static int Reserve(lgnPlanarJoints *P, sunindextype n, const char *func)
{
  if (P->m + n > P->cap) {
    const sunindextype cap = 2 * P->cap + n + 8;
    Row *r = (Row *)realloc(P->row, (size_t)cap * sizeof *r);
    if (r == NULL) {
      lgnReport(P->err, LGN_MEM_FAIL, func, "A memory request failed.");
      return LGN_MEM_FAIL;
    }
    P->row = r;
    P->cap = cap;
  }
  return LGN_SUCCESS;
}

static Row *NewRow(lgnPlanarJoints *P, RowKind kind, int a, int b, int jrow, int jrows,
                   const char *jkind)
{
  Row *r = P->row + P->m++;
  memset(r, 0, sizeof *r);
  r->kind  = kind;
  r->a     = a;
  r->b     = b;
  r->joint = P->njoints;
  r->jrow  = jrow;
  r->jrows = jrows;
  r->jkind = jkind;
  return r;
}

static void EndJoint(lgnPlanarJoints *P)
{
  P->njoints++;
  lgnPlanarPatternFree(&P->patB);
  lgnPlanarPatternFree(&P->patK);
}

static int AddRevolute(lgnPlanarJoints *P, int a, const sunrealtype sa[2], int b,
                       const sunrealtype sb[2], const char *func)
{
  int i;
  if (Reserve(P, 2, func) != LGN_SUCCESS) return LGN_MEM_FAIL;
  for (i = 0; i < 2; i++) {
    Row *r = NewRow(P, ROW_POINT, a, b, i, 2, "planar revolute");
    r->sa[0] = sa[0];
    r->sa[1] = sa[1];
    r->sb[0] = sb[0];
    r->sb[1] = sb[1];
    r->n[i]  = 1;
  }
  EndJoint(P);
  return LGN_SUCCESS;
}

int lgnPlanarJointsAddRevolute2(lgnPlanarJoints *P, int a, const sunrealtype sa[2], int b,
                                const sunrealtype sb[2], const char *func)
{
  if (CheckBodies(P, a, b, func) != LGN_SUCCESS ||
      CheckVec2(P, sa, "sa", SUNFALSE, func) != LGN_SUCCESS ||
      CheckVec2(P, sb, "sb", SUNFALSE, func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  return AddRevolute(P, a, sa, b, sb, func);
}

int lgnPlanarJointsAddRevolute3(lgnPlanarJoints *P, int a, const sunrealtype sa[3],
                                const sunrealtype axis_a[3], int b,
                                const sunrealtype sb[3], const sunrealtype axis_b[3],
                                const char *func)
{
  if (CheckBodies(P, a, b, func) != LGN_SUCCESS ||
      lgnCheckVec3(P->err, sa, "sa", func) != LGN_SUCCESS ||
      lgnCheckVec3(P->err, sb, "sb", func) != LGN_SUCCESS ||
      lgnCheckVec3(P->err, axis_a, "axis_a", func) != LGN_SUCCESS ||
      lgnCheckVec3(P->err, axis_b, "axis_b", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (axis_a[0] != 0 || axis_a[1] != 0 || axis_a[2] == 0 || axis_b[0] != 0 ||
      axis_b[1] != 0 || axis_b[2] == 0) {
    lgnReport(P->err, LGN_ILL_INPUT, func,
              "axis_a = (%g, %g, %g), axis_b = (%g, %g, %g) illegal: on a planar group "
              "a revolute joint turns about the plane's normal (0, 0, 1).",
              (double)axis_a[0], (double)axis_a[1], (double)axis_a[2], (double)axis_b[0],
              (double)axis_b[1], (double)axis_b[2]);
    return LGN_ILL_INPUT;
  }
  if (sa[2] != 0 || sb[2] != 0) {
    lgnReport(P->err, LGN_ILL_INPUT, func,
              "sa[2] = %g, sb[2] = %g illegal: the points of a planar body lie in the "
              "plane (z = 0).", (double)sa[2], (double)sb[2]);
    return LGN_ILL_INPUT;
  }
  return AddRevolute(P, a, sa, b, sb, func);
}

int lgnPlanarJointsAddPrismatic(lgnPlanarJoints *P, int a, const sunrealtype sa[2],
                                const sunrealtype axis_a[2], int b, const sunrealtype sb[2],
                                sunrealtype theta0, const char *func)
{
  sunrealtype len;
  Row *r;
  if (CheckBodies(P, a, b, func) != LGN_SUCCESS ||
      CheckVec2(P, sa, "sa", SUNFALSE, func) != LGN_SUCCESS ||
      CheckVec2(P, axis_a, "axis_a", SUNTRUE, func) != LGN_SUCCESS ||
      CheckVec2(P, sb, "sb", SUNFALSE, func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (!isfinite(theta0)) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "theta0 = %g illegal: not finite.",
              (double)theta0);
    return LGN_ILL_INPUT;
  }
  if (Reserve(P, 2, func) != LGN_SUCCESS) return LGN_MEM_FAIL;
  len = hypot(axis_a[0], axis_a[1]);
  r   = NewRow(P, ROW_LINE, a, b, 0, 2, "planar prismatic");
  r->sa[0] = sa[0];
  r->sa[1] = sa[1];
  r->sb[0] = sb[0];
  r->sb[1] = sb[1];
  r->n[0]  = -axis_a[1] / len; /* perpendicular to the axis */
  r->n[1]  = axis_a[0] / len;
  r = NewRow(P, ROW_ANGLE, a, b, 1, 2, "planar prismatic");
  r->theta0 = theta0;
  EndJoint(P);
  return LGN_SUCCESS;
}

static int CheckDrive(const lgnPlanarJoints *P, LGNDriveFn f, const char *func)
{
  if (f == NULL) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "f = NULL illegal: a driver needs its time law.");
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int lgnPlanarJointsAddRotationDriver(lgnPlanarJoints *P, int a, int b, LGNDriveFn f,
                                     void *drive_data, const char *func)
{
  Row *r;
  if (CheckBodies(P, a, b, func) != LGN_SUCCESS || CheckDrive(P, f, func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (Reserve(P, 1, func) != LGN_SUCCESS) return LGN_MEM_FAIL;
  r = NewRow(P, ROW_ANGLE, a, b, 0, 1, "planar rotation driver");
  r->drive      = f;
  r->drive_data = drive_data;
  P->ndrivers++;
  EndJoint(P);
  return LGN_SUCCESS;
}

int lgnPlanarJointsAddTranslationDriver(lgnPlanarJoints *P, int a, const sunrealtype sa[2],
                                        const sunrealtype axis_a[2], int b,
                                        const sunrealtype sb[2], LGNDriveFn f,
                                        void *drive_data, const char *func)
{
  sunrealtype len;
  Row *r;
  if (CheckBodies(P, a, b, func) != LGN_SUCCESS ||
      CheckVec2(P, sa, "sa", SUNFALSE, func) != LGN_SUCCESS ||
      CheckVec2(P, axis_a, "axis_a", SUNTRUE, func) != LGN_SUCCESS ||
      CheckVec2(P, sb, "sb", SUNFALSE, func) != LGN_SUCCESS ||
      CheckDrive(P, f, func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (Reserve(P, 1, func) != LGN_SUCCESS) return LGN_MEM_FAIL;
  len = hypot(axis_a[0], axis_a[1]);
  r   = NewRow(P, ROW_LINE, a, b, 0, 1, "planar translation driver");
  r->sa[0]      = sa[0];
  r->sa[1]      = sa[1];
  r->sb[0]      = sb[0];
  r->sb[1]      = sb[1];
  r->n[0]       = axis_a[0] / len;
  r->n[1]       = axis_a[1] / len;
  r->drive      = f;
  r->drive_data = drive_data;
  P->ndrivers++;
  EndJoint(P);
  return LGN_SUCCESS;
}

int lgnPlanarJointsDescribe(const lgnPlanarJoints *P, sunindextype row, char *buf,
                            size_t len, const char *func)
{
  const Row *r;
  char ba[24], bb[24];
  if (buf == NULL || len == 0) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "buf = NULL or len = 0 illegal.");
    return LGN_ILL_INPUT;
  }
  if (row < 0 || row >= P->m) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "row = %lld illegal: the joints have %lld rows.",
              (long long)row, (long long)P->m);
    return LGN_ILL_INPUT;
  }
  r = P->row + row;
  if (r->a == LGN_GROUND) snprintf(ba, sizeof ba, "the ground");
  else snprintf(ba, sizeof ba, "body %d", r->a);
  if (r->b == LGN_GROUND) snprintf(bb, sizeof bb, "the ground");
  else snprintf(bb, sizeof bb, "body %d", r->b);
  if (r->drive != NULL)
    snprintf(buf, len, "%s (joint %d: %s - %s), its constraint 1 of 1", r->jkind, r->joint,
             ba, bb);
  else
    snprintf(buf, len, "%s joint %d (%s - %s), its constraint %d of %d", r->jkind, r->joint,
             ba, bb, r->jrow + 1, r->jrows);
  return LGN_SUCCESS;
}

/* ---------------------------------------------------------------------------
 * Local evaluation of one row
 * ------------------------------------------------------------------------ */

static void GetPose(const lgnPlanarJoints *P, int k, const sunrealtype *q,
                    const sunrealtype *v, lgnPlanarPose *X)
{
  memset(X, 0, sizeof *X);
  X->ground = k == LGN_GROUND;
  X->c      = 1;
  X->voff   = -1;
  if (X->ground) return;
  X->se2  = P->se2[k];
  X->x[0] = q[P->qoff[k]];
  X->x[1] = q[P->qoff[k] + 1];
  X->th   = q[P->qoff[k] + 2];
  X->c    = cos(X->th);
  X->s    = sin(X->th);
  X->voff = P->voff[k];
  if (v != NULL) {
    X->v[0] = v[X->voff];
    X->v[1] = v[X->voff + 1];
    X->v[2] = v[X->voff + 2];
  }
}

/* phi, its gradient g (a's 3 directions, then b's) and, with Hs not NULL,
 * its Hessian Hs[6 u + w] = D_w D_u phi; A, B the poses of a and b. */
static void RowLocal(const Row *r, const lgnPlanarPose *A, const lgnPlanarPose *B,
                     sunrealtype *phi, sunrealtype g[6], sunrealtype *Hs)
{
  sunrealtype pa[2], pb[2], Ha[6], Hb[6];
  int i, j;
  if (Hs != NULL)
    for (i = 0; i < 36; i++) Hs[i] = 0;
  if (r->kind == ROW_ANGLE) {
    *phi = B->th - A->th - r->theta0 - r->f[0];
    g[0] = g[1] = g[3] = g[4] = 0;
    g[2] = A->ground ? 0 : -1;
    g[5] = B->ground ? 0 : 1;
    return;
  }
  lgnPlanarPoint(A, r->sa, pa, Ha);
  lgnPlanarPoint(B, r->sb, pb, Hb);
  if (r->kind == ROW_POINT) { /* n . (p_a - p_b) */
    *phi = r->n[0] * (pa[0] - pb[0]) + r->n[1] * (pa[1] - pb[1]);
    for (i = 0; i < 3; i++) {
      g[i]     = r->n[0] * Ha[i] + r->n[1] * Ha[3 + i];
      g[3 + i] = -(r->n[0] * Hb[i] + r->n[1] * Hb[3 + i]);
    }
    if (Hs != NULL) {
      lgnPlanarPointHessian(A, r->sa, r->n, 1, 0, Hs);
      lgnPlanarPointHessian(B, r->sb, r->n, -1, 3, Hs);
    }
    return;
  }
  { /* LINE: rv . d - f, rv = R_a n, d = p_b - p_a */
    const sunrealtype rv[2] = {A->c * r->n[0] - A->s * r->n[1],
                               A->s * r->n[0] + A->c * r->n[1]};
    const sunrealtype d[2]  = {pb[0] - pa[0], pb[1] - pa[1]};
    const sunrealtype dr[2] = {-rv[1], rv[0]}; /* dr/dtheta_a = J R_a n */
    sunrealtype Dd[12], Dr[12];
    *phi = rv[0] * d[0] + rv[1] * d[1] - r->f[0];
    for (i = 0; i < 3; i++) {
      Dd[i] = -Ha[i];
      Dd[6 + i] = -Ha[3 + i];
      Dd[3 + i] = Hb[i];
      Dd[9 + i] = Hb[3 + i];
    }
    for (i = 0; i < 12; i++) Dr[i] = 0;
    if (!A->ground) {
      Dr[2] = dr[0];
      Dr[8] = dr[1];
    }
    for (j = 0; j < 6; j++)
      g[j] = rv[0] * Dd[j] + rv[1] * Dd[6 + j] + d[0] * Dr[j] + d[1] * Dr[6 + j];
    if (Hs == NULL) return;
    for (i = 0; i < 6; i++)
      for (j = 0; j < 6; j++)
        Hs[6 * i + j] = Dr[i] * Dd[j] + Dr[6 + i] * Dd[6 + j] + Dd[i] * Dr[j] +
                        Dd[6 + i] * Dr[6 + j];
    if (!A->ground) Hs[6 * 2 + 2] -= rv[0] * d[0] + rv[1] * d[1];
    lgnPlanarPointHessian(A, r->sa, rv, -1, 0, Hs);
    lgnPlanarPointHessian(B, r->sb, rv, 1, 3, Hs);
  }
}

/* ---------------------------------------------------------------------------
 * Evaluations
 * ------------------------------------------------------------------------ */

static int EvalDrivers(lgnPlanarJoints *P, sunrealtype t, const char *func)
{
  sunindextype k;
  int ret;
  if (P->ndrivers == 0) return LGN_SUCCESS;
  if (!isfinite(t)) {
    lgnReport(P->err, LGN_ILL_INPUT, func, "t = %g illegal: the drivers need a finite time.",
              (double)t);
    return LGN_ILL_INPUT;
  }
  for (k = 0; k < P->m; k++) {
    Row *r = P->row + k;
    if (r->drive == NULL) continue;
    r->f[0] = r->f[1] = r->f[2] = 0;
    ret = r->drive(t, r->f, r->drive_data);
    if (ret != 0 || !isfinite(r->f[0]) || !isfinite(r->f[1]) || !isfinite(r->f[2])) {
      lgnReport(P->err, LGN_CONSTR_FAIL, func,
                "the time law of driver (joint %d) failed at t = %g: it returned %d, "
                "f = (%g, %g, %g).", r->joint, (double)t, ret, (double)r->f[0],
                (double)r->f[1], (double)r->f[2]);
      return LGN_CONSTR_FAIL;
    }
  }
  return LGN_SUCCESS;
}

static int CheckVec(const lgnPlanarJoints *P, N_Vector x, sunindextype n, const char *name,
                    const char *func)
{
  return lgnCheckSerialVector(P->err, x, n, name, func);
}

int lgnPlanarJointsResidual(lgnPlanarJoints *P, sunrealtype t, N_Vector q, N_Vector phi,
                            const char *func)
{
  const sunrealtype *qd;
  sunrealtype *pd, g[6];
  lgnPlanarPose A, B;
  sunindextype k;
  int ret;
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      CheckVec(P, phi, P->m, "phi", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if ((ret = EvalDrivers(P, t, func)) != LGN_SUCCESS) return ret;
  qd = lgnVecData(q);
  pd = lgnVecData(phi);
  for (k = 0; k < P->m; k++) {
    GetPose(P, P->row[k].a, qd, NULL, &A);
    GetPose(P, P->row[k].b, qd, NULL, &B);
    RowLocal(P->row + k, &A, &B, pd + k, g, NULL);
  }
  return LGN_SUCCESS;
}

int lgnPlanarJointsTimeDerivative(lgnPlanarJoints *P, sunrealtype t, N_Vector q,
                                  N_Vector phit, const char *func)
{
  sunrealtype *pd;
  sunindextype k;
  int ret;
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      CheckVec(P, phit, P->m, "phit", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if ((ret = EvalDrivers(P, t, func)) != LGN_SUCCESS) return ret;
  pd = lgnVecData(phit);
  for (k = 0; k < P->m; k++) pd[k] = P->row[k].drive != NULL ? -P->row[k].f[1] : 0;
  return LGN_SUCCESS;
}

int lgnPlanarJointsCurvature(lgnPlanarJoints *P, sunrealtype t, N_Vector q, N_Vector v,
                             N_Vector z, const char *func)
{
  const sunrealtype *qd, *vd;
  sunrealtype *zd, g[6], Hs[36], phi;
  lgnPlanarPose A, B;
  sunindextype k;
  int ret, i, j;
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      CheckVec(P, v, P->G->nv, "v", func) != LGN_SUCCESS ||
      CheckVec(P, z, P->m, "z", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if ((ret = EvalDrivers(P, t, func)) != LGN_SUCCESS) return ret;
  qd = lgnVecData(q);
  vd = lgnVecData(v);
  zd = lgnVecData(z);
  for (k = 0; k < P->m; k++) {
    sunrealtype vl[6], s = 0;
    GetPose(P, P->row[k].a, qd, vd, &A);
    GetPose(P, P->row[k].b, qd, vd, &B);
    RowLocal(P->row + k, &A, &B, &phi, g, Hs);
    for (i = 0; i < 3; i++) {
      vl[i]     = A.v[i];
      vl[3 + i] = B.v[i];
    }
    for (i = 0; i < 6; i++)
      for (j = 0; j < 6; j++) s += vl[i] * Hs[6 * i + j] * vl[j];
    zd[k] = s - (P->row[k].drive != NULL ? P->row[k].f[2] : 0);
  }
  return LGN_SUCCESS;
}

int lgnPlanarJointsConstraintForce(lgnPlanarJoints *P, sunrealtype t, N_Vector q,
                                   N_Vector lambda, N_Vector f, const char *func)
{
  const sunrealtype *qd, *ld;
  sunrealtype *fd, g[6], phi;
  lgnPlanarPose A, B;
  sunindextype k;
  int ret, i;
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      CheckVec(P, lambda, P->m, "lambda", func) != LGN_SUCCESS ||
      CheckVec(P, f, P->G->nv, "f", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if ((ret = EvalDrivers(P, t, func)) != LGN_SUCCESS) return ret;
  qd = lgnVecData(q);
  ld = lgnVecData(lambda);
  fd = lgnVecData(f);
  for (i = 0; i < P->G->nv; i++) fd[i] = 0;
  for (k = 0; k < P->m; k++) {
    GetPose(P, P->row[k].a, qd, NULL, &A);
    GetPose(P, P->row[k].b, qd, NULL, &B);
    RowLocal(P->row + k, &A, &B, &phi, g, NULL);
    for (i = 0; i < 3; i++) {
      if (!A.ground) fd[A.voff + i] += ld[k] * g[i];
      if (!B.ground) fd[B.voff + i] += ld[k] * g[3 + i];
    }
  }
  return LGN_SUCCESS;
}

/* The matrices, entry by entry (lgnPlanarWrite): q NULL in collect mode */
typedef struct {
  lgnPlanarJoints *P;
  const sunrealtype *q, *lambda;
} GenCtx;

static int GenJacobian(void *vctx, lgnPlanarSink *s)
{
  const GenCtx *c = (const GenCtx *)vctx;
  const lgnPlanarJoints *P = c->P;
  sunrealtype g[6] = {0, 0, 0, 0, 0, 0}, phi;
  lgnPlanarPose A, B;
  sunindextype k;
  int i;
  for (k = 0; k < P->m; k++) {
    const Row *r = P->row + k;
    if (s->mode != LGN_PA_COLLECT) {
      GetPose(P, r->a, c->q, NULL, &A);
      GetPose(P, r->b, c->q, NULL, &B);
      RowLocal(r, &A, &B, &phi, g, NULL);
    }
    for (i = 0; i < 3; i++)
      if (r->a != LGN_GROUND) lgnPlanarEmit(s, k, P->voff[r->a] + i, g[i]);
    for (i = 0; i < 3; i++)
      if (r->b != LGN_GROUND) lgnPlanarEmit(s, k, P->voff[r->b] + i, g[3 + i]);
  }
  return LGN_SUCCESS;
}

static int GenStiffness(void *vctx, lgnPlanarSink *s)
{
  const GenCtx *c = (const GenCtx *)vctx;
  const lgnPlanarJoints *P = c->P;
  sunrealtype g[6], Hs[36], phi;
  lgnPlanarPose A, B;
  sunindextype k;
  int i, j, bi, bj;
  for (i = 0; i < 36; i++) Hs[i] = 0;
  for (k = 0; k < P->m; k++) {
    const Row *r = P->row + k;
    const int body[2] = {r->a, r->b};
    if (r->kind == ROW_ANGLE) continue; /* linear: no stiffness */
    if (s->mode != LGN_PA_COLLECT) {
      GetPose(P, r->a, c->q, NULL, &A);
      GetPose(P, r->b, c->q, NULL, &B);
      RowLocal(r, &A, &B, &phi, g, Hs);
    }
    for (bj = 0; bj < 2; bj++)
      for (bi = 0; bi < 2; bi++) {
        if (body[bi] == LGN_GROUND || body[bj] == LGN_GROUND) continue;
        for (j = 0; j < 3; j++)
          for (i = 0; i < 3; i++)
            lgnPlanarEmit(s, P->voff[body[bi]] + i, P->voff[body[bj]] + j,
                          s->mode == LGN_PA_COLLECT
                              ? 0
                              : c->lambda[k] * Hs[6 * (3 * bi + i) + 3 * bj + j]);
      }
  }
  return LGN_SUCCESS;
}

sunindextype lgnPlanarJointsJacobianNnz(lgnPlanarJoints *P)
{
  GenCtx c = {P, NULL, NULL};
  lgnPlanarPattern pat;
  sunindextype n;
  memset(&pat, 0, sizeof pat);
  pat.fmt = -1;
  n = lgnPlanarCount(&pat, P->G->nv, GenJacobian, &c);
  lgnPlanarPatternFree(&pat);
  return n;
}

sunindextype lgnPlanarJointsStiffnessNnz(lgnPlanarJoints *P)
{
  GenCtx c = {P, NULL, NULL};
  lgnPlanarPattern pat;
  sunindextype n;
  memset(&pat, 0, sizeof pat);
  pat.fmt = -1;
  n = lgnPlanarCount(&pat, P->G->nv, GenStiffness, &c);
  lgnPlanarPatternFree(&pat);
  return n;
}

int lgnPlanarJointsJacobian(lgnPlanarJoints *P, sunrealtype t, N_Vector q, SUNMatrix B,
                            const char *func)
{
  GenCtx c = {P, NULL, NULL};
  int ret;
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      lgnPlanarCheckMat(B, P->m, P->G->nv, "B", P->err, func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if ((ret = EvalDrivers(P, t, func)) != LGN_SUCCESS) return ret;
  c.q = lgnVecData(q);
  return lgnPlanarWrite(&P->patB, B, SUNTRUE, GenJacobian, &c, P->err, func);
}

int lgnPlanarJointsStiffness(lgnPlanarJoints *P, sunrealtype t, N_Vector q,
                             N_Vector lambda, SUNMatrix K, const char *func)
{
  GenCtx c = {P, NULL, NULL};
  int ret;
  if (CheckVec(P, q, P->G->nq, "q", func) != LGN_SUCCESS ||
      CheckVec(P, lambda, P->m, "lambda", func) != LGN_SUCCESS ||
      lgnPlanarCheckMat(K, P->G->nv, P->G->nv, "K", P->err, func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if ((ret = EvalDrivers(P, t, func)) != LGN_SUCCESS) return ret;
  c.q      = lgnVecData(q);
  c.lambda = lgnVecData(lambda);
  return lgnPlanarWrite(&P->patK, K, SUNFALSE, GenStiffness, &c, P->err, func);
}
