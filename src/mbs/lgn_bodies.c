/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Rigid bodies and force elements (include/lignum/lignum_bodies.h).
 *
 * A point p = x + R s of a body moves, along q o exp(w), by dp = H w with
 *   H = [P, -R s~],  P = I (R^3 x SO(3)) or R (SE(3)),
 * and with the body velocity v, pdot = H v. An inertial force F at p does
 * the work of the generalised force H^T F = (P^T F, s x R^T F). For fixed F,
 * d/dq (H^T F) has the blocks (rot, rot) s~ mu~ and, on SE(3), (trans, rot)
 * mu~ (mu = R^T F); and d/dq (H v) = [0, -R (Omega x s + [SE(3)] U)~].
 *
 * Translational spring-damper: Delta = p_b - p_a, D = dDelta/dw =
 * [-H_a, H_b], F = f n the force on a; g += D^T F (minus the applied
 * forces: a is pulled by +F, b by -F), so
 *   C_t += c D^T n n^T D,
 *   K_t += D^T (G D + c n n^T E) + the fixed-F terms above (sign -1 at a),
 * with E = d(D v)/dq and G = dF/dDelta at fixed Deltadot:
 *   G = k n n^T + (f / L)(I - n n^T) + (c / L) n ((I - n n^T) Deltadot)^T.
 *
 * Rotational spring-damper: theta = log(R_a^T R_b); along R_b exp(w_b),
 * dtheta = T(theta)^-1 w_b, along R_a exp(w_a), dtheta = -T^-1 Rrel^T w_a
 * (Rrel = R_a^T R_b; Rrel theta = theta), and g_b = k theta + c (Omega_b -
 * Rrel^T Omega_a), g_a = -k theta - c (Rrel Omega_b - Omega_a). A rest
 * rotation R0 (theta = log(R0^T R_a^T R_b)) is the same element on the
 * frame a' = R_a R0 of body a: R_a exp(w_a) R0 = R_a R0 exp((R0^T w_a)~), so
 * Omega_a' = R0^T Omega_a, and a's rows of g, K_t, C_t are R0 times those
 * of a' (its columns times R0^T).
 *
 * A pure helper layer like the joints: no integrator memory, its own sink.
 * ---------------------------------------------------------------------------*/

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum_bodies.h>
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
#error "lgn_bodies.c is a pure helper: it must not see the integrator's memory record"
#endif

typedef enum { ELEM_SPRING = 0, ELEM_ROTSPRING = 1 } ElemKind;

typedef struct {
  ElemKind kind;
  int a, b;
  sunrealtype sa[3], sb[3];
  sunrealtype k, c, L0;
  sunbooleantype rest;  /* rotational: a rest rotation R0 (else identity) */
  sunrealtype p0[4], R0[9];
} Element;

struct LGNBodiesRec {
  LGNErrSink err;
  LGNGroup G;
  int nb;
  int first_ghost;       /* bodies from here on are ghosts (nb: none)  */
  sunindextype *qoff, *voff;
  sunbooleantype *se3;
  sunrealtype *mass;     /* nb          */
  sunrealtype *inertia;  /* 9 per body, row-major */
  sunrealtype gravity[3];
  Element *elem;
  int nelem, cap;
  /* block structure of K_t and C_t: per column body, the sorted row
   * bodies (itself included), and 36 values per block (row-major) */
  int *kptr, *kbody;
  sunrealtype *kblk;
  lgnPlanarBodies *planar; /* a planar set (lgn_planar_bodies.c), which
                              answers every call itself; else NULL        */
  SUNMatrix work;        /* sparse terms added to a matrix with entries */
};

#define MSG_MEM_FAIL "A memory request failed."

#if defined(__GNUC__) || defined(__clang__)
#define BERR_FORMAT __attribute__((format(printf, 4, 5)))
#else
#define BERR_FORMAT
#endif

static void BErr(const struct LGNBodiesRec *B, int code, const char *func,
                 const char *msgfmt, ...) BERR_FORMAT;
static void BErr(const struct LGNBodiesRec *B, int code, const char *func,
                 const char *msgfmt, ...)
{
  va_list ap;
  va_start(ap, msgfmt);
  lgnReportV(&B->err, code, func, msgfmt, ap);
  va_end(ap);
}

static int NullBodies(const char *func)
{
  lgnReport(NULL, LGN_ILL_INPUT, func, "B = NULL illegal.");
  return LGN_ILL_INPUT;
}

/* ---------------------------------------------------------------------------
 * 3-vector and 3x3 (row-major) kernels
 * ------------------------------------------------------------------------ */

/* C = A B, C = A^T B (3x3 row-major); C may not alias. */
static void MM(const sunrealtype *A, const sunrealtype *Bm, sunrealtype *C)
{
  int i, j;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++)
      C[3 * i + j] = A[3 * i] * Bm[j] + A[3 * i + 1] * Bm[3 + j] + A[3 * i + 2] * Bm[6 + j];
}

static void MTM(const sunrealtype *A, const sunrealtype *Bm, sunrealtype *C)
{
  int i, j;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++)
      C[3 * i + j] = A[i] * Bm[j] + A[3 + i] * Bm[3 + j] + A[6 + i] * Bm[6 + j];
}

/* ---------------------------------------------------------------------------
 * Construction
 * ------------------------------------------------------------------------ */

LGNBodies LGNBodies_Create(LGNGroup G)
{
  struct LGNBodiesRec *B;
  int nb, k;
  if (G == NULL) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__, "G = NULL illegal.");
    return NULL;
  }
  B = (struct LGNBodiesRec *)calloc(1, sizeof *B);
  if (B == NULL) {
    lgnReport(NULL, LGN_MEM_FAIL, __func__, MSG_MEM_FAIL);
    return NULL;
  }
  lgnErrSinkInit(&B->err);
  B->G = G;
  nb   = lgnGroupPlanarBodies(G, NULL, NULL, NULL);
  if (nb > 0) { /* planar bodies (lignum_planar.h) */
    B->nb          = nb;
    B->first_ghost = nb;
    B->planar      = lgnPlanarBodiesCreate(G, &B->err, __func__);
    if (B->planar == NULL) {
      free(B);
      return NULL;
    }
    return B;
  }
  nb = lgnGroupRigidBodies(G, NULL, NULL, NULL);
  if (nb < 1) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__,
              "G: the body helpers need bodies on R^3 x SO(3) or SE(3), or "
              "planar ones on SE(2) or R^2 x SO(2) (or a product of them).");
    free(B);
    return NULL;
  }
  B->nb      = nb;
  B->first_ghost = nb;
  B->qoff    = (sunindextype *)malloc((size_t)nb * sizeof *B->qoff);
  B->voff    = (sunindextype *)malloc((size_t)nb * sizeof *B->voff);
  B->se3     = (sunbooleantype *)malloc((size_t)nb * sizeof *B->se3);
  B->mass    = (sunrealtype *)malloc((size_t)nb * sizeof *B->mass);
  B->inertia = (sunrealtype *)malloc((size_t)nb * 9 * sizeof *B->inertia);
  if (B->qoff == NULL || B->voff == NULL || B->se3 == NULL || B->mass == NULL ||
      B->inertia == NULL) {
    LGNBodies_Destroy(&B);
    lgnReport(NULL, LGN_MEM_FAIL, __func__, MSG_MEM_FAIL);
    return NULL;
  }
  lgnGroupRigidBodies(G, B->qoff, B->voff, B->se3);
  for (k = 0; k < nb; k++) {
    sunrealtype *J = B->inertia + 9 * (size_t)k;
    B->mass[k] = SUN_RCONST(1.0);
    memset(J, 0, 9 * sizeof *J);
    J[0] = J[4] = J[8] = SUN_RCONST(1.0);
  }
  return B;
}

static void FreeStructure(struct LGNBodiesRec *B)
{
  free(B->kptr);
  free(B->kbody);
  free(B->kblk);
  B->kptr = B->kbody = NULL;
  B->kblk = NULL;
}

void LGNBodies_Destroy(LGNBodies *Bp)
{
  struct LGNBodiesRec *B;
  if (Bp == NULL || *Bp == NULL) return;
  B = *Bp;
  lgnPlanarBodiesDestroy(B->planar);
  FreeStructure(B);
  if (B->work != NULL) SUNMatDestroy(B->work);
  free(B->qoff);
  free(B->voff);
  free(B->se3);
  free(B->mass);
  free(B->inertia);
  free(B->elem);
  free(B);
  *Bp = NULL;
}

int LGNBodies_SetErrHandlerFn(LGNBodies B, LGNErrHandlerFn ehfun, void *eh_data)
{
  if (B == NULL) return NullBodies(__func__);
  B->err.ehfun   = ehfun;
  B->err.eh_data = eh_data;
  return LGN_SUCCESS;
}

int LGNBodies_SetErrFile(LGNBodies B, FILE *errfp)
{
  if (B == NULL) return NullBodies(__func__);
  B->err.errfp = errfp;
  return LGN_SUCCESS;
}

int LGNBodies_NumBodies(LGNBodies B) { return B != NULL ? B->nb : 0; }

/* The planar part (lgn_planar.h) and the sink, for lgn_planar_api.c. */
lgnPlanarBodies *lgnBodiesPlanarPart(LGNBodies B) { return B != NULL ? B->planar : NULL; }
const LGNErrSink *lgnBodiesSink(LGNBodies B) { return B != NULL ? &B->err : NULL; }

static int CheckBody(const struct LGNBodiesRec *B, int k, const char *func)
{
  if (k < 0 || k >= B->nb) {
    BErr(B, LGN_ILL_INPUT, func, "k = %d illegal (0..%d).", k, B->nb - 1);
    return LGN_ILL_INPUT;
  }
  if (k >= B->first_ghost) {
    BErr(B, LGN_ILL_INPUT, func,
         "k = %d illegal: a ghost body (LGNBodies_SetGhosts); its owner's rank "
         "holds its mass.", k);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int LGNBodies_SetGhosts(LGNBodies B, int first_ghost)
{
  int k;
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL) {
    BErr(B, LGN_ILL_INPUT, __func__, "B is a planar body set: it has no ghost bodies.");
    return LGN_ILL_INPUT;
  }
  if (first_ghost < 1 || first_ghost > B->nb) {
    BErr(B, LGN_ILL_INPUT, __func__, "first_ghost = %d illegal (1..%d).", first_ghost, B->nb);
    return LGN_ILL_INPUT;
  }
  for (k = first_ghost; k < B->nb; k++) { /* no mass, inertia or weight */
    B->mass[k] = SUN_RCONST(0.0);
    memset(B->inertia + 9 * (size_t)k, 0, 9 * sizeof(sunrealtype));
  }
  for (k = B->first_ghost; k < first_ghost; k++) { /* ghosts no more: defaults */
    sunrealtype *J = B->inertia + 9 * (size_t)k;
    B->mass[k] = SUN_RCONST(1.0);
    J[0] = J[4] = J[8] = SUN_RCONST(1.0);
  }
  B->first_ghost = first_ghost;
  return LGN_SUCCESS;
}

int LGNBodies_NumOwnedBodies(LGNBodies B) { return B != NULL ? B->first_ghost : 0; }

static int CheckMassValue(const struct LGNBodiesRec *B, sunrealtype m, const char *func)
{
  if (!(m > SUN_RCONST(0.0)) || !isfinite(m)) {
    BErr(B, LGN_ILL_INPUT, func, "m = %g illegal: must be positive and finite.", (double)m);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

/* The principal moments of a symmetric inertia tensor J satisfy the
 * triangle inequality J_i <= J_j + J_k iff S = (tr J / 2) 1 - J (the second
 * moment of the mass, int x x^T dm) is positive semidefinite: all its
 * principal minors >= 0, to 1e-12 relative (a plate: equality). */
static int TriangleInequality(const sunrealtype *J)
{
  const sunrealtype tr = J[0] + J[4] + J[8], tol = SUN_RCONST(1e-12);
  sunrealtype S[9], det;
  int i, j;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++)
      S[3 * i + j] = (i == j ? SUN_RCONST(0.5) * tr : SUN_RCONST(0.0)) -
                     SUN_RCONST(0.5) * (J[3 * i + j] + J[3 * j + i]);
  for (i = 0; i < 3; i++) {
    const int a = (i + 1) % 3, b = (i + 2) % 3;
    if (S[4 * i] < -tol * tr) return 0;
    if (S[4 * a] * S[4 * b] - S[3 * a + b] * S[3 * b + a] < -tol * tr * tr) return 0;
  }
  det = S[0] * (S[4] * S[8] - S[5] * S[7]) - S[1] * (S[3] * S[8] - S[5] * S[6]) +
        S[2] * (S[3] * S[7] - S[4] * S[6]);
  return det >= -tol * tr * tr * tr;
}

int LGNBodies_SetMass(LGNBodies B, int k, sunrealtype m, const sunrealtype inertia[9])
{
  int i, j;
  sunrealtype scale = SUN_RCONST(0.0), d1, d2, d3;
  const sunrealtype *J = inertia;
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL) { /* the inertia about the plane's normal */
    if (inertia == NULL) {
      BErr(B, LGN_ILL_INPUT, __func__, "inertia = NULL illegal.");
      return LGN_ILL_INPUT;
    }
    return lgnPlanarBodiesSetMass(B->planar, k, m, inertia[8], __func__);
  }
  if (CheckBody(B, k, __func__) != LGN_SUCCESS || CheckMassValue(B, m, __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (J == NULL) {
    BErr(B, LGN_ILL_INPUT, __func__, "inertia = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  for (i = 0; i < 9; i++) {
    if (!isfinite(J[i])) {
      BErr(B, LGN_ILL_INPUT, __func__, "inertia[%d] = %g illegal: not finite.", i, (double)J[i]);
      return LGN_ILL_INPUT;
    }
    if (fabs(J[i]) > scale) scale = fabs(J[i]);
  }
  for (i = 0; i < 3; i++)
    for (j = i + 1; j < 3; j++)
      if (fabs(J[3 * i + j] - J[3 * j + i]) > SUN_RCONST(1e-12) * scale) {
        BErr(B, LGN_ILL_INPUT, __func__,
             "inertia illegal: not symmetric (entries (%d,%d) = %g and (%d,%d) = %g).",
             i, j, (double)J[3 * i + j], j, i, (double)J[3 * j + i]);
        return LGN_ILL_INPUT;
      }
  /* positive definite: the leading minors (Sylvester) */
  d1 = J[0];
  d2 = J[0] * J[4] - J[1] * J[3];
  d3 = J[0] * (J[4] * J[8] - J[5] * J[7]) - J[1] * (J[3] * J[8] - J[5] * J[6]) +
       J[2] * (J[3] * J[7] - J[4] * J[6]);
  if (!(d1 > 0) || !(d2 > 0) || !(d3 > 0)) {
    BErr(B, LGN_ILL_INPUT, __func__, "inertia illegal: not positive definite.");
    return LGN_ILL_INPUT;
  }
  if (!TriangleInequality(J)) {
    BErr(B, LGN_ILL_INPUT, __func__,
         "inertia illegal: its largest principal moment exceeds the sum of the other "
         "two, which no rigid body's do (the triangle inequality).");
    return LGN_ILL_INPUT;
  }
  B->mass[k] = m;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) /* symmetrised */
      B->inertia[9 * (size_t)k + 3 * i + j] = SUN_RCONST(0.5) * (J[3 * i + j] + J[3 * j + i]);
  return LGN_SUCCESS;
}

int LGNBodies_SetPrincipalInertia(LGNBodies B, int k, sunrealtype m, const sunrealtype J[3])
{
  sunrealtype In[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL) { /* the moment about the plane's normal */
    if (J == NULL) {
      BErr(B, LGN_ILL_INPUT, __func__, "J = NULL illegal.");
      return LGN_ILL_INPUT;
    }
    return lgnPlanarBodiesSetMass(B->planar, k, m, J[2], __func__);
  }
  if (CheckBody(B, k, __func__) != LGN_SUCCESS || CheckMassValue(B, m, __func__) != LGN_SUCCESS ||
      lgnCheckVec3(&B->err, J, "J", __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (!(J[0] > 0) || !(J[1] > 0) || !(J[2] > 0)) {
    BErr(B, LGN_ILL_INPUT, __func__, "J = (%g, %g, %g) illegal: must be positive.",
         (double)J[0], (double)J[1], (double)J[2]);
    return LGN_ILL_INPUT;
  }
  {
    /* the principal moments of a rigid body satisfy J_i <= J_j + J_k
     * (J_i = int (r^2 - x_i^2) dm); equality (a plate) within round-off */
    const sunrealtype slack = SUN_RCONST(1.0) + SUN_RCONST(16.0) * SUN_UNIT_ROUNDOFF;
    int i;
    for (i = 0; i < 3; i++)
      if (J[i] > (J[(i + 1) % 3] + J[(i + 2) % 3]) * slack) {
        BErr(B, LGN_ILL_INPUT, __func__,
             "J = (%g, %g, %g) illegal: J[%d] exceeds the sum of the other two, which "
             "no rigid body's principal moments do (the triangle inequality).",
             (double)J[0], (double)J[1], (double)J[2], i);
        return LGN_ILL_INPUT;
      }
  }
  In[0] = J[0];
  In[4] = J[1];
  In[8] = J[2];
  B->mass[k] = m;
  memcpy(B->inertia + 9 * (size_t)k, In, sizeof In);
  return LGN_SUCCESS;
}

int LGNBodies_SetGravity(LGNBodies B, const sunrealtype gravity[3])
{
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL) return lgnPlanarBodiesSetGravity(B->planar, gravity, __func__);
  if (lgnCheckVec3(&B->err, gravity, "gravity", __func__) != LGN_SUCCESS) return LGN_ILL_INPUT;
  memcpy(B->gravity, gravity, sizeof B->gravity);
  return LGN_SUCCESS;
}

static int CheckPair(const struct LGNBodiesRec *B, int a, int b, const char *func)
{
  if (a < LGN_GROUND || a >= B->nb || b < LGN_GROUND || b >= B->nb || a == b) {
    BErr(B, LGN_ILL_INPUT, func,
         "bodies a = %d, b = %d illegal (0..%d or LGN_GROUND, a != b).", a, b, B->nb - 1);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

static int CheckCoef(const struct LGNBodiesRec *B, sunrealtype x, const char *name,
                     const char *func)
{
  if (!(x >= SUN_RCONST(0.0)) || !isfinite(x)) {
    BErr(B, LGN_ILL_INPUT, func, "%s = %g illegal: must be >= 0 and finite.", name, (double)x);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

static Element *NewElement(struct LGNBodiesRec *B, const char *func)
{
  if (B->nelem == B->cap) {
    int cap = B->cap > 0 ? 2 * B->cap : 8;
    Element *ne = (Element *)realloc(B->elem, (size_t)cap * sizeof *ne);
    if (ne == NULL) {
      BErr(B, LGN_MEM_FAIL, func, MSG_MEM_FAIL);
      return NULL;
    }
    B->elem = ne;
    B->cap  = cap;
  }
  FreeStructure(B); /* the coupling changed */
  memset(B->elem + B->nelem, 0, sizeof(Element));
  return B->elem + B->nelem++;
}

int LGNBodies_AddSpringDamper(LGNBodies B, int a, const sunrealtype sa[3], int b,
                              const sunrealtype sb[3], sunrealtype k, sunrealtype c,
                              sunrealtype L0)
{
  Element *e;
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL)
    return lgnPlanarBodiesAddSpring3(B->planar, a, sa, b, sb, k, c, L0, __func__);
  if (CheckPair(B, a, b, __func__) != LGN_SUCCESS || lgnCheckVec3(&B->err, sa, "sa", __func__) != LGN_SUCCESS ||
      lgnCheckVec3(&B->err, sb, "sb", __func__) != LGN_SUCCESS || CheckCoef(B, k, "k", __func__) != LGN_SUCCESS ||
      CheckCoef(B, c, "c", __func__) != LGN_SUCCESS || CheckCoef(B, L0, "L0", __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  e = NewElement(B, __func__);
  if (e == NULL) return LGN_MEM_FAIL;
  e->kind = ELEM_SPRING;
  e->a = a;
  e->b = b;
  memcpy(e->sa, sa, sizeof e->sa);
  memcpy(e->sb, sb, sizeof e->sb);
  e->k  = k;
  e->c  = c;
  e->L0 = L0;
  return LGN_SUCCESS;
}

int LGNBodies_AddRotationalSpringDamper(LGNBodies B, int a, int b, sunrealtype kr,
                                        sunrealtype cr, const sunrealtype rest[4])
{
  Element *e;
  sunrealtype nrm = SUN_RCONST(0.0);
  int i;
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL)
    return lgnPlanarBodiesAddRotSpringQuat(B->planar, a, b, kr, cr, rest, __func__);
  if (CheckPair(B, a, b, __func__) != LGN_SUCCESS || CheckCoef(B, kr, "kr", __func__) != LGN_SUCCESS ||
      CheckCoef(B, cr, "cr", __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (rest != NULL) {
    for (i = 0; i < 4; i++) nrm += rest[i] * rest[i];
    if (!(fabs(nrm - SUN_RCONST(1.0)) <= SUN_RCONST(1e-10))) {
      BErr(B, LGN_ILL_INPUT, __func__,
           "rest = (%g, %g, %g, %g) illegal: not a unit quaternion (|rest|^2 = %g).",
           (double)rest[0], (double)rest[1], (double)rest[2], (double)rest[3], (double)nrm);
      return LGN_ILL_INPUT;
    }
  }
  e = NewElement(B, __func__);
  if (e == NULL) return LGN_MEM_FAIL;
  e->kind = ELEM_ROTSPRING;
  e->a = a;
  e->b = b;
  e->k = kr;
  e->c = cr;
  e->rest = rest != NULL;
  if (e->rest) {
    for (i = 0; i < 4; i++) e->p0[i] = rest[i] / sqrt(nrm);
    LGNQuaternionToRotation(e->p0, e->R0);
  }
  return LGN_SUCCESS;
}

/* ---------------------------------------------------------------------------
 * Block structure of K_t and C_t
 * ------------------------------------------------------------------------ */

static int CompareInt(const void *x, const void *y)
{
  return *(const int *)x - *(const int *)y;
}

static int BuildStructure(struct LGNBodiesRec *B)
{
  int k, b, *cnt = (int *)calloc((size_t)B->nb + 1, sizeof(int));
  if (cnt == NULL) return LGN_MEM_FAIL;
  for (k = 0; k < B->nelem; k++) {
    const Element *e = B->elem + k;
    if (e->a != LGN_GROUND && e->b != LGN_GROUND) {
      cnt[e->a]++;
      cnt[e->b]++;
    }
  }
  B->kptr = (int *)malloc((size_t)(B->nb + 1) * sizeof(int));
  if (B->kptr == NULL) {
    free(cnt);
    return LGN_MEM_FAIL;
  }
  B->kptr[0] = 0;
  for (b = 0; b < B->nb; b++) B->kptr[b + 1] = B->kptr[b] + cnt[b] + 1;
  B->kbody = (int *)malloc((size_t)B->kptr[B->nb] * sizeof(int));
  B->kblk  = (sunrealtype *)malloc((size_t)B->kptr[B->nb] * 36 * sizeof(sunrealtype));
  if (B->kbody == NULL || B->kblk == NULL) {
    free(cnt);
    FreeStructure(B);
    return LGN_MEM_FAIL;
  }
  for (b = 0; b < B->nb; b++) {
    B->kbody[B->kptr[b]] = b;
    cnt[b] = 1;
  }
  for (k = 0; k < B->nelem; k++) {
    const Element *e = B->elem + k;
    if (e->a != LGN_GROUND && e->b != LGN_GROUND) {
      B->kbody[B->kptr[e->a] + cnt[e->a]++] = e->b;
      B->kbody[B->kptr[e->b] + cnt[e->b]++] = e->a;
    }
  }
  for (b = 0; b < B->nb; b++) {
    int *list = B->kbody + B->kptr[b], len = B->kptr[b + 1] - B->kptr[b], u = 0, i;
    qsort(list, (size_t)len, sizeof(int), CompareInt);
    for (i = 0; i < len; i++)
      if (u == 0 || list[i] != list[u - 1]) list[u++] = list[i];
    for (i = u; i < len; i++) list[i] = -2; /* unused slots */
  }
  free(cnt);
  return LGN_SUCCESS;
}

/* The 6x6 block (row body r, column body c), row-major. */
static sunrealtype *Block(struct LGNBodiesRec *B, int r, int c)
{
  int i;
  for (i = B->kptr[c]; i < B->kptr[c + 1]; i++)
    if (B->kbody[i] == r) return B->kblk + 36 * (size_t)i;
  return NULL;
}

/* blk(ro.., co..) += f X (3x3 row-major) */
static void AddSub(sunrealtype *blk, int ro, int co, const sunrealtype *X, sunrealtype f)
{
  int i, j;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) blk[6 * (ro + i) + co + j] += f * X[3 * i + j];
}

/* AddSub of a rotational spring's 3x3 term X at the rotation block of row
 * side sa and column side sb (0: body a, 1: body b), with its rest rotation:
 * a's rows R0 X, a's columns X R0^T (the file's header). */
static void AddRot(sunrealtype *blk, const Element *e, int sa, int sb, const sunrealtype *X,
                   sunrealtype f)
{
  sunrealtype Y[9], Z[9];
  int i;
  if (!e->rest) {
    AddSub(blk, 3, 3, X, f);
    return;
  }
  if (sa == 0) MM(e->R0, X, Y);
  else memcpy(Y, X, sizeof Y);
  if (sb == 0) { /* Z = Y R0^T */
    sunrealtype R0T[9];
    for (i = 0; i < 9; i++) R0T[i] = e->R0[3 * (i % 3) + i / 3];
    MM(Y, R0T, Z);
  } else
    memcpy(Z, Y, sizeof Z);
  AddSub(blk, 3, 3, Z, f);
}

sunindextype LGNBodies_MassNnz(LGNBodies B)
{
  if (B != NULL && B->planar != NULL) return lgnPlanarBodiesMassNnz(B->planar);
  return B != NULL ? 12 * (sunindextype)B->nb : 0;
}

sunindextype LGNBodies_TangentNnz(LGNBodies B)
{
  sunindextype n = 0;
  int b, i;
  if (B == NULL) return 0;
  if (B->planar != NULL) return lgnPlanarBodiesTangentNnz(B->planar);
  if (B->kptr == NULL && BuildStructure(B) != LGN_SUCCESS) return 0;
  for (b = 0; b < B->nb; b++)
    for (i = B->kptr[b]; i < B->kptr[b + 1] && B->kbody[i] >= 0; i++) n += 36;
  return n;
}

/* ---------------------------------------------------------------------------
 * Evaluation helpers
 * ------------------------------------------------------------------------ */

static int CheckMat(const struct LGNBodiesRec *B, SUNMatrix A, const char *name,
                    const char *func)
{
  const sunindextype nv = B->G->nv;
  if (A == NULL ||
      (lgnMatID(A) == SUNMATRIX_DENSE && (SM_ROWS_D(A) != nv || SM_COLUMNS_D(A) != nv)) ||
      (lgnMatIsSparse(A) &&
       (SUNSparseMatrix_Rows(A) != nv || SUNSparseMatrix_Columns(A) != nv)) ||
      (lgnMatID(A) != SUNMATRIX_DENSE && lgnMatID(A) != SUNMATRIX_SPARSE)) {
    BErr(B, LGN_ILL_INPUT, func, "%s must be a dense or sparse %lld x %lld matrix.", name,
         (long long)nv, (long long)nv);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

/* A body's pose and velocity (identity and rest for the ground). */
typedef struct {
  sunbooleantype ground, se3;
  sunrealtype x[3], R[9], p[4];
  sunrealtype v[6];
} Pose;

static void GetPose(const struct LGNBodiesRec *B, int k, const sunrealtype *q,
                    const sunrealtype *v, Pose *P)
{
  memset(P, 0, sizeof *P);
  P->ground = k == LGN_GROUND;
  if (P->ground) {
    P->R[0] = P->R[4] = P->R[8] = SUN_RCONST(1.0);
    P->p[0] = SUN_RCONST(1.0);
    return;
  }
  P->se3 = B->se3[k];
  memcpy(P->x, q + B->qoff[k], 3 * sizeof(sunrealtype));
  memcpy(P->p, q + B->qoff[k] + 3, 4 * sizeof(sunrealtype));
  LGNQuaternionToRotation(P->p, P->R);
  if (v != NULL) memcpy(P->v, v + B->voff[k], 6 * sizeof(sunrealtype));
}

/* H = [P, -R s~] (3x6 row-major), the point p = x + R s and pdot = H v. */
static void PointKin(const Pose *P, const sunrealtype *s, sunrealtype *H,
                     sunrealtype *p, sunrealtype *pd)
{
  sunrealtype S[9], RS[9], t[3];
  int i, j;
  if (P->ground) {
    memset(H, 0, 18 * sizeof *H);
    memcpy(p, s, 3 * sizeof *p);
    pd[0] = pd[1] = pd[2] = SUN_RCONST(0.0);
    return;
  }
  lgnSO3_Tilde(s, S);
  MM(P->R, S, RS);
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) {
      H[6 * i + j]     = P->se3 ? P->R[3 * i + j] : (i == j ? SUN_RCONST(1.0) : SUN_RCONST(0.0));
      H[6 * i + 3 + j] = -RS[3 * i + j];
    }
  lgnMat3Apply(P->R, s, t);
  for (i = 0; i < 3; i++) p[i] = P->x[i] + t[i];
  for (i = 0; i < 3; i++)
    pd[i] = H[6 * i] * P->v[0] + H[6 * i + 1] * P->v[1] + H[6 * i + 2] * P->v[2] +
            H[6 * i + 3] * P->v[3] + H[6 * i + 4] * P->v[4] + H[6 * i + 5] * P->v[5];
}

/* The geometry of a translational spring-damper. */
typedef struct {
  Pose P[2];
  sunrealtype H[2][18];     /* point Jacobians                         */
  sunrealtype d[3], dd[3];  /* Delta, Deltadot                         */
  sunrealtype L, n[3], f;   /* length, direction, tension              */
} SpringState;

static int SpringEval(const struct LGNBodiesRec *B, const Element *e,
                      const sunrealtype *q, const sunrealtype *v, SpringState *S,
                      const char *func)
{
  sunrealtype pa[3], pb[3], va[3], vb[3];
  int i;
  GetPose(B, e->a, q, v, &S->P[0]);
  GetPose(B, e->b, q, v, &S->P[1]);
  PointKin(&S->P[0], e->sa, S->H[0], pa, va);
  PointKin(&S->P[1], e->sb, S->H[1], pb, vb);
  for (i = 0; i < 3; i++) {
    S->d[i]  = pb[i] - pa[i];
    S->dd[i] = vb[i] - va[i];
  }
  S->L = sqrt(lgnVec3Dot(S->d, S->d));
  if (!(S->L > SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF *
                   (SUN_RCONST(1.0) + sqrt(lgnVec3Dot(pa, pa)) + sqrt(lgnVec3Dot(pb, pb))))) {
    BErr(B, LGN_ILL_INPUT, func,
         "spring-damper %d: length %g (the points coincide): its direction is undefined.",
         (int)(e - B->elem), (double)S->L);
    return LGN_ILL_INPUT;
  }
  for (i = 0; i < 3; i++) S->n[i] = S->d[i] / S->L;
  S->f = e->k * (S->L - e->L0) + e->c * lgnVec3Dot(S->n, S->dd);
  return LGN_SUCCESS;
}

/* The rotational spring-damper's relative rotation and theta. */
typedef struct {
  Pose P[2];
  sunrealtype Rrel[9], theta[3];
} RotState;

static void RotEval(const struct LGNBodiesRec *B, const Element *e, const sunrealtype *q,
                    const sunrealtype *v, RotState *S)
{
  sunrealtype pc[4], pr[4];
  GetPose(B, e->a, q, v, &S->P[0]);
  GetPose(B, e->b, q, v, &S->P[1]);
  if (e->rest) { /* body a's frame a' = R_a R0, Omega_a' = R0^T Omega_a */
    Pose *A = &S->P[0];
    sunrealtype R[9], w[3];
    MM(A->R, e->R0, R);
    memcpy(A->R, R, sizeof R);
    LGNQuaternionMultiply(A->p, e->p0, pc);
    memcpy(A->p, pc, sizeof pc);
    lgnMat3ApplyT(e->R0, A->v + 3, w);
    memcpy(A->v + 3, w, sizeof w);
  }
  MTM(S->P[0].R, S->P[1].R, S->Rrel);
  pc[0] = S->P[0].p[0];
  pc[1] = -S->P[0].p[1];
  pc[2] = -S->P[0].p[2];
  pc[3] = -S->P[0].p[3];
  LGNQuaternionMultiply(pc, S->P[1].p, pr);
  LGNRotationVectorFromQuaternion(pr, S->theta);
}

/* ---------------------------------------------------------------------------
 * M, g, energies
 * ------------------------------------------------------------------------ */

static int WriteSparse(struct LGNBodiesRec *B, SUNMatrix A, sunbooleantype mass,
                       const char *func);

/* Add the block structure's values (blocks kblk, or the mass blocks when
 * mass) to A, dense or sparse: an empty sparse A gets them written with
 * the pattern, a sparse A holding entries gets them added through the work
 * matrix (lgnSparseAdd). */
static int WriteBlocks(struct LGNBodiesRec *B, SUNMatrix A, sunbooleantype mass,
                       const char *func)
{
  int b, i, r, c;
  if (lgnMatIsSparse(A)) {
    int flag;
    if (lgnMatIsEmpty(A)) return WriteSparse(B, A, mass, func);
    if (lgnSparseWorkLike(&B->work, A) == NULL) {
      BErr(B, LGN_MEM_FAIL, func, MSG_MEM_FAIL);
      return LGN_MEM_FAIL;
    }
    flag = WriteSparse(B, B->work, mass, func);
    if (flag == LGN_SUCCESS && lgnSparseAdd(A, B->work) != LGN_SUCCESS) {
      BErr(B, LGN_MEM_FAIL, func, MSG_MEM_FAIL);
      flag = LGN_MEM_FAIL;
    }
    return flag;
  }
  {
    if (mass) {
      for (b = 0; b < B->nb; b++) {
        const sunindextype o = B->voff[b];
        for (i = 0; i < 3; i++) SM_ELEMENT_D(A, o + i, o + i) += B->mass[b];
        for (r = 0; r < 3; r++)
          for (c = 0; c < 3; c++)
            SM_ELEMENT_D(A, o + 3 + r, o + 3 + c) += B->inertia[9 * (size_t)b + 3 * r + c];
      }
      return LGN_SUCCESS;
    }
    for (b = 0; b < B->nb; b++)
      for (i = B->kptr[b]; i < B->kptr[b + 1] && B->kbody[i] >= 0; i++)
        for (r = 0; r < 6; r++)
          for (c = 0; c < 6; c++)
            SM_ELEMENT_D(A, B->voff[B->kbody[i]] + r, B->voff[b] + c) +=
                B->kblk[36 * (size_t)i + 6 * r + c];
    return LGN_SUCCESS;
  }
}

/* Overwrite the sparse A with the block structure's values and pattern. */
static int WriteSparse(struct LGNBodiesRec *B, SUNMatrix A, sunbooleantype mass,
                       const char *func)
{
  int b, i, r, c;
  {
    const sunindextype nnz = mass ? LGNBodies_MassNnz(B) : LGNBodies_TangentNnz(B);
    const sunbooleantype csc = SUNSparseMatrix_SparseType(A) == CSC_MAT;
    sunindextype *ptr, *ind, pos = 0;
    sunrealtype *val;
    if (SUNSparseMatrix_NNZ(A) < nnz && SUNSparseMatrix_Reallocate(A, nnz) != 0) {
      BErr(B, LGN_MEM_FAIL, func, MSG_MEM_FAIL);
      return LGN_MEM_FAIL;
    }
    ptr = SUNSparseMatrix_IndexPointers(A);
    ind = SUNSparseMatrix_IndexValues(A);
    val = SUNSparseMatrix_Data(A);
    ptr[0] = 0;
    for (b = 0; b < B->nb; b++)
      for (c = 0; c < 6; c++) {
        /* CSC: column c of body b; CSR: row c of body b. The bodies are in
         * offset order and the structure symmetric. */
        if (mass) {
          const sunindextype o = B->voff[b];
          if (c < 3) {
            ind[pos]   = o + c;
            val[pos++] = B->mass[b];
          } else
            for (r = 3; r < 6; r++) { /* symmetric: same in CSC and CSR */
              ind[pos]   = o + r;
              val[pos++] = B->inertia[9 * (size_t)b + 3 * (r - 3) + (c - 3)];
            }
        } else {
          for (i = B->kptr[b]; i < B->kptr[b + 1] && B->kbody[i] >= 0; i++) {
            const int o = B->kbody[i];
            const sunrealtype *blk_ob = B->kblk + 36 * (size_t)i; /* (row o, col b) */
            const sunrealtype *blk_bo = Block(B, b, o);           /* (row b, col o) */
            for (r = 0; r < 6; r++) {
              ind[pos]   = B->voff[o] + r;
              val[pos++] = csc ? blk_ob[6 * r + c] : blk_bo[6 * c + r];
            }
          }
        }
        ptr[B->voff[b] + c + 1] = pos;
      }
  }
  return LGN_SUCCESS;
}

int LGNBodies_Mass(LGNBodies B, N_Vector q, SUNMatrix M)
{
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL) return lgnPlanarBodiesMass(B->planar, q, M, __func__);
  if (lgnCheckSerialVector(&B->err, q, B->G->nq, "q", __func__) != LGN_SUCCESS ||
      CheckMat(B, M, "M", __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  return WriteBlocks(B, M, SUNTRUE, __func__);
}

int LGNBodies_Force(LGNBodies B, N_Vector q, N_Vector v, N_Vector g)
{
  const sunrealtype *qd, *vd;
  sunrealtype *gd;
  int k, i, side;
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL) return lgnPlanarBodiesForce(B->planar, q, v, g, __func__);
  if (lgnCheckSerialVector(&B->err, q, B->G->nq, "q", __func__) != LGN_SUCCESS ||
      lgnCheckSerialVector(&B->err, v, B->G->nv, "v", __func__) != LGN_SUCCESS ||
      lgnCheckSerialVector(&B->err, g, B->G->nv, "g", __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  qd = lgnVecData(q);
  vd = lgnVecData(v);
  gd = lgnVecData(g);
  for (k = 0; k < B->nb; k++) {
    const sunrealtype *u = vd + B->voff[k], *w = u + 3, *J = B->inertia + 9 * (size_t)k;
    const sunrealtype m = B->mass[k];
    sunrealtype *gk = gd + B->voff[k], Jw[3], R[9], mu[3], f[3];
    lgnMat3Apply(J, w, Jw);
    lgnVec3Cross(w, Jw, gk + 3);
    for (i = 0; i < 3; i++) f[i] = m * B->gravity[i];
    if (B->se3[k]) {
      LGNQuaternionToRotation(qd + B->qoff[k] + 3, R);
      lgnMat3ApplyT(R, f, mu);
      lgnVec3Cross(w, u, gk);
      for (i = 0; i < 3; i++) gk[i] = m * gk[i] - mu[i];
    } else {
      for (i = 0; i < 3; i++) gk[i] = -f[i];
    }
  }
  for (k = 0; k < B->nelem; k++) {
    const Element *e = B->elem + k;
    if (e->kind == ELEM_SPRING) {
      SpringState S;
      sunrealtype F[3];
      if (SpringEval(B, e, qd, vd, &S, __func__) != LGN_SUCCESS) return LGN_ILL_INPUT;
      for (i = 0; i < 3; i++) F[i] = S.f * S.n[i];
      for (side = 0; side < 2; side++) {
        const sunrealtype sign = side == 0 ? SUN_RCONST(-1.0) : SUN_RCONST(1.0);
        const sunrealtype *H = S.H[side];
        sunrealtype *gb;
        int j;
        if (S.P[side].ground) continue;
        gb = gd + B->voff[side == 0 ? e->a : e->b];
        for (j = 0; j < 6; j++) gb[j] += sign * (H[j] * F[0] + H[6 + j] * F[1] + H[12 + j] * F[2]);
      }
    } else {
      RotState S;
      sunrealtype t1[3], t2[3];
      RotEval(B, e, qd, vd, &S);
      if (e->a != LGN_GROUND) {
        sunrealtype *ga = gd + B->voff[e->a] + 3, tq[3];
        lgnMat3Apply(S.Rrel, S.P[1].v + 3, t1);
        for (i = 0; i < 3; i++) tq[i] = -e->k * S.theta[i] - e->c * (t1[i] - S.P[0].v[3 + i]);
        if (e->rest) lgnMat3Apply(e->R0, tq, t2); /* a's rows: R0 times a''s */
        else memcpy(t2, tq, sizeof tq);
        for (i = 0; i < 3; i++) ga[i] += t2[i];
      }
      if (e->b != LGN_GROUND) {
        sunrealtype *gb = gd + B->voff[e->b] + 3;
        lgnMat3ApplyT(S.Rrel, S.P[0].v + 3, t2);
        for (i = 0; i < 3; i++) gb[i] += e->k * S.theta[i] + e->c * (S.P[1].v[3 + i] - t2[i]);
      }
    }
  }
  return LGN_SUCCESS;
}

int LGNBodies_Energy(LGNBodies B, N_Vector q, N_Vector v, sunrealtype *kinetic,
                     sunrealtype *potential)
{
  const sunrealtype *qd, *vd;
  sunrealtype T = SUN_RCONST(0.0), V = SUN_RCONST(0.0), Jw[3];
  int k;
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL)
    return lgnPlanarBodiesEnergy(B->planar, q, v, kinetic, potential, __func__);
  if (lgnCheckSerialVector(&B->err, q, B->G->nq, "q", __func__) != LGN_SUCCESS ||
      lgnCheckSerialVector(&B->err, v, B->G->nv, "v", __func__) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  qd = lgnVecData(q);
  vd = lgnVecData(v);
  for (k = 0; k < B->nb; k++) {
    const sunrealtype *u = vd + B->voff[k], *w = u + 3;
    lgnMat3Apply(B->inertia + 9 * (size_t)k, w, Jw);
    T += SUN_RCONST(0.5) * (B->mass[k] * lgnVec3Dot(u, u) + lgnVec3Dot(w, Jw));
    V -= B->mass[k] * lgnVec3Dot(B->gravity, qd + B->qoff[k]);
  }
  for (k = 0; k < B->nelem; k++) {
    const Element *e = B->elem + k;
    if (e->kind == ELEM_SPRING) {
      SpringState S;
      if (SpringEval(B, e, qd, vd, &S, __func__) != LGN_SUCCESS) return LGN_ILL_INPUT;
      V += SUN_RCONST(0.5) * e->k * (S.L - e->L0) * (S.L - e->L0);
    } else {
      RotState S;
      RotEval(B, e, qd, vd, &S);
      V += SUN_RCONST(0.5) * e->k * lgnVec3Dot(S.theta, S.theta);
    }
  }
  if (kinetic != NULL) *kinetic = T;
  if (potential != NULL) *potential = V;
  return LGN_SUCCESS;
}

/* ---------------------------------------------------------------------------
 * K_t and C_t
 * ------------------------------------------------------------------------ */

/* blk += s X^T Y for X, Y 3x6 row-major, with a 3x3 middle Mm (row-major,
 * NULL: identity): blk += s X^T Mm Y. */
static void AddXtMY(sunrealtype *blk, const sunrealtype *X, const sunrealtype *Mm,
                    const sunrealtype *Y, sunrealtype s)
{
  sunrealtype MY[18];
  int i, j, l;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 6; j++)
      MY[6 * i + j] = Mm == NULL ? Y[6 * i + j]
                                 : Mm[3 * i] * Y[j] + Mm[3 * i + 1] * Y[6 + j] + Mm[3 * i + 2] * Y[12 + j];
  for (i = 0; i < 6; i++)
    for (j = 0; j < 6; j++) {
      sunrealtype acc = SUN_RCONST(0.0);
      for (l = 0; l < 3; l++) acc += X[6 * l + i] * MY[6 * l + j];
      blk[6 * i + j] += s * acc;
    }
}

/* Fill kblk with K_t (stiff) or C_t (!stiff). */
static int Tangent(struct LGNBodiesRec *B, const sunrealtype *qd, const sunrealtype *vd,
                   sunbooleantype stiff, const char *func)
{
  int k, i, j, sa, sb;
  memset(B->kblk, 0, (size_t)B->kptr[B->nb] * 36 * sizeof(sunrealtype));
  for (k = 0; k < B->nb; k++) {
    sunrealtype *blk = Block(B, k, k), X[9], t[3], R[9], mu[3], f[3];
    const sunrealtype *u = vd + B->voff[k], *w = u + 3, *J = B->inertia + 9 * (size_t)k;
    if (stiff) {
      if (!B->se3[k]) continue;
      /* d(-R^T m gvec)/dtheta = -(R^T m gvec)~ */
      LGNQuaternionToRotation(qd + B->qoff[k] + 3, R);
      for (i = 0; i < 3; i++) f[i] = B->mass[k] * B->gravity[i];
      lgnMat3ApplyT(R, f, mu);
      lgnSO3_Tilde(mu, X);
      AddSub(blk, 0, 3, X, SUN_RCONST(-1.0));
      continue;
    }
    /* d(w x J w)/dw = w~ J - (J w)~ */
    lgnSO3_Tilde(w, X);
    MM(X, J, R);
    AddSub(blk, 3, 3, R, SUN_RCONST(1.0));
    lgnMat3Apply(J, w, t);
    lgnSO3_Tilde(t, X);
    AddSub(blk, 3, 3, X, SUN_RCONST(-1.0));
    if (B->se3[k]) { /* d m (w x U) = m w~ dU - m U~ dw */
      lgnSO3_Tilde(w, X);
      AddSub(blk, 0, 0, X, B->mass[k]);
      lgnSO3_Tilde(u, X);
      AddSub(blk, 0, 3, X, -B->mass[k]);
    }
  }
  for (k = 0; k < B->nelem; k++) {
    const Element *e = B->elem + k;
    const int body[2] = {e->a, e->b};
    if (e->kind == ELEM_SPRING) {
      SpringState S;
      sunrealtype D[2][18], E[2][18], nn[9], G[9], Pp[3], F[3];
      if (SpringEval(B, e, qd, vd, &S, func) != LGN_SUCCESS) return LGN_ILL_INPUT;
      for (i = 0; i < 3; i++) F[i] = S.f * S.n[i];
      for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) nn[3 * i + j] = S.n[i] * S.n[j];
      for (sa = 0; sa < 2; sa++) {
        const sunrealtype sign = sa == 0 ? SUN_RCONST(-1.0) : SUN_RCONST(1.0);
        const Pose *P = &S.P[sa];
        sunrealtype y[3], Y[9], RY[9];
        for (i = 0; i < 18; i++) D[sa][i] = sign * S.H[sa][i];
        /* E = sign [0, -R (Omega x s + [SE(3)] U)~] */
        lgnVec3Cross(P->v + 3, sa == 0 ? e->sa : e->sb, y);
        if (P->se3)
          for (i = 0; i < 3; i++) y[i] += P->v[i];
        lgnSO3_Tilde(y, Y);
        MM(P->R, Y, RY);
        for (i = 0; i < 3; i++)
          for (j = 0; j < 3; j++) {
            E[sa][6 * i + j]     = SUN_RCONST(0.0);
            E[sa][6 * i + 3 + j] = -sign * RY[3 * i + j];
          }
        if (P->ground) memset(E[sa], 0, sizeof E[sa]);
      }
      if (stiff) {
        const sunrealtype fl = S.f / S.L, cl = e->c / S.L;
        sunrealtype sdot = lgnVec3Dot(S.n, S.dd);
        for (i = 0; i < 3; i++) Pp[i] = S.dd[i] - sdot * S.n[i]; /* (I - nn^T) Deltadot */
        for (i = 0; i < 3; i++)
          for (j = 0; j < 3; j++)
            G[3 * i + j] = e->k * nn[3 * i + j] +
                           fl * ((i == j ? SUN_RCONST(1.0) : SUN_RCONST(0.0)) - nn[3 * i + j]) +
                           cl * S.n[i] * Pp[j];
      }
      for (sa = 0; sa < 2; sa++) {
        if (S.P[sa].ground) continue;
        for (sb = 0; sb < 2; sb++) {
          sunrealtype *blk;
          if (S.P[sb].ground) continue;
          blk = Block(B, body[sa], body[sb]);
          if (stiff) {
            AddXtMY(blk, D[sa], G, D[sb], SUN_RCONST(1.0));
            if (e->c != SUN_RCONST(0.0)) AddXtMY(blk, D[sa], nn, E[sb], e->c);
          } else if (e->c != SUN_RCONST(0.0)) {
            AddXtMY(blk, D[sa], nn, D[sb], e->c);
          }
        }
        if (stiff) { /* the fixed-F terms, sign -1 at a */
          const sunrealtype sign = sa == 0 ? SUN_RCONST(-1.0) : SUN_RCONST(1.0);
          sunrealtype mu[3], Sx[9], Mu[9], SM[9];
          sunrealtype *blk = Block(B, body[sa], body[sa]);
          lgnMat3ApplyT(S.P[sa].R, F, mu);
          lgnSO3_Tilde(sa == 0 ? e->sa : e->sb, Sx);
          lgnSO3_Tilde(mu, Mu);
          MM(Sx, Mu, SM);
          AddSub(blk, 3, 3, SM, sign);
          if (S.P[sa].se3) AddSub(blk, 0, 3, Mu, sign);
        }
      }
    } else {
      RotState S;
      sunrealtype Ti[9], X[9], Y[9], Z[9], t[3], RT[9];
      RotEval(B, e, qd, vd, &S);
      for (i = 0; i < 9; i++) RT[i] = S.Rrel[3 * (i % 3) + i / 3];
      if (stiff) {
        for (j = 0; j < 3; j++) { /* T(theta)^-1, column j */
          sunrealtype ej[3] = {0, 0, 0}, col[3];
          ej[j] = SUN_RCONST(1.0);
          lgnSO3_TInvApply(S.theta, ej, col);
          for (i = 0; i < 3; i++) Ti[3 * i + j] = col[i];
        }
      }
      for (sa = 0; sa < 2; sa++) {
        if (body[sa] == LGN_GROUND) continue;
        for (sb = 0; sb < 2; sb++) {
          sunrealtype *blk;
          if (body[sb] == LGN_GROUND) continue;
          blk = Block(B, body[sa], body[sb]);
          if (!stiff) {
            /* C: aa cI, ab -c Rrel, ba -c Rrel^T, bb cI */
            if (sa == sb) {
              for (i = 0; i < 3; i++) blk[6 * (3 + i) + 3 + i] += e->c;
            } else {
              AddRot(blk, e, sa, sb, sa == 0 ? S.Rrel : RT, -e->c);
            }
            continue;
          }
          if (sa == 1 && sb == 1) { /* k T^-1 - c (Rrel^T Omega_a)~ */
            AddRot(blk, e, sa, sb, Ti, e->k);
            lgnMat3Apply(RT, S.P[0].v + 3, t);
            lgnSO3_Tilde(t, X);
            AddRot(blk, e, sa, sb, X, -e->c);
          } else if (sa == 1 && sb == 0) { /* -k T^-1 Rrel^T + c Rrel^T Omega_a~ */
            MM(Ti, RT, Z);
            AddRot(blk, e, sa, sb, Z, -e->k);
            lgnSO3_Tilde(S.P[0].v + 3, X);
            MM(RT, X, Y);
            AddRot(blk, e, sa, sb, Y, e->c);
          } else if (sa == 0 && sb == 1) { /* -k T^-1 + c Rrel Omega_b~ */
            AddRot(blk, e, sa, sb, Ti, -e->k);
            lgnSO3_Tilde(S.P[1].v + 3, X);
            MM(S.Rrel, X, Y);
            AddRot(blk, e, sa, sb, Y, e->c);
          } else { /* k T^-1 Rrel^T - c (Rrel Omega_b)~ */
            MM(Ti, RT, Z);
            AddRot(blk, e, sa, sb, Z, e->k);
            lgnMat3Apply(S.Rrel, S.P[1].v + 3, t);
            lgnSO3_Tilde(t, X);
            AddRot(blk, e, sa, sb, X, -e->c);
          }
        }
      }
    }
  }
  return LGN_SUCCESS;
}

static int TangentPublic(struct LGNBodiesRec *B, N_Vector q, N_Vector v, SUNMatrix A,
                         sunbooleantype stiff, const char *func)
{
  if (lgnCheckSerialVector(&B->err, q, B->G->nq, "q", func) != LGN_SUCCESS ||
      lgnCheckSerialVector(&B->err, v, B->G->nv, "v", func) != LGN_SUCCESS ||
      CheckMat(B, A, stiff ? "K" : "C", func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  if (B->kptr == NULL && BuildStructure(B) != LGN_SUCCESS) {
    BErr(B, LGN_MEM_FAIL, func, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  if (Tangent(B, lgnVecData(q), lgnVecData(v), stiff, func) != LGN_SUCCESS)
    return LGN_ILL_INPUT;
  return WriteBlocks(B, A, SUNFALSE, func);
}

int LGNBodies_Stiffness(LGNBodies B, N_Vector q, N_Vector v, SUNMatrix K)
{
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL) return lgnPlanarBodiesTangent(B->planar, q, v, K, SUNFALSE, __func__);
  return TangentPublic(B, q, v, K, SUNTRUE, __func__);
}

int LGNBodies_Damping(LGNBodies B, N_Vector q, N_Vector v, SUNMatrix C)
{
  if (B == NULL) return NullBodies(__func__);
  if (B->planar != NULL) return lgnPlanarBodiesTangent(B->planar, q, v, C, SUNTRUE, __func__);
  return TangentPublic(B, q, v, C, SUNFALSE, __func__);
}

/* ---------------------------------------------------------------------------
 * Callbacks
 * ------------------------------------------------------------------------ */

int LGNBodies_MassFn(sunrealtype t, N_Vector q, SUNMatrix M, void *user_data)
{
  (void)t;
  return LGNBodies_Mass((LGNBodies)user_data, q, M) == LGN_SUCCESS ? 0 : -1;
}

int LGNBodies_ForceFn(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *user_data)
{
  (void)t;
  return LGNBodies_Force((LGNBodies)user_data, q, v, g) == LGN_SUCCESS ? 0 : -1;
}

int LGNBodies_StiffnessFn(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                          N_Vector lambda, SUNMatrix K, void *user_data)
{
  (void)t;
  (void)vdot;
  (void)lambda;
  return LGNBodies_Stiffness((LGNBodies)user_data, q, v, K) == LGN_SUCCESS ? 0 : -1;
}

int LGNBodies_DampingFn(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *user_data)
{
  (void)t;
  return LGNBodies_Damping((LGNBodies)user_data, q, v, C) == LGN_SUCCESS ? 0 : -1;
}

LGNGroup lgnBodiesGroup(LGNBodies B) { return B != NULL ? B->G : NULL; }
