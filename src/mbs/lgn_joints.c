/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Joint constraints (include/lignum/lignum_joints.h). Every joint is made of
 * three primitives:
 *   POINT (3 rows):  x_a + R_a s_a - x_b - R_b s_b
 *   PERP  (1 row):   (R_a e) . (R_b c)
 *   LINE  (1 row):   (R_a e) . (p_b - p_a),  p = x + R s  (point on a line)
 * with, along q o exp(w) (body velocity w = (w_x, w_theta)):
 *   d x = P w_x  (P = I on R^3 x SO(3), P = R on SE(3)),  d R = R w_theta~
 * so that
 *   B_POINT = [ P_a, -R_a s_a~ | -P_b, R_b s_b~ ]
 *   B_PERP  = [ 0, (e x R_a^T R_b c)^T | 0, (c x R_b^T R_a e)^T ]
 *   B_LINE  = [ -(P_a^T r)^T, (e x rho)^T | (P_b^T r)^T, (s_b x R_b^T r)^T ]
 * (r = R_a e, rho = R_a^T (p_b - x_a): p_b in the frame of a).
 * The curvature Z(q)(v,v) is the second time derivative of Phi along the
 * flow with constant body velocities, and the geometric stiffness is
 * d/dq (B^T lambda) along the group; the formulas are at each routine.
 * Every evaluation first computes the rotation of each jointed body once
 * (FillRotations). The pattern of a sparse B depends only on the joints: it
 * is built on the first call and kept, and later calls write the values
 * straight to their positions.
 * A pure helper layer: it knows nothing of the integrator's memory record
 * (lgn_impl.h) and reports errors through its own sink (lgn_err.h), always
 * under the name of the public function that was called.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum_joints.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "groups/lgn_group_impl.h"
#include "lgn_matops.h"
#include "groups/lgn_so3.h"
#include "lgn_argcheck.h"
#include "lgn_err.h"
#include "lgn_planar.h"
#include "lgn_mbs.h"

#ifdef LGN_IMPL_H
#error "lgn_joints.c is a pure helper: it must not see the integrator's memory record"
#endif

typedef enum { PRIM_POINT = 0, PRIM_PERP = 1, PRIM_LINE = 2 } PrimKind;

typedef struct {
  PrimKind kind;
  int a, b;             /* bodies, or LGN_GROUND                          */
  sunrealtype u[3];     /* POINT: s_a;  PERP: e (body a)                   */
  sunrealtype w[3];     /* POINT: s_b;  PERP: c (body b)                   */
  sunrealtype e[3];     /* LINE: e (body a), with s_a in u and s_b in w    */
  sunindextype row;     /* first row in Phi                                */
  int joint;            /* the joint it belongs to (0, 1, ... in order)    */
  const char *jkind;    /* ... and its kind: "spherical", "revolute", ...  */
  /* a driver (drive != NULL): PERP with e = e(t) = cos f d0 + sin f d1 in
   * u (rotation driver), or LINE minus f(t) (translation driver) */
  LGNDriveFn drive;
  void *drive_data;
  sunrealtype d0[3], d1[3];
  sunrealtype f[3];     /* f, f', f'' at the last evaluation               */
  sunrealtype ud[3], udd[3]; /* rotation driver: e'(t), e''(t)            */
} Primitive;

struct LGNJointsRec {
  LGNErrSink err;             /* where error messages go                   */
  LGNGroup G;
  int nb;                     /* bodies                                    */
  sunindextype *qoff, *voff;  /* offsets of each body                      */
  sunbooleantype *se3;        /* body on SE(3) (else R^3 x SO(3))          */
  sunbooleantype *injoint;    /* body appears in a primitive               */
  sunbooleantype *online;     /* body appears in a LINE primitive: its
                                 blocks of the sparse K are full 6 x 6    */
  sunrealtype *rot;           /* ROT_STRIDE per body: R(p) (9, row-major)
                                 and the quaternion p it is of (4)        */
  Primitive *prim;
  int nprim, cap;
  int njoints;                /* joints added                              */
  int ndrivers;               /* of them drivers                           */
  sunindextype m;
  sunindextype nnzB;          /* entries of B (explicit zeros included)    */
  /* pattern of the sparse B in format bfmt (NO_PATTERN: none yet), and the
   * position in its data of each entry in generation order */
  int bfmt;
  sunindextype *bptr, *bind;  /* index pointers, index values              */
  sunindextype *bpos;         /* nnzB                                      */
  lgnPlanarJoints *planar;    /* a planar set (lgn_planar_joints.c), which
                                 answers every call itself; else NULL       */
  /* geometric stiffness: per body, the sorted list of coupled bodies */
  int *kptr, *kbody;          /* nb + 1, kptr[nb]                          */
  sunrealtype *kblk;          /* 36 per (body, coupled body), column-major */
  SUNMatrix work;             /* the sparse K added to a matrix with entries */
};

#define NO_PATTERN (-1) /* bfmt before the first sparse B and after an Add */
#define ROT_STRIDE 13   /* R(p) and p per body in rot                       */

#define MSG_MEM_FAIL "A memory request failed." /* as the integrator's */

#if defined(__GNUC__) || defined(__clang__)
#define JERR_FORMAT __attribute__((format(printf, 4, 5)))
#else
#define JERR_FORMAT
#endif

/* Report an error of the public function func through J's own sink. */
static void JErr(const struct LGNJointsRec *J, int code, const char *func,
                 const char *msgfmt, ...) JERR_FORMAT;
static void JErr(const struct LGNJointsRec *J, int code, const char *func,
                 const char *msgfmt, ...)
{
  va_list ap;
  va_start(ap, msgfmt);
  lgnReportV(&J->err, code, func, msgfmt, ap);
  va_end(ap);
}

/* J = NULL given to the public function func: there is no sink to find, so
 * the message goes to stderr. Returns the flag. */
static int NullJoints(const char *func)
{
  lgnReport(NULL, LGN_ILL_INPUT, func, "J = NULL illegal.");
  return LGN_ILL_INPUT;
}

/* ---------------------------------------------------------------------------
 * Column-major 3x3 kernels (the row-major 3-vector ones, for R as
 * LGNQuaternionToRotation writes it, are in groups/lgn_so3.h)
 * ------------------------------------------------------------------------ */

/* x~ as a column-major 3x3 (X[i + 3 j]). */
static void Skew(const sunrealtype *x, sunrealtype *X)
{
  X[0] = 0;     X[3] = -x[2]; X[6] = x[1];
  X[1] = x[2];  X[4] = 0;     X[7] = -x[0];
  X[2] = -x[1]; X[5] = x[0];  X[8] = 0;
}

/* C = A B for column-major 3x3. */
static void Mul3(const sunrealtype *A, const sunrealtype *B, sunrealtype *C)
{
  int i, j;
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++)
      C[i + 3 * j] = A[i] * B[3 * j] + A[i + 3] * B[3 * j + 1] + A[i + 6] * B[3 * j + 2];
}

/* R(q) of every body that appears in a joint, once per evaluation: a chain
 * body is in two joints, and each joint reads it in several primitives.
 * A rotation whose quaternion is bit for bit the one of the last call is
 * kept (the residual, the constraint forces and B are evaluated at the
 * same iterate); the stored quaternions start as NaN, equal to nothing. */
static void FillRotations(struct LGNJointsRec *J, const sunrealtype *q)
{
  int k;
  for (k = 0; k < J->nb; k++) {
    const sunrealtype *p = q + J->qoff[k] + 3;
    sunrealtype *R = J->rot + ROT_STRIDE * (size_t)k, *pR = R + 9;
    if (!J->injoint[k]) continue;
    if (p[0] == pR[0] && p[1] == pR[1] && p[2] == pR[2] && p[3] == pR[3]) continue;
    LGNQuaternionToRotation(p, R);
    pR[0] = p[0]; pR[1] = p[1]; pR[2] = p[2]; pR[3] = p[3];
  }
}

/* Position and rotation of a body (identity for the ground), pointing into
 * q and the rotations of FillRotations. */
typedef struct {
  const sunrealtype *x, *R;
  const sunrealtype *v;   /* body velocity (u or U, Omega), NULL: none */
  sunbooleantype se3, ground;
  sunindextype voff;
} Pose;

static const sunrealtype Origin[3]   = {0, 0, 0};
static const sunrealtype Identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

static void GetPose(const struct LGNJointsRec *J, int k, const sunrealtype *q,
                    const sunrealtype *v, Pose *P)
{
  P->ground = (k == LGN_GROUND);
  if (P->ground) {
    P->x    = Origin;
    P->R    = Identity;
    P->v    = NULL;
    P->se3  = SUNFALSE;
    P->voff = -1;
    return;
  }
  P->x    = q + J->qoff[k];
  P->R    = J->rot + ROT_STRIDE * (size_t)k;
  P->v    = v != NULL ? v + J->voff[k] : NULL;
  P->se3  = J->se3[k];
  P->voff = J->voff[k];
}

/* ---------------------------------------------------------------------------
 * Drivers: the time laws at t, before every evaluation
 * ------------------------------------------------------------------------ */

/* f, f', f'' of every driver at t and, for a rotation driver,
 * e(t) = cos f d0 + sin f d1 (into u), e' = f' (-sin f d0 + cos f d1) and
 * e'' = f'' (-sin f d0 + cos f d1) - f'^2 e. */
static int EvalDrivers(struct LGNJointsRec *J, sunrealtype t, const char *func)
{
  int k, i, ret;
  if (J->ndrivers == 0) return LGN_SUCCESS;
  if (!isfinite(t)) {
    JErr(J, LGN_ILL_INPUT, func, "t = %g illegal: the drivers need a finite time.", (double)t);
    return LGN_ILL_INPUT;
  }
  for (k = 0; k < J->nprim; k++) {
    Primitive *p = J->prim + k;
    sunrealtype c, s, e1[3];
    if (p->drive == NULL) continue;
    p->f[0] = p->f[1] = p->f[2] = SUN_RCONST(0.0);
    ret = p->drive(t, p->f, p->drive_data);
    if (ret != 0 || !isfinite(p->f[0]) || !isfinite(p->f[1]) || !isfinite(p->f[2])) {
      JErr(J, LGN_CONSTR_FAIL, func,
           "the time law of driver (joint %d) failed at t = %g: it returned %d, "
           "f = (%g, %g, %g).", p->joint, (double)t, ret, (double)p->f[0],
           (double)p->f[1], (double)p->f[2]);
      return LGN_CONSTR_FAIL;
    }
    if (p->kind != PRIM_PERP) continue;
    c = cos(p->f[0]);
    s = sin(p->f[0]);
    for (i = 0; i < 3; i++) {
      p->u[i]   = c * p->d0[i] + s * p->d1[i];
      e1[i]     = -s * p->d0[i] + c * p->d1[i];
      p->ud[i]  = p->f[1] * e1[i];
      p->udd[i] = p->f[2] * e1[i] - p->f[1] * p->f[1] * p->u[i];
    }
  }
  return LGN_SUCCESS;
}

/* ---------------------------------------------------------------------------
 * Construction
 * ------------------------------------------------------------------------ */

/* A new joint set reports to stderr (its sink's default) until the user
 * sets a handler or stream; so do its failures, which have no set yet. */
LGNJoints LGNJoints_Create(LGNGroup G)
{
  struct LGNJointsRec *J;
  size_t k;
  int nb;
  if (G == NULL) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__, "G = NULL illegal.");
    return NULL;
  }
  J = (struct LGNJointsRec *)calloc(1, sizeof *J);
  if (J == NULL) {
    lgnReport(NULL, LGN_MEM_FAIL, __func__, MSG_MEM_FAIL);
    return NULL;
  }
  lgnErrSinkInit(&J->err);
  J->G = G;
  nb   = lgnGroupPlanarBodies(G, NULL, NULL, NULL);
  if (nb > 0) { /* planar bodies (lignum_planar.h) */
    J->nb     = nb;
    J->planar = lgnPlanarJointsCreate(G, &J->err, __func__);
    if (J->planar == NULL) {
      free(J);
      return NULL;
    }
    return J;
  }
  nb = lgnGroupRigidBodies(G, NULL, NULL, NULL);
  if (nb < 1) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__,
              "G: the joint helpers need bodies on R^3 x SO(3) or SE(3), or "
              "planar ones on SE(2) or R^2 x SO(2) (or a product of them).");
    free(J);
    return NULL;
  }
  J->nb   = nb;
  J->qoff = (sunindextype *)malloc((size_t)nb * sizeof *J->qoff);
  J->voff = (sunindextype *)malloc((size_t)nb * sizeof *J->voff);
  J->se3  = (sunbooleantype *)malloc((size_t)nb * sizeof *J->se3);
  J->injoint  = (sunbooleantype *)calloc((size_t)nb, sizeof *J->injoint);
  J->online   = (sunbooleantype *)calloc((size_t)nb, sizeof *J->online);
  J->rot      = (sunrealtype *)malloc((size_t)nb * ROT_STRIDE * sizeof *J->rot);
  J->bfmt     = NO_PATTERN;
  if (J->qoff == NULL || J->voff == NULL || J->se3 == NULL || J->injoint == NULL ||
      J->online == NULL || J->rot == NULL) {
    LGNJoints_Destroy(&J);
    lgnReport(NULL, LGN_MEM_FAIL, __func__, MSG_MEM_FAIL);
    return NULL;
  }
  lgnGroupRigidBodies(G, J->qoff, J->voff, J->se3);
  for (k = 0; k < (size_t)nb * ROT_STRIDE; k++) J->rot[k] = NAN;
  return J;
}

static void FreeJacobianPattern(struct LGNJointsRec *J)
{
  free(J->bptr);
  free(J->bind);
  free(J->bpos);
  J->bptr = J->bind = J->bpos = NULL;
  J->bfmt = NO_PATTERN;
}

static void FreeStiffnessStructure(struct LGNJointsRec *J)
{
  free(J->kptr);
  free(J->kbody);
  free(J->kblk);
  J->kptr = J->kbody = NULL;
  J->kblk = NULL;
}

void LGNJoints_Destroy(LGNJoints *Jp)
{
  struct LGNJointsRec *J;
  if (Jp == NULL || *Jp == NULL) return;
  J = *Jp;
  lgnPlanarJointsDestroy(J->planar);
  FreeJacobianPattern(J);
  FreeStiffnessStructure(J);
  if (J->work != NULL) SUNMatDestroy(J->work);
  free(J->qoff);
  free(J->voff);
  free(J->se3);
  free(J->injoint);
  free(J->online);
  free(J->rot);
  free(J->prim);
  free(J);
  *Jp = NULL;
}

/* The joint set's own handler, as LGNSetErrHandlerFn for the integrator. */
int LGNJoints_SetErrHandlerFn(LGNJoints J, LGNErrHandlerFn ehfun, void *eh_data)
{
  if (J == NULL) return NullJoints(__func__);
  J->err.ehfun   = ehfun;
  J->err.eh_data = eh_data;
  return LGN_SUCCESS;
}

/* The stream of its default handler, as LGNSetErrFile. */
int LGNJoints_SetErrFile(LGNJoints J, FILE *errfp)
{
  if (J == NULL) return NullJoints(__func__);
  J->err.errfp = errfp;
  return LGN_SUCCESS;
}

int LGNJoints_NumBodies(LGNJoints J) { return J != NULL ? J->nb : 0; }

sunindextype LGNJoints_NumConstraints(LGNJoints J)
{
  if (J != NULL && J->planar != NULL) return lgnPlanarJointsNumConstraints(J->planar);
  return J != NULL ? J->m : 0;
}

/* The planar part (lgn_planar.h) and the sink, for lgn_planar_api.c. */
lgnPlanarJoints *lgnJointsPlanarPart(LGNJoints J) { return J != NULL ? J->planar : NULL; }
const LGNErrSink *lgnJointsSink(LGNJoints J) { return J != NULL ? &J->err : NULL; }

/* A spatial joint on a planar set (lignum_planar.h). */
static int RefusePlanar(const struct LGNJointsRec *J, const char *func)
{
  JErr(J, LGN_ILL_INPUT, func,
       "J is a planar joint set (SE(2) or R^2 x SO(2) bodies): use the planar "
       "joints of lignum_planar.h.");
  return LGN_ILL_INPUT;
}

/* The bodies a, b of a joint added by the public function func. */
static int CheckBodies(const struct LGNJointsRec *J, int a, int b, const char *func)
{
  if (a < LGN_GROUND || a >= J->nb || b < LGN_GROUND || b >= J->nb || a == b) {
    JErr(J, LGN_ILL_INPUT, func,
         "bodies a = %d, b = %d illegal (0..%d or LGN_GROUND, a != b).",
         a, b, J->nb - 1);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

/* Label the primitives from first on as joint number J->njoints of kind
 * kind (after an Add* call succeeded). */
static void EndJoint(struct LGNJointsRec *J, int first, const char *kind)
{
  int k;
  for (k = first; k < J->nprim; k++) {
    J->prim[k].joint = J->njoints;
    J->prim[k].jkind = kind;
  }
  J->njoints++;
}

/* Append a primitive for the public function func. */
static int AddPrimitive(struct LGNJointsRec *J, PrimKind kind, int a,
                        const sunrealtype *u, int b, const sunrealtype *w,
                        const char *func)
{
  Primitive *p;
  if (J->nprim == J->cap) {
    int cap = J->cap > 0 ? 2 * J->cap : 16;
    Primitive *np = (Primitive *)realloc(J->prim, (size_t)cap * sizeof *np);
    if (np == NULL) {
      JErr(J, LGN_MEM_FAIL, func, MSG_MEM_FAIL);
      return LGN_MEM_FAIL;
    }
    J->prim = np;
    J->cap  = cap;
  }
  p       = J->prim + J->nprim++;
  memset(p, 0, sizeof *p);
  p->kind = kind;
  p->a    = a;
  p->b    = b;
  memcpy(p->u, u, sizeof p->u);
  memcpy(p->w, w, sizeof p->w);
  p->row   = J->m;
  J->m    += kind == PRIM_POINT ? 3 : 1;
  /* per body in B: 3 rows x 6 columns (POINT at an SE(3) body), 3 rows x
   * (1 + 3) columns (POINT at an R^3 x SO(3) body, whose translation part
   * is +-I), 1 row x 3 columns (PERP) */
  if (a != LGN_GROUND)
    J->nnzB += kind == PRIM_PERP ? 3 : kind == PRIM_LINE ? 6 : (J->se3[a] ? 18 : 12);
  if (b != LGN_GROUND)
    J->nnzB += kind == PRIM_PERP ? 3 : kind == PRIM_LINE ? 6 : (J->se3[b] ? 18 : 12);
  if (kind == PRIM_LINE) {
    if (a != LGN_GROUND) J->online[a] = SUNTRUE;
    if (b != LGN_GROUND) J->online[b] = SUNTRUE;
  }
  if (a != LGN_GROUND) J->injoint[a] = SUNTRUE;
  if (b != LGN_GROUND) J->injoint[b] = SUNTRUE;
  FreeJacobianPattern(J);    /* the pattern of B changed */
  FreeStiffnessStructure(J); /* the coupling changed */
  return LGN_SUCCESS;
}

int LGNJoints_AddSpherical(LGNJoints J, int a, const sunrealtype sa[3], int b,
                           const sunrealtype sb[3])
{
  int flag;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return RefusePlanar(J, __func__);
  flag = CheckBodies(J, a, b, __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, sa, "sa", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, sb, "sb", __func__);
  if (flag == LGN_SUCCESS) flag = AddPrimitive(J, PRIM_POINT, a, sa, b, sb, __func__);
  if (flag == LGN_SUCCESS) EndJoint(J, J->nprim - 1, "spherical");
  return flag;
}

/* y = x / |x| for the axis (named name) given to the public function func. */
static int Normalised(const struct LGNJointsRec *J, const sunrealtype *x,
                      sunrealtype *y, const char *name, const char *func)
{
  sunrealtype n = sqrt(lgnVec3Dot(x, x));
  if (!(n > SUN_RCONST(0.0)) || !isfinite(n)) {
    JErr(J, LGN_ILL_INPUT, func, "%s is zero or not finite.", name);
    return LGN_ILL_INPUT;
  }
  y[0] = x[0] / n;
  y[1] = x[1] / n;
  y[2] = x[2] / n;
  return LGN_SUCCESS;
}

/* Bodies, points and axes of a revolute or universal joint (func). */
static int CheckJointArgs(const struct LGNJointsRec *J, int a,
                          const sunrealtype *sa, const sunrealtype *axis_a, int b,
                          const sunrealtype *sb, const sunrealtype *axis_b,
                          const char *func)
{
  int flag = CheckBodies(J, a, b, func);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, sa, "sa", func);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, axis_a, "axis_a", func);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, sb, "sb", func);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, axis_b, "axis_b", func);
  return flag;
}

int LGNJoints_AddRevolute(LGNJoints J, int a, const sunrealtype sa[3],
                          const sunrealtype axis_a[3], int b,
                          const sunrealtype sb[3], const sunrealtype axis_b[3])
{
  sunrealtype n[3], c[3], e1[3], e2[3], t[3];
  int flag, first;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL)
    return lgnPlanarJointsAddRevolute3(J->planar, a, sa, axis_a, b, sb, axis_b, __func__);
  flag = CheckJointArgs(J, a, sa, axis_a, b, sb, axis_b, __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_a, n, "axis_a", __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_b, c, "axis_b", __func__);
  if (flag != LGN_SUCCESS) return flag;
  /* e1, e2: an orthonormal pair perpendicular to axis_a */
  t[0] = t[1] = t[2] = SUN_RCONST(0.0);
  t[fabs(n[0]) < SUN_RCONST(0.6) ? 0 : (fabs(n[1]) < SUN_RCONST(0.6) ? 1 : 2)] = SUN_RCONST(1.0);
  lgnVec3Cross(n, t, e1);
  Normalised(J, e1, e1, "e1", __func__); /* |n x t| >= 0.8: cannot fail */
  lgnVec3Cross(n, e1, e2);
  first = J->nprim;
  flag = AddPrimitive(J, PRIM_POINT, a, sa, b, sb, __func__);
  if (flag == LGN_SUCCESS) flag = AddPrimitive(J, PRIM_PERP, a, e1, b, c, __func__);
  if (flag == LGN_SUCCESS) flag = AddPrimitive(J, PRIM_PERP, a, e2, b, c, __func__);
  if (flag == LGN_SUCCESS) EndJoint(J, first, "revolute");
  return flag;
}

int LGNJoints_AddUniversal(LGNJoints J, int a, const sunrealtype sa[3],
                           const sunrealtype axis_a[3], int b,
                           const sunrealtype sb[3], const sunrealtype axis_b[3])
{
  sunrealtype e[3], c[3];
  int flag, first;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return RefusePlanar(J, __func__);
  flag = CheckJointArgs(J, a, sa, axis_a, b, sb, axis_b, __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_a, e, "axis_a", __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_b, c, "axis_b", __func__);
  first = J->nprim;
  if (flag == LGN_SUCCESS) flag = AddPrimitive(J, PRIM_POINT, a, sa, b, sb, __func__);
  if (flag == LGN_SUCCESS) flag = AddPrimitive(J, PRIM_PERP, a, e, b, c, __func__);
  if (flag == LGN_SUCCESS) EndJoint(J, first, "universal");
  return flag;
}

/* An orthonormal pair e1, e2 perpendicular to the unit vector n (the rule
 * of the revolute joint). */
static void PerpPair(const sunrealtype *n, sunrealtype *e1, sunrealtype *e2)
{
  sunrealtype t[3] = {0, 0, 0}, l;
  t[fabs(n[0]) < SUN_RCONST(0.6) ? 0 : (fabs(n[1]) < SUN_RCONST(0.6) ? 1 : 2)] = SUN_RCONST(1.0);
  lgnVec3Cross(n, t, e1);
  l = sqrt(lgnVec3Dot(e1, e1)); /* |n x t| >= 0.8 */
  e1[0] /= l;
  e1[1] /= l;
  e1[2] /= l;
  lgnVec3Cross(n, e1, e2);
}

/* Append a LINE primitive: (R_a e) . (p_b - p_a). */
static int AddLine(struct LGNJointsRec *J, int a, const sunrealtype *sa,
                   const sunrealtype *e, int b, const sunrealtype *sb, const char *func)
{
  int flag = AddPrimitive(J, PRIM_LINE, a, sa, b, sb, func);
  if (flag == LGN_SUCCESS) memcpy(J->prim[J->nprim - 1].e, e, 3 * sizeof(sunrealtype));
  return flag;
}

/* The part of ref perpendicular to the unit vector n, normalised (named
 * name for the public function func). */
static int PerpendicularPart(const struct LGNJointsRec *J, const sunrealtype *n,
                             const sunrealtype *ref, sunrealtype *r,
                             const char *name, const char *func)
{
  const sunrealtype along = lgnVec3Dot(ref, n), len = sqrt(lgnVec3Dot(ref, ref));
  int i;
  for (i = 0; i < 3; i++) r[i] = ref[i] - along * n[i];
  if (!(sqrt(lgnVec3Dot(r, r)) > SUN_RCONST(1e-6) * len)) {
    JErr(J, LGN_ILL_INPUT, func, "%s is zero or parallel to the axis.", name);
    return LGN_ILL_INPUT;
  }
  return Normalised(J, r, r, name, func);
}

/* The five rows of a prismatic joint locked at R_a^T R_b = R0 (row-major),
 * with c = axis_b and d1, d2 an orthonormal pair perpendicular to it (body
 * b): (R_a R0 d1).(R_b c), (R_a R0 d2).(R_b c), (R_a R0 d1).(R_b d2), and sb
 * on the line through sa along R0 c: (R_a R0 d_i).(p_b - p_a), i = 1, 2. */
static int AddPrismaticRows(struct LGNJointsRec *J, int a, const sunrealtype *sa,
                            int b, const sunrealtype *sb, const sunrealtype *c,
                            const sunrealtype *d1, const sunrealtype *d2,
                            const sunrealtype *R0, const char *func)
{
  sunrealtype e1[3], e2[3];
  int flag, first = J->nprim;
  lgnMat3Apply(R0, d1, e1);
  lgnMat3Apply(R0, d2, e2);
  flag = AddPrimitive(J, PRIM_PERP, a, e1, b, c, func);
  if (flag == LGN_SUCCESS) flag = AddPrimitive(J, PRIM_PERP, a, e2, b, c, func);
  if (flag == LGN_SUCCESS) flag = AddPrimitive(J, PRIM_PERP, a, e1, b, d2, func);
  if (flag == LGN_SUCCESS) flag = AddLine(J, a, sa, e1, b, sb, func);
  if (flag == LGN_SUCCESS) flag = AddLine(J, a, sa, e2, b, sb, func);
  if (flag == LGN_SUCCESS) EndJoint(J, first, "prismatic");
  return flag;
}

int LGNJoints_AddPrismatic(LGNJoints J, int a, const sunrealtype sa[3],
                           const sunrealtype axis_a[3], int b,
                           const sunrealtype sb[3], const sunrealtype axis_b[3])
{
  sunrealtype n[3], c[3], d1[3], d2[3], k[3], R0[9], cs;
  int flag, i, j;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return RefusePlanar(J, __func__);
  flag = CheckJointArgs(J, a, sa, axis_a, b, sb, axis_b, __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_a, n, "axis_a", __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_b, c, "axis_b", __func__);
  if (flag != LGN_SUCCESS) return flag;
  /* R0: the smallest rotation taking c to n (row-major), Rodrigues with
   * k = c x n: R0 = I + k~ + k~^2 / (1 + c.n) */
  PerpPair(c, d1, d2);
  cs = lgnVec3Dot(c, n);
  lgnVec3Cross(c, n, k);
  if (cs > SUN_RCONST(-1.0) + SUN_RCONST(1e-8)) {
    sunrealtype K[9], K2[9];
    K[0] = 0;     K[1] = -k[2]; K[2] = k[1];
    K[3] = k[2];  K[4] = 0;     K[5] = -k[0];
    K[6] = -k[1]; K[7] = k[0];  K[8] = 0;
    for (i = 0; i < 3; i++)
      for (j = 0; j < 3; j++)
        K2[3 * i + j] = K[3 * i] * K[j] + K[3 * i + 1] * K[3 + j] + K[3 * i + 2] * K[6 + j];
    for (i = 0; i < 9; i++) R0[i] = K[i] + K2[i] / (SUN_RCONST(1.0) + cs);
    R0[0] += SUN_RCONST(1.0);
    R0[4] += SUN_RCONST(1.0);
    R0[8] += SUN_RCONST(1.0);
  } else { /* antiparallel: half a turn about d1 */
    for (i = 0; i < 3; i++)
      for (j = 0; j < 3; j++)
        R0[3 * i + j] = SUN_RCONST(2.0) * d1[i] * d1[j] - (i == j ? SUN_RCONST(1.0) : SUN_RCONST(0.0));
  }
  return AddPrismaticRows(J, a, sa, b, sb, c, d1, d2, R0, __func__);
}

int LGNJoints_AddPrismaticFrames(LGNJoints J, int a, const sunrealtype sa[3],
                                 const sunrealtype axis_a[3],
                                 const sunrealtype ref_a[3], int b,
                                 const sunrealtype sb[3],
                                 const sunrealtype axis_b[3],
                                 const sunrealtype ref_b[3])
{
  sunrealtype n[3], ra[3], na[3], c[3], rb[3], nb[3], R0[9];
  int flag, i, j;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return RefusePlanar(J, __func__);
  flag = CheckJointArgs(J, a, sa, axis_a, b, sb, axis_b, __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, ref_a, "ref_a", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, ref_b, "ref_b", __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_a, n, "axis_a", __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_b, c, "axis_b", __func__);
  if (flag == LGN_SUCCESS) flag = PerpendicularPart(J, n, ref_a, ra, "ref_a", __func__);
  if (flag == LGN_SUCCESS) flag = PerpendicularPart(J, c, ref_b, rb, "ref_b", __func__);
  if (flag != LGN_SUCCESS) return flag;
  /* R0 = F_a F_b^T with the frames F = [axis, ref, axis x ref] (columns):
   * R0 c = n and R0 rb = ra */
  lgnVec3Cross(n, ra, na);
  lgnVec3Cross(c, rb, nb);
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) R0[3 * i + j] = n[i] * c[j] + ra[i] * rb[j] + na[i] * nb[j];
  return AddPrismaticRows(J, a, sa, b, sb, c, rb, nb, R0, __func__);
}

int LGNJoints_AddCylindrical(LGNJoints J, int a, const sunrealtype sa[3],
                             const sunrealtype axis_a[3], int b,
                             const sunrealtype sb[3], const sunrealtype axis_b[3])
{
  sunrealtype n[3], c[3], e1[3], e2[3];
  int flag, first;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return RefusePlanar(J, __func__);
  flag = CheckJointArgs(J, a, sa, axis_a, b, sb, axis_b, __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_a, n, "axis_a", __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_b, c, "axis_b", __func__);
  if (flag != LGN_SUCCESS) return flag;
  PerpPair(n, e1, e2);
  first = J->nprim;
  flag = AddPrimitive(J, PRIM_PERP, a, e1, b, c, __func__);
  if (flag == LGN_SUCCESS) flag = AddPrimitive(J, PRIM_PERP, a, e2, b, c, __func__);
  if (flag == LGN_SUCCESS) flag = AddLine(J, a, sa, e1, b, sb, __func__);
  if (flag == LGN_SUCCESS) flag = AddLine(J, a, sa, e2, b, sb, __func__);
  if (flag == LGN_SUCCESS) EndJoint(J, first, "cylindrical");
  return flag;
}

int LGNJoints_AddRotationDriver(LGNJoints J, int a, const sunrealtype axis_a[3],
                                const sunrealtype ref_a[3], int b,
                                const sunrealtype ref_b[3], LGNDriveFn f,
                                void *drive_data)
{
  sunrealtype n[3], r[3], c[3], nr[3];
  int flag, i;
  Primitive *p;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return RefusePlanar(J, __func__);
  flag = CheckBodies(J, a, b, __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, axis_a, "axis_a", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, ref_a, "ref_a", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, ref_b, "ref_b", __func__);
  if (flag == LGN_SUCCESS && f == NULL) {
    JErr(J, LGN_ILL_INPUT, __func__, "f = NULL illegal: the driver needs a time law.");
    flag = LGN_ILL_INPUT;
  }
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_a, n, "axis_a", __func__);
  if (flag == LGN_SUCCESS) flag = PerpendicularPart(J, n, ref_a, r, "ref_a", __func__);
  if (flag == LGN_SUCCESS) flag = Normalised(J, ref_b, c, "ref_b", __func__);
  if (flag != LGN_SUCCESS) return flag;
  /* Phi = (R_a e(t)) . (R_b c) with e(t) = cos f (n x r) - sin f r: with
   * R_b c = R_a (cos theta r + sin theta n x r), Phi = sin(theta - f) */
  lgnVec3Cross(n, r, nr);
  flag = AddPrimitive(J, PRIM_PERP, a, nr, b, c, __func__);
  if (flag != LGN_SUCCESS) return flag;
  p = J->prim + J->nprim - 1;
  for (i = 0; i < 3; i++) {
    p->d0[i] = nr[i];
    p->d1[i] = -r[i];
  }
  p->drive      = f;
  p->drive_data = drive_data;
  EndJoint(J, J->nprim - 1, "rotation driver");
  J->ndrivers++;
  return LGN_SUCCESS;
}

int LGNJoints_AddTranslationDriver(LGNJoints J, int a, const sunrealtype sa[3],
                                   const sunrealtype axis_a[3], int b,
                                   const sunrealtype sb[3], LGNDriveFn f,
                                   void *drive_data)
{
  sunrealtype n[3];
  int flag;
  Primitive *p;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return RefusePlanar(J, __func__);
  flag = CheckJointArgs(J, a, sa, axis_a, b, sb, axis_a, __func__);
  if (flag == LGN_SUCCESS && f == NULL) {
    JErr(J, LGN_ILL_INPUT, __func__, "f = NULL illegal: the driver needs a time law.");
    flag = LGN_ILL_INPUT;
  }
  if (flag == LGN_SUCCESS) flag = Normalised(J, axis_a, n, "axis_a", __func__);
  if (flag == LGN_SUCCESS) flag = AddLine(J, a, sa, n, b, sb, __func__);
  if (flag != LGN_SUCCESS) return flag;
  p             = J->prim + J->nprim - 1;
  p->drive      = f;
  p->drive_data = drive_data;
  EndJoint(J, J->nprim - 1, "translation driver");
  J->ndrivers++;
  return LGN_SUCCESS;
}

int LGNJoints_NumDrivers(LGNJoints J)
{
  if (J != NULL && J->planar != NULL) return lgnPlanarJointsNumDrivers(J->planar);
  return J != NULL ? J->ndrivers : 0;
}

int LGNJoints_DescribeConstraint(LGNJoints J, sunindextype row, char *buf,
                                 size_t len)
{
  int k, first = -1, last = -1, joint;
  sunindextype r0, r1;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return lgnPlanarJointsDescribe(J->planar, row, buf, len, __func__);
  if (buf == NULL || len == 0) {
    JErr(J, LGN_ILL_INPUT, __func__, "buf = NULL or len = 0 illegal.");
    return LGN_ILL_INPUT;
  }
  if (row < 0 || row >= J->m) {
    JErr(J, LGN_ILL_INPUT, __func__, "row = %lld illegal: the joints have %lld rows.",
         (long long)row, (long long)J->m);
    return LGN_ILL_INPUT;
  }
  for (k = 0; k < J->nprim; k++)
    if (J->prim[k].row <= row) first = k; /* rows increase with k */
  joint = J->prim[first].joint;
  for (k = 0; k < J->nprim; k++) {
    if (J->prim[k].joint != joint) continue;
    if (last < 0) first = k;
    last = k;
  }
  r0 = J->prim[first].row;
  r1 = J->prim[last].row + (J->prim[last].kind == PRIM_POINT ? 3 : 1);
  {
    const Primitive *p = J->prim + first;
    char ba[24], bb[24];
    if (p->a == LGN_GROUND) snprintf(ba, sizeof ba, "the ground");
    else snprintf(ba, sizeof ba, "body %d", p->a);
    if (p->b == LGN_GROUND) snprintf(bb, sizeof bb, "the ground");
    else snprintf(bb, sizeof bb, "body %d", p->b);
    if (p->drive != NULL)
      snprintf(buf, len, "%s (joint %d: %s - %s), its constraint 1 of 1", p->jkind, joint,
               ba, bb);
    else
      snprintf(buf, len, "%s joint %d (%s - %s), its constraint %lld of %lld", p->jkind,
               joint, ba, bb, (long long)(row - r0 + 1), (long long)(r1 - r0));
  }
  return LGN_SUCCESS;
}

/* ---------------------------------------------------------------------------
 * Evaluation
 * ------------------------------------------------------------------------ */

/* The geometry of a LINE primitive: r = R_a e, d = p_b - p_a, rho =
 * R_a^T (p_b - x_a), y = R_b^T r, and its rows of B at a and b
 * (translation, rotation): ga = (-(P_a^T r), e x rho), gb = (P_b^T r,
 * s_b x y). */
typedef struct {
  sunrealtype r[3], d[3], rho[3], y[3];
  sunrealtype ga[6], gb[6];
} LineGeom;

static void LineGeometry(const Pose *A, const Pose *B, const Primitive *p, LineGeom *L)
{
  sunrealtype ya[3], yb[3], t[3];
  int i;
  lgnMat3Apply(A->R, p->e, L->r);
  lgnMat3Apply(A->R, p->u, ya);
  lgnMat3Apply(B->R, p->w, yb);
  for (i = 0; i < 3; i++) {
    L->d[i] = B->x[i] + yb[i] - A->x[i] - ya[i];
    t[i]    = B->x[i] + yb[i] - A->x[i];
  }
  lgnMat3ApplyT(A->R, t, L->rho);
  lgnMat3ApplyT(B->R, L->r, L->y);
  for (i = 0; i < 3; i++) {
    L->ga[i] = -(A->se3 ? p->e[i] : L->r[i]);
    L->gb[i] = B->se3 ? L->y[i] : L->r[i];
  }
  lgnVec3Cross(p->e, L->rho, L->ga + 3);
  lgnVec3Cross(p->w, L->y, L->gb + 3);
}

int LGNJoints_Residual(LGNJoints J, sunrealtype t, N_Vector q, N_Vector phi)
{
  const sunrealtype *qd;
  sunrealtype *f, ya[3], yb[3];
  Pose A, B;
  int k, i, flag;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return lgnPlanarJointsResidual(J->planar, t, q, phi, __func__);
  flag = lgnCheckSerialVector(&J->err, q, J->G->nq, "q", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckSerialVector(&J->err, phi, J->m, "phi", __func__);
  if (flag == LGN_SUCCESS) flag = EvalDrivers(J, t, __func__);
  if (flag != LGN_SUCCESS) return flag;
  qd = lgnVecData(q);
  f  = lgnVecData(phi);
  FillRotations(J, qd);
  for (k = 0; k < J->nprim; k++) {
    const Primitive *p = J->prim + k;
    GetPose(J, p->a, qd, NULL, &A);
    GetPose(J, p->b, qd, NULL, &B);
    lgnMat3Apply(A.R, p->u, ya);
    lgnMat3Apply(B.R, p->w, yb);
    if (p->kind == PRIM_POINT)
      for (i = 0; i < 3; i++) f[p->row + i] = A.x[i] + ya[i] - B.x[i] - yb[i];
    else if (p->kind == PRIM_LINE) {
      LineGeom L;
      LineGeometry(&A, &B, p, &L);
      f[p->row] = lgnVec3Dot(L.r, L.d) - p->f[0]; /* f = 0 unless driven */
    } else
      f[p->row] = lgnVec3Dot(ya, yb);
  }
  return LGN_SUCCESS;
}

/* ---------------------------------------------------------------------------
 * Jacobian B(q)
 *
 * One generator, JacobianEntries, puts the entries of B in a fixed order
 * into a Sink: once to record their rows and columns, from which the sparse
 * pattern and each entry's position in the data are built and kept; then
 * at every call to write the values, straight to their positions in a
 * sparse B or to a dense B.
 * ------------------------------------------------------------------------ */

typedef enum {
  SINK_PATTERN, /* record row and column of each entry */
  SINK_VALUES,  /* value of entry n to val[pos[n]]     */
  SINK_DENSE    /* value to B(row, column)             */
} SinkKind;

typedef struct {
  SinkKind kind;
  sunindextype n;          /* entries put so far                      */
  sunindextype *row, *col; /* SINK_PATTERN                            */
  sunrealtype *val;        /* SINK_VALUES: data of the sparse B       */
  const sunindextype *pos;
  SUNMatrix B;             /* SINK_DENSE                              */
} Sink;

/* Put the entries (r, c + j) = x[j], j < len. */
static void PutRow(Sink *s, sunindextype r, sunindextype c, const sunrealtype *x,
                   int len)
{
  const sunindextype n = s->n;
  int j;
  switch (s->kind) {
  case SINK_VALUES:
    for (j = 0; j < len; j++) s->val[s->pos[n + j]] = x[j];
    break;
  case SINK_DENSE:
    for (j = 0; j < len; j++) SM_ELEMENT_D(s->B, r, c + j) = x[j];
    break;
  case SINK_PATTERN:
    for (j = 0; j < len; j++) {
      s->row[n + j] = r;
      s->col[n + j] = c + j;
    }
    break;
  }
  s->n = n + len;
}

/* The 3 x 6 block of a POINT primitive's rows at one body, row-major:
 * sign [P, -R s~] (sign = 1 for body a, -1 for body b). (R s~)_ij is the
 * sum over k of R_ik (s~)_kj in the order of Mul3, zero terms included, so
 * that the rounding is that of the product. */
static void PointBlock(const Pose *P, const sunrealtype *s, sunrealtype sign,
                       sunrealtype *blk)
{
  sunrealtype sk[9];
  int i, j;
  Skew(s, sk);
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) {
      const sunrealtype *r = P->R + 3 * i, *c = sk + 3 * j;
      blk[6 * i + j] = sign * (P->se3 ? r[j] : (i == j ? SUN_RCONST(1.0) : SUN_RCONST(0.0)));
      blk[6 * i + 3 + j] = (r[0] * c[0] + r[1] * c[1] + r[2] * c[2]) * -sign;
    }
}

/* The 1 x 3 rotation parts of a PERP primitive: (e x R_a^T R_b c)^T at
 * body a, (c x R_b^T R_a e)^T at body b. */
static void PerpRows(const Pose *A, const Pose *B, const sunrealtype *e,
                     const sunrealtype *c, sunrealtype g[2][3])
{
  sunrealtype t1[3], t2[3];
  lgnMat3Apply(B->R, c, t1);
  lgnMat3ApplyT(A->R, t1, t2);
  lgnVec3Cross(e, t2, g[0]);
  lgnMat3Apply(A->R, e, t1);
  lgnMat3ApplyT(B->R, t1, t2);
  lgnVec3Cross(c, t2, g[1]);
}

/* The entries of B (rotations from FillRotations) in generation order:
 * primitives in order, so rows ascending, and columns ascending within each
 * row. LGNJointsRec.nnzB of them. */
static void JacobianEntries(const struct LGNJointsRec *J, const sunrealtype *qd,
                            Sink *s)
{
  int k, i, side;
  for (k = 0; k < J->nprim; k++) {
    const Primitive *p = J->prim + k;
    Pose P[2];
    int order[2];
    GetPose(J, p->a, qd, NULL, &P[0]);
    GetPose(J, p->b, qd, NULL, &P[1]);
    /* the body with the smaller column offset first */
    order[0] = (P[1].voff >= 0 && (P[0].voff < 0 || P[1].voff < P[0].voff)) ? 1 : 0;
    order[1] = 1 - order[0];
    if (p->kind == PRIM_POINT) {
      sunrealtype blk[2][18];
      for (side = 0; side < 2; side++)
        if (!P[side].ground)
          PointBlock(&P[side], side == 0 ? p->u : p->w,
                     side == 0 ? SUN_RCONST(1.0) : SUN_RCONST(-1.0), blk[side]);
      for (i = 0; i < 3; i++)
        for (side = 0; side < 2; side++) {
          const int o = order[side];
          if (P[o].ground) continue;
          if (P[o].se3 || s->kind == SINK_DENSE) {
            PutRow(s, p->row + i, P[o].voff, blk[o] + 6 * i, 6);
          } else { /* R^3 x SO(3): the translation part is +-I */
            PutRow(s, p->row + i, P[o].voff + i, blk[o] + 7 * i, 1);
            PutRow(s, p->row + i, P[o].voff + 3, blk[o] + 6 * i + 3, 3);
          }
        }
    } else if (p->kind == PRIM_LINE) {
      LineGeom L;
      LineGeometry(&P[0], &P[1], p, &L);
      for (side = 0; side < 2; side++) {
        const int o = order[side];
        if (!P[o].ground) PutRow(s, p->row, P[o].voff, o == 0 ? L.ga : L.gb, 6);
      }
    } else {
      sunrealtype g[2][3];
      PerpRows(&P[0], &P[1], p->u, p->w, g);
      for (side = 0; side < 2; side++) {
        const int o = order[side];
        if (!P[o].ground) PutRow(s, p->row, P[o].voff + 3, g[o], 3);
      }
    }
  }
}

/* Compress nnz entries (key, other) into n lists by key: ptr (n + 1), ind
 * and, for entry k, its position pos[k]. A stable counting sort, so the
 * entries of each list keep their order. next: n scratch. */
static void CountingSort(sunindextype nnz, const sunindextype *key,
                         const sunindextype *other, sunindextype n,
                         sunindextype *ptr, sunindextype *ind,
                         sunindextype *pos, sunindextype *next)
{
  sunindextype k;
  memset(ptr, 0, (size_t)(n + 1) * sizeof *ptr);
  for (k = 0; k < nnz; k++) ptr[key[k] + 1]++;
  for (k = 0; k < n; k++) ptr[k + 1] += ptr[k];
  memcpy(next, ptr, (size_t)n * sizeof *next);
  for (k = 0; k < nnz; k++) {
    const sunindextype d = next[key[k]]++;
    ind[d] = other[k];
    pos[k] = d;
  }
}

/* Build and keep the pattern of the sparse B in format fmt (CSC_MAT: by
 * column, rows ascending; CSR_MAT: by row, columns ascending) and the
 * positions of the generated entries. Needs the rotations (the values are
 * generated along, unused). */
static int BuildJacobianPattern(struct LGNJointsRec *J, const sunrealtype *qd, int fmt)
{
  const sunindextype nnz = J->nnzB, n = fmt == CSC_MAT ? J->G->nv : J->m;
  const size_t len = (size_t)(nnz > 0 ? nnz : 1) * sizeof(sunindextype);
  Sink s = {SINK_PATTERN, 0, NULL, NULL, NULL, NULL, NULL};
  sunindextype *next;
  FreeJacobianPattern(J);
  J->bptr = (sunindextype *)malloc((size_t)(n + 1) * sizeof(sunindextype));
  J->bind = (sunindextype *)malloc(len);
  J->bpos = (sunindextype *)malloc(len);
  s.row   = (sunindextype *)malloc(len);
  s.col   = (sunindextype *)malloc(len);
  next    = (sunindextype *)malloc((size_t)(n + 1) * sizeof(sunindextype));
  if (J->bptr != NULL && J->bind != NULL && J->bpos != NULL && s.row != NULL &&
      s.col != NULL && next != NULL) {
    JacobianEntries(J, qd, &s);
    if (fmt == CSC_MAT) CountingSort(nnz, s.col, s.row, n, J->bptr, J->bind, J->bpos, next);
    else CountingSort(nnz, s.row, s.col, n, J->bptr, J->bind, J->bpos, next);
    J->bfmt = fmt;
  }
  free(s.row);
  free(s.col);
  free(next);
  if (J->bfmt != fmt) {
    FreeJacobianPattern(J);
    return LGN_MEM_FAIL;
  }
  return LGN_SUCCESS;
}

/* Sparse B: the kept pattern, copied in whole (the caller may have cleared
 * B, as Lignum does before an LGNConstrJacFn), and the values written
 * straight to their positions. */
static int SparseJacobian(struct LGNJointsRec *J, const sunrealtype *qd, SUNMatrix B,
                          const char *func)
{
  const int fmt = SUNSparseMatrix_SparseType(B);
  const sunindextype n = fmt == CSC_MAT ? J->G->nv : J->m;
  Sink s = {SINK_VALUES, 0, NULL, NULL, NULL, NULL, NULL};
  if ((J->bfmt != fmt && BuildJacobianPattern(J, qd, fmt) != LGN_SUCCESS) ||
      (SUNSparseMatrix_NNZ(B) < J->nnzB && SUNSparseMatrix_Reallocate(B, J->nnzB) != 0)) {
    JErr(J, LGN_MEM_FAIL, func, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  memcpy(SUNSparseMatrix_IndexPointers(B), J->bptr, (size_t)(n + 1) * sizeof *J->bptr);
  memcpy(SUNSparseMatrix_IndexValues(B), J->bind, (size_t)J->nnzB * sizeof *J->bind);
  s.val = SUNSparseMatrix_Data(B);
  s.pos = J->bpos;
  JacobianEntries(J, qd, &s);
  return LGN_SUCCESS;
}

sunindextype LGNJoints_JacobianNnz(LGNJoints J)
{
  if (J != NULL && J->planar != NULL) return lgnPlanarJointsJacobianNnz(J->planar);
  return J != NULL ? J->nnzB : 0;
}

int LGNJoints_Jacobian(LGNJoints J, sunrealtype t, N_Vector q, SUNMatrix B)
{
  const sunindextype nv = J != NULL ? J->G->nv : 0;
  const sunrealtype *qd;
  int flag;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return lgnPlanarJointsJacobian(J->planar, t, q, B, __func__);
  flag = lgnCheckSerialVector(&J->err, q, J->G->nq, "q", __func__);
  if (flag != LGN_SUCCESS) return flag;
  if (B == NULL ||
      (lgnMatID(B) == SUNMATRIX_DENSE &&
       (SM_ROWS_D(B) != J->m || SM_COLUMNS_D(B) != nv)) ||
      (lgnMatIsSparse(B) &&
       (SUNSparseMatrix_Rows(B) != J->m || SUNSparseMatrix_Columns(B) != nv)) ||
      (lgnMatID(B) != SUNMATRIX_DENSE && lgnMatID(B) != SUNMATRIX_SPARSE)) {
    JErr(J, LGN_ILL_INPUT, __func__, "B must be a dense or sparse %lld x %lld matrix.",
         (long long)J->m, (long long)nv);
    return LGN_ILL_INPUT;
  }
  flag = EvalDrivers(J, t, __func__);
  if (flag != LGN_SUCCESS) return flag;
  qd = lgnVecData(q);
  FillRotations(J, qd);
  if (lgnMatID(B) == SUNMATRIX_DENSE) {
    Sink s = {SINK_DENSE, 0, NULL, NULL, NULL, NULL, NULL};
    s.B = B;
    JacobianEntries(J, qd, &s);
    return LGN_SUCCESS;
  }
  return SparseJacobian(J, qd, B, __func__);
}

/* ---------------------------------------------------------------------------
 * Constraint forces B(q)^T lambda, from the blocks of B transposed, with
 * l the primitive's multipliers and, at a body with point s, sign = 1 for
 * body a and -1 for body b:
 *   POINT:  translation += sign P^T l,
 *           rotation    += (-sign R s~)^T l = sign s x (R^T l);
 *   PERP:   rotation    += l g (g of PerpRows).
 * ------------------------------------------------------------------------ */

int LGNJoints_ConstraintForce(LGNJoints J, sunrealtype t, N_Vector q, N_Vector lambda,
                              N_Vector f)
{
  const sunrealtype *qd, *ld;
  sunrealtype *fd, mu[3], sxmu[3], g[2][3];
  Pose P[2];
  int k, i, side, flag;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL)
    return lgnPlanarJointsConstraintForce(J->planar, t, q, lambda, f, __func__);
  flag = lgnCheckSerialVector(&J->err, q, J->G->nq, "q", __func__);
  /* no joints: lambda has no entries (and may have no data) */
  if (flag == LGN_SUCCESS && J->m > 0) flag = lgnCheckSerialVector(&J->err, lambda, J->m, "lambda", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckSerialVector(&J->err, f, J->G->nv, "f", __func__);
  if (flag == LGN_SUCCESS) flag = EvalDrivers(J, t, __func__);
  if (flag != LGN_SUCCESS) return flag;
  fd = lgnVecData(f);
  memset(fd, 0, (size_t)J->G->nv * sizeof(sunrealtype)); /* the data checked above */
  if (J->m == 0) return LGN_SUCCESS;
  qd = lgnVecData(q);
  ld = lgnVecData(lambda);
  FillRotations(J, qd);
  for (k = 0; k < J->nprim; k++) {
    const Primitive *p = J->prim + k;
    const sunrealtype *l = ld + p->row;
    GetPose(J, p->a, qd, NULL, &P[0]);
    GetPose(J, p->b, qd, NULL, &P[1]);
    if (p->kind == PRIM_PERP) PerpRows(&P[0], &P[1], p->u, p->w, g);
    if (p->kind == PRIM_LINE) {
      LineGeom L;
      LineGeometry(&P[0], &P[1], p, &L);
      for (side = 0; side < 2; side++) {
        const sunrealtype *gr = side == 0 ? L.ga : L.gb;
        if (P[side].ground) continue;
        for (i = 0; i < 6; i++) fd[P[side].voff + i] += l[0] * gr[i];
      }
      continue;
    }
    for (side = 0; side < 2; side++) {
      const sunrealtype sign = side == 0 ? SUN_RCONST(1.0) : SUN_RCONST(-1.0);
      sunrealtype *fb;
      if (P[side].ground) continue;
      fb = fd + P[side].voff;
      if (p->kind == PRIM_PERP) {
        for (i = 0; i < 3; i++) fb[3 + i] += l[0] * g[side][i];
        continue;
      }
      lgnMat3ApplyT(P[side].R, l, mu);
      lgnVec3Cross(side == 0 ? p->u : p->w, mu, sxmu);
      for (i = 0; i < 3; i++) {
        fb[i]     += sign * (P[side].se3 ? mu[i] : l[i]);
        fb[3 + i] += sign * sxmu[i];
      }
    }
  }
  return LGN_SUCCESS;
}

/* Second time derivative of R y along constant body velocities:
 * d/dt (R y) = R (Omega x y), d2/dt2 = R (Omega x (Omega x y)). */
static void Accel(const Pose *P, const sunrealtype *y, sunrealtype *out)
{
  sunrealtype t1[3], t2[3];
  if (P->ground) {
    out[0] = out[1] = out[2] = SUN_RCONST(0.0);
    return;
  }
  lgnVec3Cross(P->v + 3, y, t1);
  lgnVec3Cross(P->v + 3, t1, t2);
  lgnMat3Apply(P->R, t2, out);
}

/* Velocity and acceleration of the point x + R s along constant body
 * velocities: xdot = u or R U, pdot = xdot + R (Omega x s), pddot =
 * R (Omega x (Omega x s)) + [SE(3)] R (Omega x U). Zero at the ground. */
static void PointMotion(const Pose *P, const sunrealtype *s, sunrealtype *pd,
                        sunrealtype *pdd)
{
  sunrealtype t1[3], t2[3];
  int i;
  if (P->ground) {
    for (i = 0; i < 3; i++) pd[i] = pdd[i] = SUN_RCONST(0.0);
    return;
  }
  lgnVec3Cross(P->v + 3, s, t1);
  lgnMat3Apply(P->R, t1, pd);
  if (P->se3) {
    lgnMat3Apply(P->R, P->v, t2);
    for (i = 0; i < 3; i++) pd[i] += t2[i];
  } else
    for (i = 0; i < 3; i++) pd[i] += P->v[i];
  Accel(P, s, pdd);
  if (P->se3) {
    lgnVec3Cross(P->v + 3, P->v, t1);
    lgnMat3Apply(P->R, t1, t2);
    for (i = 0; i < 3; i++) pdd[i] += t2[i];
  }
}

/* (r . d)'' = r'' . d + 2 r' . d' + r . d'' of a LINE primitive. */
static sunrealtype LineCurvature(const Pose *A, const Pose *B, const Primitive *p)
{
  LineGeom L;
  sunrealtype rd[3], rdd[3], pa[3], paa[3], pb[3], pbb[3], dd[3], ddd[3], t[3];
  int i;
  LineGeometry(A, B, p, &L);
  for (i = 0; i < 3; i++) rd[i] = rdd[i] = SUN_RCONST(0.0);
  if (!A->ground) { /* r = R_a e turns with a */
    lgnVec3Cross(A->v + 3, p->e, t);
    lgnMat3Apply(A->R, t, rd);
    Accel(A, p->e, rdd);
  }
  PointMotion(A, p->u, pa, paa);
  PointMotion(B, p->w, pb, pbb);
  for (i = 0; i < 3; i++) {
    dd[i]  = pb[i] - pa[i];
    ddd[i] = pbb[i] - paa[i];
  }
  return lgnVec3Dot(rdd, L.d) + SUN_RCONST(2.0) * lgnVec3Dot(rd, dd) + lgnVec3Dot(L.r, ddd);
}

int LGNJoints_Curvature(LGNJoints J, sunrealtype t, N_Vector q, N_Vector v, N_Vector z)
{
  const sunrealtype *qd, *vd;
  sunrealtype *zd, aa[3], ab[3], t1[3], t2[3], ra[3], rb[3], da[3], db[3];
  Pose A, B;
  int k, i, flag;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return lgnPlanarJointsCurvature(J->planar, t, q, v, z, __func__);
  flag = lgnCheckSerialVector(&J->err, q, J->G->nq, "q", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckSerialVector(&J->err, v, J->G->nv, "v", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckSerialVector(&J->err, z, J->m, "z", __func__);
  if (flag == LGN_SUCCESS) flag = EvalDrivers(J, t, __func__);
  if (flag != LGN_SUCCESS) return flag;
  qd = lgnVecData(q);
  vd = lgnVecData(v);
  zd = lgnVecData(z);
  FillRotations(J, qd);
  for (k = 0; k < J->nprim; k++) {
    const Primitive *p = J->prim + k;
    GetPose(J, p->a, qd, vd, &A);
    GetPose(J, p->b, qd, vd, &B);
    if (p->kind == PRIM_LINE) {
      zd[p->row] = LineCurvature(&A, &B, p) - p->f[2]; /* f'' = 0 unless driven */
      continue;
    }
    Accel(&A, p->u, aa);
    Accel(&B, p->w, ab);
    if (p->kind == PRIM_POINT) {
      /* SE(3): xdot = R U, so x'' = R (Omega x U) at constant (U, Omega) */
      if (A.se3) {
        lgnVec3Cross(A.v + 3, A.v, t1);
        lgnMat3Apply(A.R, t1, t2);
        for (i = 0; i < 3; i++) aa[i] += t2[i];
      }
      if (B.se3) {
        lgnVec3Cross(B.v + 3, B.v, t1);
        lgnMat3Apply(B.R, t1, t2);
        for (i = 0; i < 3; i++) ab[i] += t2[i];
      }
      for (i = 0; i < 3; i++) zd[p->row + i] = aa[i] - ab[i];
    } else {
      /* (ra . rb)'' = ra'' . rb + 2 ra' . rb' + ra . rb'' */
      lgnMat3Apply(A.R, p->u, ra);
      lgnMat3Apply(B.R, p->w, rb);
      da[0] = da[1] = da[2] = db[0] = db[1] = db[2] = SUN_RCONST(0.0);
      if (!A.ground) {
        lgnVec3Cross(A.v + 3, p->u, t1);
        lgnMat3Apply(A.R, t1, da);
      }
      if (!B.ground) {
        lgnVec3Cross(B.v + 3, p->w, t1);
        lgnMat3Apply(B.R, t1, db);
      }
      if (p->drive != NULL) {
        /* e = e(t) turns in a's frame: ra' += R_a e',
         * ra'' += 2 R_a (Omega_a x e') + R_a e'' */
        lgnMat3Apply(A.R, p->ud, t2);
        for (i = 0; i < 3; i++) da[i] += t2[i];
        lgnMat3Apply(A.R, p->udd, t2);
        for (i = 0; i < 3; i++) aa[i] += t2[i];
        if (!A.ground) {
          lgnVec3Cross(A.v + 3, p->ud, t1);
          lgnMat3Apply(A.R, t1, t2);
          for (i = 0; i < 3; i++) aa[i] += SUN_RCONST(2.0) * t2[i];
        }
      }
      zd[p->row] = lgnVec3Dot(aa, rb) + SUN_RCONST(2.0) * lgnVec3Dot(da, db) + lgnVec3Dot(ra, ab);
    }
  }
  return LGN_SUCCESS;
}

/* Phi_t: -f' for a translation driver, (R_a e'(t)) . (R_b c) for a
 * rotation driver, 0 elsewhere. */
int LGNJoints_TimeDerivative(LGNJoints J, sunrealtype t, N_Vector q, N_Vector phit)
{
  const sunrealtype *qd;
  sunrealtype *pd, ra[3], rb[3];
  Pose A, B;
  int k, flag;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return lgnPlanarJointsTimeDerivative(J->planar, t, q, phit, __func__);
  flag = lgnCheckSerialVector(&J->err, q, J->G->nq, "q", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckSerialVector(&J->err, phit, J->m, "phit", __func__);
  if (flag == LGN_SUCCESS) flag = EvalDrivers(J, t, __func__);
  if (flag != LGN_SUCCESS) return flag;
  pd = lgnVecData(phit);
  if (J->m > 0) memset(pd, 0, (size_t)J->m * sizeof(sunrealtype));
  if (J->ndrivers == 0) return LGN_SUCCESS;
  qd = lgnVecData(q);
  FillRotations(J, qd);
  for (k = 0; k < J->nprim; k++) {
    const Primitive *p = J->prim + k;
    if (p->drive == NULL) continue;
    if (p->kind == PRIM_LINE) {
      pd[p->row] = -p->f[1];
      continue;
    }
    GetPose(J, p->a, qd, NULL, &A);
    GetPose(J, p->b, qd, NULL, &B);
    lgnMat3Apply(A.R, p->ud, ra);
    lgnMat3Apply(B.R, p->w, rb);
    pd[p->row] = lgnVec3Dot(ra, rb);
  }
  return LGN_SUCCESS;
}

/* ---------------------------------------------------------------------------
 * Geometric stiffness d/dq (B^T lambda)
 * ------------------------------------------------------------------------ */

static int CompareInt(const void *x, const void *y)
{
  return *(const int *)x - *(const int *)y;
}

/* Per body, the sorted bodies it is coupled with (itself included). */
static int BuildStiffnessStructure(struct LGNJointsRec *J)
{
  int k, b, *cnt = (int *)calloc((size_t)J->nb + 1, sizeof(int));
  if (cnt == NULL) return LGN_MEM_FAIL;
  for (k = 0; k < J->nprim; k++) {
    const Primitive *p = J->prim + k;
    if (p->kind != PRIM_POINT && p->a != LGN_GROUND && p->b != LGN_GROUND) {
      cnt[p->a]++;
      cnt[p->b]++;
    }
  }
  J->kptr = (int *)malloc((size_t)(J->nb + 1) * sizeof(int));
  if (J->kptr == NULL) {
    free(cnt);
    return LGN_MEM_FAIL;
  }
  J->kptr[0] = 0;
  for (b = 0; b < J->nb; b++) J->kptr[b + 1] = J->kptr[b] + cnt[b] + 1;
  J->kbody = (int *)malloc((size_t)J->kptr[J->nb] * sizeof(int));
  J->kblk  = (sunrealtype *)malloc((size_t)J->kptr[J->nb] * 36 * sizeof(sunrealtype));
  if (J->kbody == NULL || J->kblk == NULL) {
    free(cnt);
    FreeStiffnessStructure(J);
    return LGN_MEM_FAIL;
  }
  for (b = 0; b < J->nb; b++) {
    J->kbody[J->kptr[b]] = b;
    cnt[b] = 1;
  }
  for (k = 0; k < J->nprim; k++) {
    const Primitive *p = J->prim + k;
    if (p->kind != PRIM_POINT && p->a != LGN_GROUND && p->b != LGN_GROUND) {
      J->kbody[J->kptr[p->a] + cnt[p->a]++] = p->b;
      J->kbody[J->kptr[p->b] + cnt[p->b]++] = p->a;
    }
  }
  /* sort and drop duplicates (a revolute couples the same pair twice) */
  for (b = 0; b < J->nb; b++) {
    int *list = J->kbody + J->kptr[b], len = J->kptr[b + 1] - J->kptr[b], u = 0, i;
    qsort(list, (size_t)len, sizeof(int), CompareInt);
    for (i = 0; i < len; i++)
      if (u == 0 || list[i] != list[u - 1]) list[u++] = list[i];
    for (i = u; i < len; i++) list[i] = -2; /* unused slots */
  }
  free(cnt);
  return LGN_SUCCESS;
}

/* The 6x6 block (row body r, column body c), column-major. */
static sunrealtype *Block(struct LGNJointsRec *J, int r, int c)
{
  int i;
  for (i = J->kptr[c]; i < J->kptr[c + 1]; i++)
    if (J->kbody[i] == r) return J->kblk + 36 * (size_t)i;
  return NULL;
}

/* Add the 3x3 X (column-major) times f at (row offset ro, col offset co) of
 * the 6x6 block. */
static void AddSub(sunrealtype *blk, int ro, int co, const sunrealtype *X,
                   sunrealtype f)
{
  int i, j;
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++) blk[(ro + i) + 6 * (co + j)] += f * X[i + 3 * j];
}

/* X = R (column-major) of a row-major rotation R; its transpose R^T in
 * column-major is the row-major array itself. */
static void ColMajor(const sunrealtype *Rrow, sunrealtype *X)
{
  int i, j;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) X[i + 3 * j] = Rrow[3 * i + j];
}

/* Geometric stiffness of a LINE primitive with multiplier l (column-major
 * 3x3 blocks, t: translation, r: rotation; P_b's type decides):
 *   (a_t, a_r)  R^3 x SO(3): l R_a e~            SE(3): 0
 *   (a_r, a_t)  R^3 x SO(3): -l e~ R_a^T         SE(3): -l e~
 *   (a_r, a_r)  l e~ rho~
 *   (a_r, b_t)  l e~ R_a^T P_b
 *   (a_r, b_r)  -l e~ R_a^T R_b s_b~
 *   (b_t, a_r)  -l P_b^T R_a e~
 *   (b_t, b_r)  R^3 x SO(3): 0                   SE(3): l y~
 *   (b_r, a_r)  -l s_b~ R_b^T R_a e~
 *   (b_r, b_r)  l s_b~ y~ */
static void LineStiffness(struct LGNJointsRec *J, const Primitive *p, const Pose *A,
                          const Pose *B, sunrealtype l)
{
  LineGeom L;
  sunrealtype E[9], Ra[9], RaT[9], Rb[9], RbT[9], X[9], Y[9], Z[9], W[9], Sb[9], Pb[9];
  const int a = p->a, b = p->b;
  int i;
  LineGeometry(A, B, p, &L);
  Skew(p->e, E);
  ColMajor(A->R, Ra);
  memcpy(RaT, A->R, sizeof RaT);
  ColMajor(B->R, Rb);
  memcpy(RbT, B->R, sizeof RbT);
  Skew(p->w, Sb);
  /* P_b (column-major) */
  if (B->se3) memcpy(Pb, Rb, sizeof Pb);
  else
    for (i = 0; i < 9; i++) Pb[i] = (i % 4 == 0) ? SUN_RCONST(1.0) : SUN_RCONST(0.0);
  if (a != LGN_GROUND) {
    sunrealtype *aa = Block(J, a, a);
    if (!A->se3) {
      Mul3(Ra, E, X);
      AddSub(aa, 0, 3, X, l);
      Mul3(E, RaT, X);
      AddSub(aa, 3, 0, X, -l);
    } else
      AddSub(aa, 3, 0, E, -l);
    Skew(L.rho, Y);
    Mul3(E, Y, X);
    AddSub(aa, 3, 3, X, l);
    if (b != LGN_GROUND) {
      sunrealtype *ab = Block(J, a, b);
      Mul3(E, RaT, X);  /* e~ R_a^T */
      Mul3(X, Pb, Y);
      AddSub(ab, 3, 0, Y, l);
      Mul3(X, Rb, Y);
      Mul3(Y, Sb, Z);
      AddSub(ab, 3, 3, Z, -l);
    }
  }
  if (b != LGN_GROUND) {
    sunrealtype *bb = Block(J, b, b);
    Skew(L.y, Y);
    if (B->se3) AddSub(bb, 0, 3, Y, l);
    Mul3(Sb, Y, X);
    AddSub(bb, 3, 3, X, l);
    if (a != LGN_GROUND) {
      sunrealtype *ba = Block(J, b, a), PbT[9];
      int r, c;
      for (r = 0; r < 3; r++)
        for (c = 0; c < 3; c++) PbT[r + 3 * c] = Pb[c + 3 * r];
      Mul3(Ra, E, X);   /* R_a e~ */
      Mul3(PbT, X, Y);
      AddSub(ba, 0, 3, Y, -l);
      Mul3(RbT, X, W);  /* R_b^T R_a e~ */
      Mul3(Sb, W, Z);
      AddSub(ba, 3, 3, Z, -l);
    }
  }
}

/* Geometric stiffness of one primitive into the blocks. With mu = R^T l:
 *   POINT, body a: K_{th,th} += s_a~ mu_a~ (SE(3): K_{x,th} += mu_a~), body
 *          b with the opposite sign;
 *   PERP:  K_{a,a} += l e~ w~ (w = R_a^T R_b c), K_{a,b} -= l e~ R_ab c~,
 *          K_{b,b} += l c~ y~ (y = R_b^T R_a e), K_{b,a} -= l c~ R_ba e~. */
static void PrimitiveStiffness(struct LGNJointsRec *J, const Primitive *p,
                               const sunrealtype *qd, const sunrealtype *l)
{
  Pose P[2];
  sunrealtype X[9], Y[9], Z[9], mu[3], t[3], Rab[9];
  int side, i, j;
  GetPose(J, p->a, qd, NULL, &P[0]);
  GetPose(J, p->b, qd, NULL, &P[1]);
  if (p->kind == PRIM_LINE) {
    LineStiffness(J, p, &P[0], &P[1], l[0]);
    return;
  }
  if (p->kind == PRIM_POINT) {
    for (side = 0; side < 2; side++) {
      const int body = side == 0 ? p->a : p->b;
      const sunrealtype sign = side == 0 ? SUN_RCONST(1.0) : SUN_RCONST(-1.0);
      sunrealtype *blk;
      if (body == LGN_GROUND) continue;
      blk = Block(J, body, body);
      lgnMat3ApplyT(P[side].R, l, mu);
      Skew(side == 0 ? p->u : p->w, X);
      Skew(mu, Y);
      Mul3(X, Y, Z);
      AddSub(blk, 3, 3, Z, sign);
      if (P[side].se3) AddSub(blk, 0, 3, Y, sign);
    }
    return;
  }
  for (side = 0; side < 2; side++) {
    const int me = side == 0 ? p->a : p->b, other = side == 0 ? p->b : p->a;
    const sunrealtype *e = side == 0 ? p->u : p->w, *c = side == 0 ? p->w : p->u;
    const Pose *Pm = &P[side], *Po = &P[1 - side];
    if (me == LGN_GROUND) continue;
    /* w = R_me^T R_other c */
    lgnMat3Apply(Po->R, c, t);
    lgnMat3ApplyT(Pm->R, t, mu);
    Skew(e, X);
    Skew(mu, Y);
    Mul3(X, Y, Z);
    AddSub(Block(J, me, me), 3, 3, Z, l[0]);
    if (other == LGN_GROUND) continue;
    /* R_me^T R_other (column-major) times c~ */
    for (j = 0; j < 3; j++)
      for (i = 0; i < 3; i++)
        Rab[i + 3 * j] = Pm->R[i] * Po->R[j] + Pm->R[3 + i] * Po->R[3 + j] +
                         Pm->R[6 + i] * Po->R[6 + j];
    Skew(c, Y);
    Mul3(Rab, Y, Z);
    Mul3(X, Z, Y);
    AddSub(Block(J, me, other), 3, 3, Y, -l[0]);
  }
}

/* The first row of block (row body r, column body c) in the sparse K. Only
 * the rotation columns 3..5 of a block are nonzero (B^T lambda does not
 * depend on the translations), and only its rows 3..5, except in an SE(3)
 * body's own block, where the point rows' R^T lambda adds rows 0..2. */
static int StiffnessFirstRow(const struct LGNJointsRec *J, int r, int c)
{
  if (J->online[r] || J->online[c]) return 0; /* full blocks: see below */
  return r == c && J->se3[r] ? 0 : 3;
}

/* The first column of the block: 3, or 0 (all of the 6 x 6 block stored)
 * when either body is in a point-on-line constraint (prismatic,
 * cylindrical), whose B^T lambda depends on the translations. */
static int StiffnessFirstCol(const struct LGNJointsRec *J, int r, int c)
{
  return J->online[r] || J->online[c] ? 0 : 3;
}

sunindextype LGNJoints_StiffnessNnz(LGNJoints J)
{
  if (J == NULL) return 0;
  if (J->planar != NULL) return lgnPlanarJointsStiffnessNnz(J->planar);
  if (J->kptr == NULL && BuildStiffnessStructure(J) != LGN_SUCCESS) return 0;
  {
    sunindextype n = 0;
    int b, i;
    for (b = 0; b < J->nb; b++)
      for (i = J->kptr[b]; i < J->kptr[b + 1] && J->kbody[i] >= 0; i++)
        n += (6 - StiffnessFirstCol(J, J->kbody[i], b)) * (6 - StiffnessFirstRow(J, J->kbody[i], b));
    return n;
  }
}

static int WriteSparseStiffness(struct LGNJointsRec *J, SUNMatrix K, const char *func);

int LGNJoints_Stiffness(LGNJoints J, sunrealtype t, N_Vector q, N_Vector lambda,
                        SUNMatrix K)
{
  const sunrealtype *qd, *ld;
  sunindextype nv;
  int k, b, i, r, c, flag;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return lgnPlanarJointsStiffness(J->planar, t, q, lambda, K, __func__);
  nv = J->G->nv;
  if (lgnCheckSerialVector(&J->err, q, J->G->nq, "q", __func__) != LGN_SUCCESS ||
      (J->m > 0 && lgnCheckSerialVector(&J->err, lambda, J->m, "lambda", __func__) != LGN_SUCCESS))
    return LGN_ILL_INPUT;
  if (K == NULL ||
      (lgnMatID(K) == SUNMATRIX_DENSE && (SM_ROWS_D(K) != nv || SM_COLUMNS_D(K) != nv)) ||
      (lgnMatIsSparse(K) &&
       (SUNSparseMatrix_Rows(K) != nv || SUNSparseMatrix_Columns(K) != nv)) ||
      (lgnMatID(K) != SUNMATRIX_DENSE && lgnMatID(K) != SUNMATRIX_SPARSE)) {
    JErr(J, LGN_ILL_INPUT, __func__, "K must be a dense or sparse %lld x %lld matrix.",
         (long long)nv, (long long)nv);
    return LGN_ILL_INPUT;
  }
  if (J->kptr == NULL && BuildStiffnessStructure(J) != LGN_SUCCESS) {
    JErr(J, LGN_MEM_FAIL, __func__, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  if (J->m == 0) return LGN_SUCCESS;
  flag = EvalDrivers(J, t, __func__);
  if (flag != LGN_SUCCESS) return flag;
  qd = lgnVecData(q);
  ld = lgnVecData(lambda);
  FillRotations(J, qd);
  memset(J->kblk, 0, (size_t)J->kptr[J->nb] * 36 * sizeof(sunrealtype));
  for (k = 0; k < J->nprim; k++) PrimitiveStiffness(J, J->prim + k, qd, ld + J->prim[k].row);

  if (lgnMatID(K) == SUNMATRIX_DENSE) {
    for (b = 0; b < J->nb; b++)
      for (i = J->kptr[b]; i < J->kptr[b + 1] && J->kbody[i] >= 0; i++)
        for (c = 0; c < 6; c++)
          for (r = 0; r < 6; r++)
            SM_ELEMENT_D(K, J->voff[J->kbody[i]] + r, J->voff[b] + c) +=
                J->kblk[36 * (size_t)i + r + 6 * c];
    return LGN_SUCCESS;
  }
  if (lgnMatIsEmpty(K)) return WriteSparseStiffness(J, K, __func__);
  /* K holds entries: add through the work matrix (lignum_bodies.h,
   * "Matrices": the same rule as for a dense K) */
  if (lgnSparseWorkLike(&J->work, K) == NULL) {
    JErr(J, LGN_MEM_FAIL, __func__, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  flag = WriteSparseStiffness(J, J->work, __func__);
  if (flag == LGN_SUCCESS && lgnSparseAdd(K, J->work) != LGN_SUCCESS) {
    JErr(J, LGN_MEM_FAIL, __func__, MSG_MEM_FAIL);
    flag = LGN_MEM_FAIL;
  }
  return flag;
}

/* Overwrite the sparse K with the blocks kblk and their pattern. */
static int WriteSparseStiffness(struct LGNJointsRec *J, SUNMatrix K, const char *func)
{
  const sunindextype nnz = LGNJoints_StiffnessNnz(J);
  sunindextype pos = 0;
  int b, i, r, c;
  if (SUNSparseMatrix_NNZ(K) < nnz && SUNSparseMatrix_Reallocate(K, nnz) != 0) {
    JErr(J, LGN_MEM_FAIL, func, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  {
    /* the block structure is symmetric: CSC column c of body b lists the
     * coupled bodies' rows; CSR row c of body b lists their columns, with
     * the transposed block values. Bodies are in offset order, so sorted.
     * Within a block, the pattern of StiffnessFirstRow. */
    const sunbooleantype csc = SUNSparseMatrix_SparseType(K) == CSC_MAT;
    sunindextype *ptr = SUNSparseMatrix_IndexPointers(K);
    sunindextype *ind = SUNSparseMatrix_IndexValues(K);
    sunrealtype *val  = SUNSparseMatrix_Data(K);
    ptr[0] = 0;
    for (b = 0; b < J->nb; b++)
      for (c = 0; c < 6; c++) {
        for (i = J->kptr[b]; i < J->kptr[b + 1] && J->kbody[i] >= 0; i++) {
          const int o = J->kbody[i];
          const sunrealtype *blk_bo = J->kblk + 36 * (size_t)i; /* (row o, col b) */
          const sunrealtype *blk_ob = Block(J, b, o);           /* (row b, col o) */
          const int r0 = csc ? StiffnessFirstRow(J, o, b) : StiffnessFirstCol(J, b, o);
          if (csc ? c < StiffnessFirstCol(J, o, b) : c < StiffnessFirstRow(J, b, o)) continue;
          for (r = r0; r < 6; r++) {
            ind[pos] = J->voff[o] + r;
            val[pos] = csc ? blk_bo[r + 6 * c] : blk_ob[c + 6 * r];
            pos++;
          }
        }
        ptr[J->voff[b] + c + 1] = pos;
      }
  }
  return LGN_SUCCESS;
}

/* ---------------------------------------------------------------------------
 * Contact of a body's point with a plane (LGNApplyImpact's rows)
 * ------------------------------------------------------------------------ */

/* gap = n . (x + R s) - d and its row along q o exp(w): d x = P w_x,
 * d (R s) = R (w_theta x s), so G = [n^T P, (s x R^T n)^T] at the body's
 * six velocities (P = I on R^3 x SO(3), R on SE(3)). */
int LGNJoints_PointPlaneContact(LGNJoints J, N_Vector q, int b, const sunrealtype s[3],
                                const sunrealtype n[3], sunrealtype d, sunrealtype *gap,
                                sunrealtype *row)
{
  const sunrealtype *qd, *x;
  sunrealtype R[9], Rs[3], Rtn[3], g[3];
  sunindextype i;
  int flag;
  if (J == NULL) return NullJoints(__func__);
  if (J->planar != NULL) return RefusePlanar(J, __func__);
  if (b < 0 || b >= J->nb) {
    JErr(J, LGN_ILL_INPUT, __func__, "body b = %d illegal (0..%d).", b, J->nb - 1);
    return LGN_ILL_INPUT;
  }
  if (gap == NULL || row == NULL) {
    JErr(J, LGN_ILL_INPUT, __func__, "%s = NULL illegal.", gap == NULL ? "gap" : "row");
    return LGN_ILL_INPUT;
  }
  flag = lgnCheckVec3(&J->err, s, "s", __func__);
  if (flag == LGN_SUCCESS) flag = lgnCheckVec3(&J->err, n, "n", __func__);
  if (flag != LGN_SUCCESS) return flag;
  if (!(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > SUN_RCONST(0.0)) || !isfinite(d)) {
    JErr(J, LGN_ILL_INPUT, __func__, "n = 0 or d not finite: illegal.");
    return LGN_ILL_INPUT;
  }
  if (lgnCheckSerialVector(&J->err, q, J->G->nq, "q", __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  qd = lgnVecData(q);
  x  = qd + J->qoff[b];
  LGNQuaternionToRotation(x + 3, R);
  lgnMat3Apply(R, s, Rs);
  lgnMat3ApplyT(R, n, Rtn);
  *gap = n[0] * (x[0] + Rs[0]) + n[1] * (x[1] + Rs[1]) + n[2] * (x[2] + Rs[2]) - d;
  for (i = 0; i < J->G->nv; i++) row[i] = SUN_RCONST(0.0);
  if (J->se3[b]) lgnMat3ApplyT(R, n, g); /* P = R: (R^T n)^T */
  else
    for (i = 0; i < 3; i++) g[i] = n[i];
  for (i = 0; i < 3; i++) row[J->voff[b] + i] = g[i];
  lgnVec3Cross(s, Rtn, g);
  for (i = 0; i < 3; i++) row[J->voff[b] + 3 + i] = g[i];
  return LGN_SUCCESS;
}

LGNGroup lgnJointsGroup(LGNJoints J) { return J != NULL ? J->G : NULL; }
