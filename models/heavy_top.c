/* -----------------------------------------------------------------------------
 * Lignum study models: the heavy top (Brüls and Cardona 2010) in three formulations.
 *
 *  Lie group R^3 x SO(3): q = (x, p), v = (u, Omega), spherical joint at 0:
 *    M = diag(m I, J),  g = [-m gamma_g ; Omega x J Omega],
 *    Phi = X - R^T x,   B = [-R^T, -X~]           (Brüls-Cardona, Klemps (2.21)-(2.26))
 *    K_t = [[0, R lambda~], [0, 0]],  C_t = [[0, 0], [0, Omega~ J - (J Omega)~]],
 *    Z(q)(v, v) = Omega x (R^T u).
 *
 *  Lie group SE(3) (doc/theory.md): q = (x, p) with x the
 *  centre of mass (the body frame's origin), v = (U, Omega) both body-fixed,
 *  xdot = R U, q o exp(w) moves x by R dU and R by R dpsi~:
 *    M = diag(m I, J),  g = [m Omega x U - m R^T gamma_g ; Omega x J Omega],
 *    Phi = X - R^T x,   B = [-I, -X~]                (Klemps (2.25), (2.27))
 *    K_t = [[0, -m (R^T gamma_g)~], [0, 0]],
 *    C_t = [[m Omega~, -m U~], [0, Omega~ J - (J Omega)~]],   Z = 0.
 *  The exact derivative is B(q) = [-I, -(R^T x)~]; it equals [-I, -X~] on the
 *  constraint manifold, and the constant form (as in Brüls and Cardona 2010) is used, as the
 *  R^3 x SO(3) model uses -X~ for -(R^T x)~. B is constant, so Z = 0 and B^T
 *  lambda adds nothing to K_t. The multiplier is the same as in R^3 x SO(3):
 *  m(Udot + Omega x U) = R^T m udot, so lambda = R^T(m udot - m gamma_g).
 *
 *  Euler parameters on R^7 (doc/theory.md): q = (x, p), v = (xdot, pdot):
 *    M = diag(m I, 4 G^T J G),  g = [-m gamma_g ; 8 Gdot^T J G pdot],
 *    Phi = [X - R(p)^T x ; p^T p - 1],  B = dPhi/dq,
 *    with G(p) = [-pbar, -pbar~ + p0 I] and R(p) = (p0^2 - pbar.pbar) I
 *    + 2 pbar pbar^T + 2 p0 pbar~. K_t, C_t and Z are the plain derivatives
 *    on R^7 (q w~ = w); their formulas are at EPStiffness, EPDamping and
 *    EPCurvature.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include "heavy_top.h"
#include "euler_parameters.h"

#include <float.h>
#include <math.h>
#include <string.h>
#include <time.h>

#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#define ELEM(A, i, j) SM_ELEMENT_D(A, i, j)

static const double X_BODY[3] = {0.0, 1.0, 0.0};       /* centre of mass */
static const double J_BODY[3] = {HT_J1, HT_J2, HT_J3}; /* principal inertia */

/* =============================================================================
 * Small vector helpers
 * ===========================================================================*/

static void Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* T = a~ (row-major), so that T b = a x b */
static void Tilde(const double a[3], double T[9])
{
  T[0] = 0.0;   T[1] = -a[2]; T[2] = a[1];
  T[3] = a[2];  T[4] = 0.0;   T[5] = -a[0];
  T[6] = -a[1]; T[7] = a[0];  T[8] = 0.0;
}

/* The rotational block -X~ of the joint Jacobian B = [ . , -X~] (columns 3..5). */
static void SetMinusXTilde(SUNMatrix B)
{
  double Xt[9];
  int i, j;
  Tilde(X_BODY, Xt);
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) ELEM(B, i, 3 + j) = -Xt[3 * i + j];
}

/* y = R^T x for row-major R */
static void MatTVec(const double R[9], const double x[3], double y[3])
{
  int i;
  for (i = 0; i < 3; i++) y[i] = R[i] * x[0] + R[3 + i] * x[1] + R[6 + i] * x[2];
}

/* =============================================================================
 * R^3 x SO(3) callbacks
 * ===========================================================================*/

static int LieMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  int i;
  (void)t; (void)q; (void)ud;
  for (i = 0; i < 3; i++) {
    ELEM(M, i, i)         = HT_MASS;
    ELEM(M, 3 + i, 3 + i) = J_BODY[i];
  }
  return 0;
}

static int LieForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const double *vv = N_VGetArrayPointer(v);
  double *gg = N_VGetArrayPointer(g), JW[3];
  int i;
  (void)t; (void)q; (void)ud;
  gg[0] = 0.0;
  gg[1] = 0.0;
  gg[2] = -HT_MASS * HT_GRAVITY;
  for (i = 0; i < 3; i++) JW[i] = J_BODY[i] * vv[3 + i];
  Cross(vv + 3, JW, gg + 3);
  return 0;
}

static int LieConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const double *qq = N_VGetArrayPointer(q);
  double *ph = N_VGetArrayPointer(phi), R[9], Rtx[3];
  int i;
  (void)t; (void)ud;
  LGNQuaternionToRotation(qq + 3, R);
  MatTVec(R, qq, Rtx);
  for (i = 0; i < 3; i++) ph[i] = X_BODY[i] - Rtx[i];
  return 0;
}

static int LieConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  const double *qq = N_VGetArrayPointer(q);
  double R[9];
  int i, j;
  (void)t; (void)ud;
  LGNQuaternionToRotation(qq + 3, R);
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) ELEM(B, i, j) = -R[3 * j + i]; /* -R^T */
  SetMinusXTilde(B);
  return 0;
}

static int LieStiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                        N_Vector lambda, SUNMatrix K, void *ud)
{
  const double *qq = N_VGetArrayPointer(q), *l = N_VGetArrayPointer(lambda);
  double R[9], lt[9];
  int i, j, k;
  (void)t; (void)v; (void)vdot; (void)ud;
  LGNQuaternionToRotation(qq + 3, R);
  /* lambda~ row-major */
  Tilde(l, lt);
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) {
      double s = 0.0;
      for (k = 0; k < 3; k++) s += R[3 * i + k] * lt[3 * k + j];
      ELEM(K, i, 3 + j) = s;
    }
  return 0;
}

static int LieDamping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  const double *W = N_VGetArrayPointer(v) + 3;
  double JW[3];
  int i;
  (void)t; (void)q; (void)ud;
  for (i = 0; i < 3; i++) JW[i] = J_BODY[i] * W[i];
  /* Omega~ J - (J Omega)~ */
  ELEM(C, 3, 4) = -W[2] * J_BODY[1] + JW[2];
  ELEM(C, 3, 5) = W[1] * J_BODY[2] - JW[1];
  ELEM(C, 4, 3) = W[2] * J_BODY[0] - JW[2];
  ELEM(C, 4, 5) = -W[0] * J_BODY[2] + JW[0];
  ELEM(C, 5, 3) = -W[1] * J_BODY[0] + JW[1];
  ELEM(C, 5, 4) = W[0] * J_BODY[1] - JW[0];
  return 0;
}

static int LieCurvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  const double *qq = N_VGetArrayPointer(q), *vv = N_VGetArrayPointer(v);
  double R[9], Rtu[3];
  (void)t; (void)ud;
  LGNQuaternionToRotation(qq + 3, R);
  MatTVec(R, vv, Rtu);
  Cross(vv + 3, Rtu, N_VGetArrayPointer(z));
  return 0;
}

/* =============================================================================
 * SE(3) callbacks (q = (x, p), v = (U, Omega), both body-fixed)
 * ===========================================================================*/

/* The mass matrix is the same as in R^3 x SO(3): LieMass. Phi too: LieConstr. */

static int SE3Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const double *qq = N_VGetArrayPointer(q), *vv = N_VGetArrayPointer(v);
  double *gg = N_VGetArrayPointer(g), R[9], Rtg[3], WxU[3], JW[3];
  const double grav[3] = {0.0, 0.0, HT_GRAVITY};
  int i;
  (void)t; (void)ud;
  LGNQuaternionToRotation(qq + 3, R);
  MatTVec(R, grav, Rtg);
  Cross(vv + 3, vv, WxU);
  for (i = 0; i < 3; i++) {
    gg[i] = HT_MASS * (WxU[i] - Rtg[i]);
    JW[i] = J_BODY[i] * vv[3 + i];
  }
  Cross(vv + 3, JW, gg + 3);
  return 0;
}

static int SE3ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  int i;
  (void)t; (void)q; (void)ud;
  for (i = 0; i < 3; i++) ELEM(B, i, i) = -1.0; /* -I */
  SetMinusXTilde(B);
  return 0;
}

/* K_t: only -m R^T gamma_g depends on q; along R -> R exp(dpsi~),
 * d(R^T gamma_g) = -dpsi~ R^T gamma_g = (R^T gamma_g)~ dpsi. */
static int SE3Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                        N_Vector lambda, SUNMatrix K, void *ud)
{
  const double *qq = N_VGetArrayPointer(q);
  const double grav[3] = {0.0, 0.0, HT_GRAVITY};
  double R[9], c[3];
  int i;
  (void)t; (void)v; (void)vdot; (void)lambda; (void)ud;
  LGNQuaternionToRotation(qq + 3, R);
  MatTVec(R, grav, c);
  for (i = 0; i < 3; i++) c[i] *= -HT_MASS; /* K_12 = (c)~, c = -m R^T gamma_g */
  ELEM(K, 0, 4) = -c[2]; ELEM(K, 0, 5) = c[1];
  ELEM(K, 1, 3) = c[2];  ELEM(K, 1, 5) = -c[0];
  ELEM(K, 2, 3) = -c[1]; ELEM(K, 2, 4) = c[0];
  return 0;
}

static int SE3Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  const double *U = N_VGetArrayPointer(v), *W = U + 3;
  const double m = HT_MASS;
  int flag;
  /* rotational block as in R^3 x SO(3) */
  flag = LieDamping(t, q, v, C, ud);
  /* d(m Omega x U)/dU = m Omega~ */
  ELEM(C, 0, 1) = -m * W[2]; ELEM(C, 0, 2) = m * W[1];
  ELEM(C, 1, 0) = m * W[2];  ELEM(C, 1, 2) = -m * W[0];
  ELEM(C, 2, 0) = -m * W[1]; ELEM(C, 2, 1) = m * W[0];
  /* d(m Omega x U)/dOmega = -m U~ */
  ELEM(C, 0, 4) = m * U[2];  ELEM(C, 0, 5) = -m * U[1];
  ELEM(C, 1, 3) = -m * U[2]; ELEM(C, 1, 5) = m * U[0];
  ELEM(C, 2, 3) = m * U[1];  ELEM(C, 2, 4) = -m * U[0];
  return flag;
}

/* Z(q)(v, v) = d/dt(B v) - B vdot = 0, since B is constant. */
static int SE3Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  N_VConst(0.0, z);
  return 0;
}

/* =============================================================================
 * Euler-parameter callbacks (q = (x, p0, pbar) in R^7)
 *
 * G(p) is linear in p and G(p) p = 0, so G(a) b = -G(b) a; G(d)^T c = H(c) d
 * with H(c) = [[0, -c^T], [c, -c~]] (4 x 4). R(p) = Q(p, p) for the symmetric
 * bilinear Q(a, b) = (a0 b0 - abar.bbar) I + abar bbar^T + bbar abar^T
 * + a0 bbar~ + b0 abar~, so Phi and B are polynomials in q and the tangent
 * matrices below are their exact derivatives.
 * ===========================================================================*/

/* z = Q(a, b)^T y = (a0 b0 - abar.bbar) y + bbar (abar.y) + abar (bbar.y)
 *                   - a0 bbar x y - b0 abar x y */
static void EPQuadTVec(const double a[4], const double b[4], const double y[3],
                       double z[3])
{
  const double s = a[0] * b[0] - Dot(a + 1, b + 1), ay = Dot(a + 1, y), by = Dot(b + 1, y);
  double axy[3], bxy[3];
  int i;
  Cross(a + 1, y, axy);
  Cross(b + 1, y, bxy);
  for (i = 0; i < 3; i++)
    z[i] = s * y[i] + b[1 + i] * ay + a[1 + i] * by - a[0] * bxy[i] - b[0] * axy[i];
}


static int EPMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  const double *p = N_VGetArrayPointer(q) + 3;
  double G[12], Mp[16] = {0.0};
  int i, j;
  (void)t; (void)ud;
  ep_matrix_g(p, G);
  ep_add_gt_j_g(G, J_BODY, G, 4.0, Mp); /* 4 G^T J G */
  for (i = 0; i < 3; i++) ELEM(M, i, i) = HT_MASS;
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) ELEM(M, 3 + i, 3 + j) = Mp[4 * i + j];
  return 0;
}

static int EPForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const double *p = N_VGetArrayPointer(q) + 3, *pd = N_VGetArrayPointer(v) + 3;
  double *gg = N_VGetArrayPointer(g), G[12], Gd[12], JGpd[3];
  int i, k;
  (void)t; (void)ud;
  ep_matrix_g(p, G);
  ep_matrix_g(pd, Gd); /* Gdot = G(pdot) */
  gg[0] = 0.0;
  gg[1] = 0.0;
  gg[2] = -HT_MASS * HT_GRAVITY;
  ep_g_vec(G, pd, JGpd);
  for (k = 0; k < 3; k++) JGpd[k] *= J_BODY[k];
  for (i = 0; i < 4; i++)
    gg[3 + i] = 8.0 * (Gd[i] * JGpd[0] + Gd[4 + i] * JGpd[1] + Gd[8 + i] * JGpd[2]);
  return 0;
}

static int EPConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const double *qq = N_VGetArrayPointer(q), *p = qq + 3;
  double *ph = N_VGetArrayPointer(phi), R[9], Rtx[3];
  int i;
  (void)t; (void)ud;
  ep_rotation(p, R);
  MatTVec(R, qq, Rtx);
  for (i = 0; i < 3; i++) ph[i] = X_BODY[i] - Rtx[i];
  ph[3] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1.0;
  return 0;
}

/* B = dPhi/dq. With R^T x = (p0^2 - |pbar|^2) x + 2 pbar (pbar.x) - 2 p0 pbar x x:
 *   d/dp0   = 2 p0 x - 2 pbar x x
 *   d/dpbar = -2 x pbar^T + 2 (pbar.x) I + 2 pbar x^T + 2 p0 x~            */
static int EPConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  const double *x = N_VGetArrayPointer(q), *p = x + 3, *pb = p + 1;
  double R[9], pxx[3], px = pb[0] * x[0] + pb[1] * x[1] + pb[2] * x[2];
  double xt[9];
  int i, j;
  (void)t; (void)ud;
  ep_rotation(p, R);
  Cross(pb, x, pxx);
  Tilde(x, xt);
  for (i = 0; i < 3; i++) {
    for (j = 0; j < 3; j++) ELEM(B, i, j) = -R[3 * j + i];
    ELEM(B, i, 3) = -(2.0 * p[0] * x[i] - 2.0 * pxx[i]);
    for (j = 0; j < 3; j++)
      ELEM(B, i, 4 + j) = -(-2.0 * x[i] * pb[j] + (i == j ? 2.0 * px : 0.0) +
                            2.0 * pb[i] * x[j] + 2.0 * p[0] * xt[3 * i + j]);
  }
  for (j = 0; j < 4; j++) ELEM(B, 3, 3 + j) = 2.0 * p[j];
  return 0;
}

/* K_t = d/dq [M(q) qddot + g(q, qdot) + B(q)^T lambda]. With l = lambda[0..2],
 * mu = lambda[3], w = pddot and S(q) = l . R(p)^T x = x . R(p) l:
 *   B^T lambda = [-R(p) l ; -dS/dp + 2 mu p],
 *   D := d(R(p) l)/dp = [2 p0 l - 2 l x pbar | -2 l pbar^T + 2 pbar l^T + 2 (l.pbar) I - 2 p0 l~],
 *   d2S/dp2 = [[2 x.l, -2 (x x l)^T], [-2 x x l, -2 (x.l) I + 2 (x l^T + l x^T)]],
 *   d/dp [4 G^T J G w]       = 4 H(J G w) - 4 G^T J G(w),
 *   d/dp [8 G(pdot)^T J G pdot] = -8 G(pdot)^T J G(pdot),
 * K_t = [[0, -D], [-D^T, -d2S/dp2 + 2 mu I + 4 H(J G w) - 4 G^T J G(w)
 *                        - 8 G(pdot)^T J G(pdot)]]  (x enters only through B). */
static int EPStiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                       N_Vector lambda, SUNMatrix K, void *ud)
{
  const double *x = N_VGetArrayPointer(q), *p = x + 3, *pb = p + 1;
  const double *pd = N_VGetArrayPointer(v) + 3, *w = N_VGetArrayPointer(vdot) + 3;
  const double *l = N_VGetArrayPointer(lambda);
  const double lx = Dot(l, x), lp = Dot(l, pb);
  double G[12], Gd[12], Gw[12], c[3], lxp[3], xxl[3], lt[9], Kpp[16];
  int i, j;
  (void)t; (void)ud;

  /* -D and -D^T */
  Cross(l, pb, lxp);
  Tilde(l, lt);
  for (i = 0; i < 3; i++) {
    ELEM(K, i, 3) = ELEM(K, 3, i) = -(2.0 * p[0] * l[i] - 2.0 * lxp[i]);
    for (j = 0; j < 3; j++)
      ELEM(K, i, 4 + j) = ELEM(K, 4 + j, i) =
          -(-2.0 * l[i] * pb[j] + 2.0 * pb[i] * l[j] + (i == j ? 2.0 * lp : 0.0) -
            2.0 * p[0] * lt[3 * i + j]);
  }

  /* -d2S/dp2 + 2 mu I */
  Cross(x, l, xxl);
  Kpp[0] = -2.0 * lx;
  for (i = 0; i < 3; i++) {
    Kpp[1 + i] = Kpp[4 * (1 + i)] = 2.0 * xxl[i];
    for (j = 0; j < 3; j++)
      Kpp[4 * (1 + i) + 1 + j] = (i == j ? 2.0 * lx : 0.0) - 2.0 * (x[i] * l[j] + l[i] * x[j]);
  }
  for (i = 0; i < 4; i++) Kpp[5 * i] += 2.0 * l[3];

  /* inertial terms */
  ep_matrix_g(p, G);
  ep_matrix_g(pd, Gd);
  ep_matrix_g(w, Gw);
  ep_g_vec(G, w, c);
  for (i = 0; i < 3; i++) c[i] *= J_BODY[i];
  ep_add_h(c, 4.0, Kpp);
  ep_add_gt_j_g(G, J_BODY, Gw, -4.0, Kpp);
  ep_add_gt_j_g(Gd, J_BODY, Gd, -8.0, Kpp);

  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) ELEM(K, 3 + i, 3 + j) = Kpp[4 * i + j];
  return 0;
}

/* C_t = dg/dqdot: only g_p = 8 G(pdot)^T J G(p) pdot depends on qdot,
 *   C_t = diag(0, 8 H(J G pdot) + 8 G(pdot)^T J G). */
static int EPDamping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  const double *p = N_VGetArrayPointer(q) + 3, *pd = N_VGetArrayPointer(v) + 3;
  double G[12], Gd[12], c[3], Cpp[16] = {0.0};
  int i, j;
  (void)t; (void)ud;
  ep_matrix_g(p, G);
  ep_matrix_g(pd, Gd);
  ep_g_vec(G, pd, c);
  for (i = 0; i < 3; i++) c[i] *= J_BODY[i];
  ep_add_h(c, 8.0, Cpp);
  ep_add_gt_j_g(Gd, J_BODY, G, 8.0, Cpp);
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) ELEM(C, 3 + i, 3 + j) = Cpp[4 * i + j];
  return 0;
}

/* Z(q)(qdot, qdot) = (d/dq (B(q) qdot)) qdot = d^2/de^2 Phi(q + e qdot) at 0.
 * Phi is X - Q(p, p)^T x (cubic) and p^T p - 1, so
 *   Z = [-(2 Q(pdot, pdot)^T x + 4 Q(p, pdot)^T xdot) ; 2 pdot^T pdot]. */
static int EPCurvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  const double *x = N_VGetArrayPointer(q), *p = x + 3;
  const double *xd = N_VGetArrayPointer(v), *pd = xd + 3;
  double *zz = N_VGetArrayPointer(z), a[3], b[3];
  int i;
  (void)t; (void)ud;
  EPQuadTVec(pd, pd, x, a);
  EPQuadTVec(p, pd, xd, b);
  for (i = 0; i < 3; i++) zz[i] = -(2.0 * a[i] + 4.0 * b[i]);
  zz[3] = 2.0 * (pd[0] * pd[0] + pd[1] * pd[1] + pd[2] * pd[2] + pd[3] * pd[3]);
  return 0;
}

/* =============================================================================
 * The callbacks of each formulation
 * ===========================================================================*/

typedef struct {
  LGNMassFn mass;
  LGNForceFn force;
  LGNConstrFn constr;
  LGNConstrJacFn constr_jac;
  LGNStiffnessFn stiffness; /* the analytic tangents (analytic_jacobians) */
  LGNDampingFn damping;
  LGNCurvatureFn curvature;
} ModelCallbacks;

static const ModelCallbacks LIE_CALLBACKS = {
    LieMass, LieForce, LieConstr, LieConstrJac, LieStiffness, LieDamping, LieCurvature};
static const ModelCallbacks SE3_CALLBACKS = {
    LieMass, SE3Force, LieConstr, SE3ConstrJac, SE3Stiffness, SE3Damping, SE3Curvature};
static const ModelCallbacks EP_CALLBACKS = {
    EPMass, EPForce, EPConstr, EPConstrJac, EPStiffness, EPDamping, EPCurvature};

static const ModelCallbacks *Callbacks(HeavyTopFormulation f)
{
  return f == HT_EULER_PARAMETERS ? &EP_CALLBACKS : f == HT_SE3 ? &SE3_CALLBACKS
                                                                : &LIE_CALLBACKS;
}

/* =============================================================================
 * Check of the analytic tangents against central differences
 * ===========================================================================*/

/* Uniform in [-1, 1) from a 64-bit LCG (Knuth's MMIX constants): the same
 * states on every platform. */
static double RandomUniform(unsigned long long *s)
{
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return 2.0 * (double)(*s >> 11) / 9007199254740992.0 - 1.0;
}

/* max |a - b| / max(|a|, |b|) over n entries (0 if both vanish) */
static double RelDiff(const double *a, const double *b, int n)
{
  double d = 0.0, s = 0.0;
  int i;
  for (i = 0; i < n; i++) {
    d = fmax(d, fabs(a[i] - b[i]));
    s = fmax(s, fmax(fabs(a[i]), fabs(b[i])));
  }
  return d == 0.0 ? 0.0 : d / s;
}

/* Objects of one check, freed together. */
typedef struct {
  SUNContext ctx;
  LGNGroup G;
  N_Vector q, v, vdot, lambda, qe, ve, g, z;
  SUNMatrix M, B, T;
} CheckObjects;

static void FreeCheck(CheckObjects *o)
{
  N_Vector *vec[] = {&o->q, &o->v, &o->vdot, &o->lambda, &o->qe, &o->ve, &o->g, &o->z};
  SUNMatrix *mat[] = {&o->M, &o->B, &o->T};
  size_t i;
  for (i = 0; i < sizeof vec / sizeof vec[0]; i++)
    if (*vec[i]) N_VDestroy(*vec[i]);
  for (i = 0; i < sizeof mat / sizeof mat[0]; i++)
    if (*mat[i]) SUNMatDestroy(*mat[i]);
  LGNGroup_Destroy(o->G);
  if (o->ctx) SUNContext_Free(&o->ctx);
}

/* qe = q o exp(s w) */
static int Displace(CheckObjects *o, const double *w, double s, int nv)
{
  double sw[7];
  int i;
  for (i = 0; i < nv; i++) sw[i] = s * w[i];
  return LGNGroup_ComposeExp(o->G, N_VGetArrayPointer(o->q), sw, N_VGetArrayPointer(o->qe));
}

/* r = M(qe) vdot + g(qe, v) + B(qe)^T lambda (nv) */
static int DynamicResidual(const ModelCallbacks *cb, CheckObjects *o, int nv, int m,
                           double *r)
{
  const double *vd = N_VGetArrayPointer(o->vdot), *l = N_VGetArrayPointer(o->lambda);
  const double *g = N_VGetArrayPointer(o->g);
  int i, j, ret;
  SUNMatZero(o->M);
  SUNMatZero(o->B);
  N_VConst(0.0, o->g);
  ret = cb->mass(0.0, o->qe, o->M, NULL);
  if (ret == 0) ret = cb->force(0.0, o->qe, o->v, o->g, NULL);
  if (ret == 0) ret = cb->constr_jac(0.0, o->qe, o->B, NULL);
  if (ret != 0) return ret;
  for (i = 0; i < nv; i++) {
    r[i] = g[i];
    for (j = 0; j < nv; j++) r[i] += ELEM(o->M, i, j) * vd[j];
    for (j = 0; j < m; j++) r[i] += ELEM(o->B, j, i) * l[j];
  }
  return 0;
}

/* y = B(qe) v (m) */
static int ConstraintVelocity(const ModelCallbacks *cb, CheckObjects *o, int nv, int m,
                              double *y)
{
  const double *v = N_VGetArrayPointer(o->v);
  int i, j, ret;
  SUNMatZero(o->B);
  ret = cb->constr_jac(0.0, o->qe, o->B, NULL);
  for (i = 0; i < m; i++) {
    y[i] = 0.0;
    for (j = 0; j < nv; j++) y[i] += ELEM(o->B, i, j) * v[j];
  }
  return ret;
}

/* Column-major copy of the dense matrix A (rows x cols) */
static void CopyDense(SUNMatrix A, int rows, int cols, double *out)
{
  int i, j;
  for (j = 0; j < cols; j++)
    for (i = 0; i < rows; i++) out[i + rows * j] = ELEM(A, i, j);
}

int heavy_top_check_jacobians(HeavyTopFormulation formulation, unsigned int seed,
                              HeavyTopJacobianErrors *err)
{
  const ModelCallbacks *cb = Callbacks(formulation);
  const int ep = formulation == HT_EULER_PARAMETERS;
  const int nv = ep ? 7 : 6, m = ep ? 4 : 3;
  /* central differences of unit-size data: error ~ eps^2 + DBL_EPSILON / eps */
  const double eps = cbrt(DBL_EPSILON);
  unsigned long long s = 0x9e3779b97f4a7c15ULL ^ seed;
  double *q, *v, *vd, *l, w[7], nrm, R[9];
  double an[49], dq[49], yp[7], ym[7];
  CheckObjects o;
  int i, j, ret;

  memset(&o, 0, sizeof o);
  memset(err, 0, sizeof *err);
  if (SUNContext_Create(NULL, &o.ctx) != 0) return -1;
  o.G = ep ? LGNGroup_Rn(7) : formulation == HT_SE3 ? LGNGroup_SE3() : LGNGroup_R3xSO3();
  o.q = N_VNew_Serial(7, o.ctx);
  o.qe = N_VNew_Serial(7, o.ctx);
  o.v = N_VNew_Serial(nv, o.ctx);
  o.ve = N_VNew_Serial(nv, o.ctx);
  o.vdot = N_VNew_Serial(nv, o.ctx);
  o.g = N_VNew_Serial(nv, o.ctx);
  o.lambda = N_VNew_Serial(m, o.ctx);
  o.z = N_VNew_Serial(m, o.ctx);
  o.M = SUNDenseMatrix(nv, nv, o.ctx);
  o.T = SUNDenseMatrix(nv, nv, o.ctx);
  o.B = SUNDenseMatrix(m, nv, o.ctx);
  if (!o.G || !o.q || !o.qe || !o.v || !o.ve || !o.vdot || !o.g || !o.lambda || !o.z ||
      !o.M || !o.T || !o.B) {
    FreeCheck(&o);
    return -1;
  }

  /* random state: unit p; x anywhere for Euler parameters, but x = R X for
   * the Lie group models, whose B uses the constant -X~ for -(R^T x)~ (exact
   * on the joint manifold only); v, vdot, lambda in [-1, 1) */
  q = N_VGetArrayPointer(o.q);
  v = N_VGetArrayPointer(o.v);
  vd = N_VGetArrayPointer(o.vdot);
  l = N_VGetArrayPointer(o.lambda);
  do {
    for (i = 0; i < 4; i++) q[3 + i] = RandomUniform(&s);
    nrm = sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]);
  } while (nrm < 0.1);
  for (i = 0; i < 4; i++) q[3 + i] /= nrm;
  for (i = 0; i < 3; i++) q[i] = RandomUniform(&s);
  if (!ep) {
    LGNQuaternionToRotation(q + 3, R);
    for (i = 0; i < 3; i++)
      q[i] = R[3 * i] * X_BODY[0] + R[3 * i + 1] * X_BODY[1] + R[3 * i + 2] * X_BODY[2];
  }
  for (i = 0; i < nv; i++) v[i] = RandomUniform(&s);
  for (i = 0; i < nv; i++) vd[i] = RandomUniform(&s);
  for (i = 0; i < m; i++) l[i] = RandomUniform(&s);

  /* B w = d/de Phi(q o exp(e w)) */
  ret = cb->constr_jac(0.0, o.q, o.B, NULL);
  CopyDense(o.B, m, nv, an);
  for (j = 0; ret == 0 && j < nv; j++) {
    memset(w, 0, sizeof w);
    w[j] = eps;
    ret = Displace(&o, w, 1.0, nv);
    if (ret == 0) ret = cb->constr(0.0, o.qe, o.z, NULL);
    memcpy(yp, N_VGetArrayPointer(o.z), (size_t)m * sizeof(double));
    if (ret == 0) ret = Displace(&o, w, -1.0, nv);
    if (ret == 0) ret = cb->constr(0.0, o.qe, o.z, NULL);
    for (i = 0; i < m; i++) dq[i + m * j] = (yp[i] - N_VGetArrayPointer(o.z)[i]) / (2.0 * eps);
  }
  err->B = RelDiff(an, dq, m * nv);

  /* K_t w = d/de r(q o exp(e w)), r = M vdot + g + B^T lambda */
  if (ret == 0) {
    SUNMatZero(o.T);
    ret = cb->stiffness(0.0, o.q, o.v, o.vdot, o.lambda, o.T, NULL);
    CopyDense(o.T, nv, nv, an);
  }
  for (j = 0; ret == 0 && j < nv; j++) {
    memset(w, 0, sizeof w);
    w[j] = eps;
    ret = Displace(&o, w, 1.0, nv);
    if (ret == 0) ret = DynamicResidual(cb, &o, nv, m, yp);
    if (ret == 0) ret = Displace(&o, w, -1.0, nv);
    if (ret == 0) ret = DynamicResidual(cb, &o, nv, m, ym);
    for (i = 0; i < nv; i++) dq[i + nv * j] = (yp[i] - ym[i]) / (2.0 * eps);
  }
  err->K = RelDiff(an, dq, nv * nv);

  /* C_t w = d/de g(q, v + e w) */
  if (ret == 0) {
    SUNMatZero(o.T);
    ret = cb->damping(0.0, o.q, o.v, o.T, NULL);
    CopyDense(o.T, nv, nv, an);
  }
  for (j = 0; ret == 0 && j < nv; j++) {
    const double *g = N_VGetArrayPointer(o.g);
    double *ve = N_VGetArrayPointer(o.ve);
    memcpy(ve, v, (size_t)nv * sizeof(double));
    ve[j] = v[j] + eps;
    N_VConst(0.0, o.g);
    ret = cb->force(0.0, o.q, o.ve, o.g, NULL);
    memcpy(yp, g, (size_t)nv * sizeof(double));
    ve[j] = v[j] - eps;
    N_VConst(0.0, o.g);
    if (ret == 0) ret = cb->force(0.0, o.q, o.ve, o.g, NULL);
    for (i = 0; i < nv; i++) dq[i + nv * j] = (yp[i] - g[i]) / (2.0 * eps);
  }
  err->C = RelDiff(an, dq, nv * nv);

  /* Z(q)(v, v) = d/de B(q o exp(e v)) v */
  if (ret == 0) ret = cb->curvature(0.0, o.q, o.v, o.z, NULL);
  if (ret == 0) ret = Displace(&o, v, eps, nv);
  if (ret == 0) ret = ConstraintVelocity(cb, &o, nv, m, yp);
  if (ret == 0) ret = Displace(&o, v, -eps, nv);
  if (ret == 0) ret = ConstraintVelocity(cb, &o, nv, m, ym);
  for (i = 0; i < m; i++) dq[i] = (yp[i] - ym[i]) / (2.0 * eps);
  err->Z = RelDiff(N_VGetArrayPointer(o.z), dq, m);

  FreeCheck(&o);
  return ret == 0 ? 0 : -1;
}

/* =============================================================================
 * Driver
 * ===========================================================================*/

void heavy_top_default_options(HeavyTopOptions *opt)
{
  memset(opt, 0, sizeof *opt);
  opt->formulation        = HT_LIE;
  opt->method             = HT_GENALPHA;
  opt->rho_inf            = 0.9;
  opt->beta               = 0.25;
  opt->gamma              = 0.5;
  opt->constraints        = LGN_CONSTR_INDEX3;
  opt->kinematics         = LGN_KINEMATICS_SIMPLIFIED;
  opt->newton             = LGN_NEWTON_FULL;
  opt->predictor          = LGN_PREDICTOR_ZERO;
  opt->h                  = 1e-3;
  opt->t_end              = 1.0;
  opt->analytic_jacobians = 1;
}

void heavy_top_describe(const HeavyTopOptions *opt, char *buf, size_t len)
{
  const char *kin = opt->kinematics == LGN_KINEMATICS_EXACT   ? "mod. "
                    : opt->kinematics == LGN_KINEMATICS_SIGMA ? "sigma-"
                                                              : "";
  const char *grp = opt->formulation == HT_SE3 ? "SE3 " : "";
  const char *idx = opt->constraints == LGN_CONSTR_INDEX2 ? "idx2"
                    : opt->constraints == LGN_CONSTR_GGL  ? "GGL"
                                                          : "idx3";
  if (opt->formulation == HT_EULER_PARAMETERS) {
    if (opt->method == HT_GENALPHA)
      snprintf(buf, len, "EP gen-alpha(%.2g) %s", opt->rho_inf, idx);
    else
      snprintf(buf, len, "EP Newmark(%.4g,%.4g) %s", opt->beta, opt->gamma, idx);
  } else if (opt->method == HT_GENALPHA) {
    snprintf(buf, len, "%s%sLGGalpha(%.2g) %s", grp, kin, opt->rho_inf, idx);
  } else {
    snprintf(buf, len, "%s%sLGNM(%.4g,%.4g) %s", grp, kin, opt->beta, opt->gamma, idx);
  }
}

/* The state in Lie group variables, for either formulation. */
static void ExtractState(const HeavyTopOptions *opt, const double *q,
                         const double *v, const double *vdot, const double *a,
                         HeavyTopResult *res)
{
  int i;
  double nrm;
  for (i = 0; i < 3; i++) {
    res->x[i] = q[i];
    res->u[i] = v[i];
    res->vdot[i] = vdot[i];
    res->a[i] = a[i];
  }
  nrm = sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]);
  for (i = 0; i < 4; i++) res->p[i] = (q[3] >= 0.0 ? 1.0 : -1.0) * q[3 + i] / nrm;
  LGNQuaternionToRotation(res->p, res->R);
  if (opt->formulation == HT_LIE || opt->formulation == HT_SE3) {
    for (i = 0; i < 3; i++) {
      res->Omega[i] = v[3 + i];
      res->vdot[3 + i] = vdot[3 + i];
      res->a[3 + i] = a[3 + i];
    }
  } else {
    /* Omega = 2 G(p) pdot; Omegadot = 2 G(p) pddot since Gdot pdot = 0 */
    double G[12];
    int k;
    ep_matrix_g(q + 3, G);
    for (k = 0; k < 3; k++) {
      res->Omega[k] = res->vdot[3 + k] = res->a[3 + k] = 0.0;
      for (i = 0; i < 4; i++) {
        res->Omega[k] += 2.0 * G[4 * k + i] * v[3 + i];
        res->vdot[3 + k] += 2.0 * G[4 * k + i] * vdot[3 + i];
        res->a[3 + k] += 2.0 * G[4 * k + i] * a[3 + i];
      }
    }
  }
  if (opt->formulation == HT_SE3) {
    /* body-fixed (U, Udot) -> inertial u = R U, udot = R (Udot + Omega x U);
     * the algorithmic a_U is mapped like Udot, R (a_U + Omega x U). */
    const double *R = res->R;
    double WxU[3], bu[3], bd[3], ba[3];
    Cross(v + 3, v, WxU);
    for (i = 0; i < 3; i++) {
      bu[i] = v[i];
      bd[i] = vdot[i] + WxU[i];
      ba[i] = a[i] + WxU[i];
    }
    for (i = 0; i < 3; i++) {
      res->u[i] = R[3 * i] * bu[0] + R[3 * i + 1] * bu[1] + R[3 * i + 2] * bu[2];
      res->vdot[i] = R[3 * i] * bd[0] + R[3 * i + 1] * bd[1] + R[3 * i + 2] * bd[2];
      res->a[i] = R[3 * i] * ba[0] + R[3 * i + 1] * ba[1] + R[3 * i + 2] * ba[2];
    }
  }
}

/* |X - R^T x|_inf of the raw state q (R from the unnormalised quaternion,
 * as in the constraint callbacks of the Lie group formulations). */
static double JointViolation(const HeavyTopOptions *opt, const double *q)
{
  double R[9], Rtx[3], mx = 0.0;
  int i;
  if (opt->formulation == HT_EULER_PARAMETERS)
    ep_rotation(q + 3, R);
  else
    LGNQuaternionToRotation(q + 3, R);
  MatTVec(R, q, Rtx);
  for (i = 0; i < 3; i++) mx = fmax(mx, fabs(X_BODY[i] - Rtx[i]));
  return mx;
}

static void WriteCsvRow(FILE *fp, const HeavyTopResult *r)
{
  fprintf(fp, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
              "%.17g,%.17g,%.17g,%.17g\n",
          r->t, r->x[0], r->x[1], r->x[2], r->p[0], r->p[1], r->p[2], r->p[3],
          r->Omega[0], r->Omega[1], r->Omega[2], r->lambda[0], r->lambda[1],
          r->lambda[2]);
}

/* Objects of one run, freed together. */
typedef struct {
  SUNContext ctx;
  LGNGroup G;
  N_Vector q, v, vdot, a, lambda, tmpl;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
} RunObjects;

static void FreeRun(RunObjects *o)
{
  LGNFree(&o->mem);
  if (o->LS) SUNLinSolFree(o->LS);
  if (o->A) SUNMatDestroy(o->A);
  if (o->q) N_VDestroy(o->q);
  if (o->v) N_VDestroy(o->v);
  if (o->vdot) N_VDestroy(o->vdot);
  if (o->a) N_VDestroy(o->a);
  if (o->lambda) N_VDestroy(o->lambda);
  if (o->tmpl) N_VDestroy(o->tmpl);
  LGNGroup_Destroy(o->G);
  if (o->ctx) SUNContext_Free(&o->ctx);
}

/* Set up model, method and linear solver; returns a Lignum flag. */
static int SetupRun(const HeavyTopOptions *opt, RunObjects *o)
{
  const ModelCallbacks *cb = Callbacks(opt->formulation);
  const int ep = opt->formulation == HT_EULER_PARAMETERS;
  const int se3 = opt->formulation == HT_SE3;
  const sunindextype nv = ep ? 7 : 6, m = ep ? 4 : 3;
  double *q, *v;
  int flag;

  if (SUNContext_Create(NULL, &o->ctx) != 0) return LGN_MEM_FAIL;
  o->G = ep ? LGNGroup_Rn(7) : se3 ? LGNGroup_SE3() : LGNGroup_R3xSO3();
  o->q = N_VNew_Serial(7, o->ctx);
  o->v = N_VNew_Serial(nv, o->ctx);
  o->vdot = N_VNew_Serial(nv, o->ctx);
  o->a = N_VNew_Serial(nv, o->ctx);
  o->lambda = N_VNew_Serial(m, o->ctx);
  /* nv + 2m rows under GGL (the multipliers lambda and mu) */
  const sunindextype n = nv + (opt->constraints == LGN_CONSTR_GGL ? 2 * m : m);
  o->A = SUNDenseMatrix(n, n, o->ctx);
  o->tmpl = N_VNew_Serial(n, o->ctx); /* template of the linear solver */
  o->LS = (o->A && o->tmpl) ? (opt->make_ls != NULL ? opt->make_ls : SUNLinSol_Dense)(
                                  o->tmpl, o->A, o->ctx)
                            : NULL;
  o->mem = LGNCreate(o->ctx);
  if (!o->G || !o->q || !o->v || !o->vdot || !o->a || !o->lambda || !o->LS || !o->mem)
    return LGN_MEM_FAIL;

  /* initial state: R0 = I, x0 = X, u0 = Omega0 x X, p0 = (1,0,0,0);
   * on SE(3) U0 = R0^T u0 = Omega0 x X, the same numbers since R0 = I */
  q = N_VGetArrayPointer(o->q);
  v = N_VGetArrayPointer(o->v);
  memset(q, 0, 7 * sizeof(double));
  memset(v, 0, (size_t)nv * sizeof(double));
  q[1] = X_BODY[1];
  q[3] = 1.0;
  v[0] = -HT_OMEGA0_Z; /* (Omega0 x X)_x = -Omega_z for X = e_y */
  if (ep) {
    /* pdot0 = G(p0)^T Omega0 / 2 with G(1,0,0,0) = [0 | I] */
    v[4] = 0.0;
    v[5] = 0.5 * HT_OMEGA0_Y;
    v[6] = 0.5 * HT_OMEGA0_Z;
  } else {
    v[4] = HT_OMEGA0_Y;
    v[5] = HT_OMEGA0_Z;
  }

  flag = LGNSetGroup(o->mem, o->G);
  if (flag == 0) flag = LGNSetMassFn(o->mem, cb->mass);
  if (flag == 0) flag = LGNSetForceFn(o->mem, cb->force);
  if (flag == 0) flag = LGNSetConstraints(o->mem, m, cb->constr, cb->constr_jac);
  if (flag == 0 && opt->analytic_jacobians) {
    flag = LGNSetStiffnessFn(o->mem, cb->stiffness);
    if (flag == 0) flag = LGNSetDampingFn(o->mem, cb->damping);
    if (flag == 0) flag = LGNSetCurvatureFn(o->mem, cb->curvature);
  }
  if (flag == 0) flag = LGNInit(o->mem, 0.0, o->q, o->v);
  if (flag == 0) flag = LGNSetLinearSolver(o->mem, o->LS, o->A);
  if (flag == 0)
    flag = opt->method == HT_GENALPHA ? LGNSetGenAlpha(o->mem, opt->rho_inf)
                                      : LGNSetNewmark(o->mem, opt->beta, opt->gamma);
  if (flag == 0) flag = LGNSetConstraintIndex(o->mem, opt->constraints);
  if (flag == 0 && opt->bdf_maxord == 0) flag = LGNSetKinematics(o->mem, opt->kinematics);
  if (flag == 0 && opt->bdf_maxord > 0) flag = LGNSetBDF(o->mem, opt->bdf_maxord);
  if (flag == 0) flag = LGNSetStepSize(o->mem, opt->h);
  if (flag == 0 && (opt->rtol > 0.0 || opt->atol > 0.0 || opt->adaptive))
    flag = LGNSStolerances(o->mem, opt->rtol, opt->atol);
  if (flag == 0 && opt->adaptive) {
    flag = LGNSetStepControl(o->mem, LGN_STEP_ADAPTIVE);
    if (flag == 0) flag = LGNSetStopTime(o->mem, opt->t_end);
  }
  if (flag == 0 && opt->max_steps > 0) flag = LGNSetMaxNumSteps(o->mem, opt->max_steps);
  /* the heavy top's studies measure the method itself: the step's own
   * vdot_n and lambda_n, and the step's q, v (not the consistent and
   * projected outputs of LGNSetConsistentOutputs / LGNSetProjectOutputs) */
  if (flag == 0) flag = LGNSetConsistentOutputs(o->mem, SUNFALSE);
  if (flag == 0) flag = LGNSetProjectOutputs(o->mem, LGN_PROJECT_NONE);
  if (flag == 0) flag = LGNSetPredictor(o->mem, opt->predictor);
  if (flag == 0) flag = LGNSetNewtonMode(o->mem, opt->newton);
  if (flag == 0) flag = LGNSetLSetupFrequency(o->mem, opt->msbp);
  if (flag == 0 && opt->zero_a0) {
    N_VConst(0.0, o->a);
    flag = LGNSetInitialAux(o->mem, o->a);
  }
  return flag;
}

/* Fill res from the integrator's current state. */
static void Collect(const HeavyTopOptions *opt, RunObjects *o, double t,
                    HeavyTopResult *res)
{
  LGNGetAcceleration(o->mem, o->vdot);
  LGNGetAuxAcceleration(o->mem, o->a);
  LGNGetMultipliers(o->mem, o->lambda);
  res->t = t;
  ExtractState(opt, N_VGetArrayPointer(o->q), N_VGetArrayPointer(o->v),
               N_VGetArrayPointer(o->vdot), N_VGetArrayPointer(o->a), res);
  memcpy(res->lambda, N_VGetArrayPointer(o->lambda), 3 * sizeof(double));
  res->max_phi = fmax(res->max_phi, JointViolation(opt, N_VGetArrayPointer(o->q)));
}

static void RecordHistory(const HeavyTopOptions *opt, HeavyTopResult *res)
{
  if (opt->com_history != NULL && res->history_points < opt->history_len) {
    memcpy(opt->com_history + 3 * res->history_points, res->x, 3 * sizeof(double));
    res->history_points++;
  }
  if (opt->csv != NULL) WriteCsvRow(opt->csv, res);
}

int heavy_top_run(const HeavyTopOptions *opt, HeavyTopResult *res)
{
  RunObjects o;
  double t = 0.0, tout;
  clock_t c0;
  long int k, nsteps;
  int flag;

  memset(&o, 0, sizeof o);
  memset(res, 0, sizeof *res);
  flag = SetupRun(opt, &o);
  if (flag == 0 && opt->csv != NULL)
    fprintf(opt->csv, "t,x,y,z,p0,p1,p2,p3,Omega1,Omega2,Omega3,lambda1,lambda2,lambda3\n");

  nsteps = (opt->h > 0.0) ? (long int)ceil(opt->t_end / opt->h - 1e-9) : 0;
  c0 = clock();
  if (opt->single_solve) {
    /* consistent accelerations and all steps in one call */
    const int ready = flag == 0;
    if (ready) flag = LGNSolve(o.mem, opt->t_end, &t, o.q, o.v, LGN_NORMAL);
    if (flag == LGN_TSTOP_RETURN) flag = 0; /* at t_end */
    res->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (ready) Collect(opt, &o, t, res);
  } else {
    /* the initial state (consistent accelerations after a zero-length solve) */
    if (flag == 0) flag = LGNSolve(o.mem, 0.0, &t, o.q, o.v, LGN_NORMAL);
    if (flag == 0) {
      Collect(opt, &o, t, res);
      RecordHistory(opt, res);
    }
    for (k = 1; flag == 0 && k <= nsteps; k++) {
      tout = (double)k * opt->h;
      if (tout > opt->t_end) tout = opt->t_end;
      flag = LGNSolve(o.mem, tout, &t, o.q, o.v, LGN_NORMAL);
      if (flag == LGN_TSTOP_RETURN) flag = 0; /* at t_end */
      Collect(opt, &o, t, res);
      if (flag == 0) RecordHistory(opt, res);
    }
    res->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
  }
  res->flag = flag;
  if (o.mem != NULL) {
    LGNGetNumSteps(o.mem, &res->nsteps);
    LGNGetNumNewtonIters(o.mem, &res->nniters);
    LGNGetNumResEvals(o.mem, &res->nres);
    LGNGetNumDQEvals(o.mem, &res->ndq);
    LGNGetNumJacEvals(o.mem, &res->njevals);
    LGNGetNumLinSolves(o.mem, &res->nlsolves);
    LGNGetNumLinSolvSetups(o.mem, &res->nlsetups);
    LGNGetNumErrTestFails(o.mem, &res->netfails);
    LGNGetNumNewtonConvFails(o.mem, &res->nncfails);
    LGNGetNumNewtonStalls(o.mem, &res->nstall);
  }
  FreeRun(&o);
  return flag;
}
