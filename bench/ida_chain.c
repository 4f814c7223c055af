/* -----------------------------------------------------------------------------
 * Lignum benchmarks: the N-body chain as a stabilised index-2 (GGL) DAE in
 * Euler parameters for SUNDIALS IDA (equations in ida_chain.h).
 *
 * With R(p) = (p0^2 - pbar.pbar) I + 2 pbar pbar^T + 2 p0 pbar~
 * (models/euler_parameters.h), the derivative of a body point R(p) s is
 *   d(R s)/dp0   = 2 p0 s + 2 pbar x s,
 *   d(R s)/dpbar = -2 s pbar^T + 2 (pbar.s) I + 2 pbar s^T - 2 p0 s~,
 * checked against central differences of Phi by
 * ida_chain_check_constraint_jacobian() (CTest bench_work_precision_quick).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include "ida_chain.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "models/chain.h"
#include "models/euler_parameters.h"

#define MAXN IDACH_MAXN
#define HALF_L 0.5 /* rods of 1 m (chain.c) */

static const double TOP[3] = {0.0, 0.0, HALF_L}, BOTTOM[3] = {0.0, 0.0, -HALF_L};

typedef struct {
  int n;
  double mass[MAXN], J[3 * MAXN], gravity[3];
} Chain;

/* offsets in y for n bodies */
#define OQ(n) 0
#define OV(n) (7 * (n))
#define OL(n) (14 * (n))
#define OM(n) (18 * (n))

/* =============================================================================
 * Model pieces
 * ===========================================================================*/

/* P = x + R(p) s and D = d(R(p) s)/dp (3 x 4 row-major) */
static void BodyPoint(const double *q, const double s[3], double P[3], double D[12])
{
  const double *p = q + 3, *pb = q + 4;
  const double ps = pb[0] * s[0] + pb[1] * s[1] + pb[2] * s[2];
  double R[9], pxs[3];
  int i, j;
  ep_rotation(p, R);
  for (i = 0; i < 3; i++) P[i] = q[i] + R[3 * i] * s[0] + R[3 * i + 1] * s[1] + R[3 * i + 2] * s[2];
  if (D == NULL) return;
  pxs[0] = pb[1] * s[2] - pb[2] * s[1];
  pxs[1] = pb[2] * s[0] - pb[0] * s[2];
  pxs[2] = pb[0] * s[1] - pb[1] * s[0];
  for (i = 0; i < 3; i++) {
    double st[3]; /* row i of s~ */
    st[0] = i == 0 ? 0.0 : i == 1 ? s[2] : -s[1];
    st[1] = i == 0 ? -s[2] : i == 1 ? 0.0 : s[0];
    st[2] = i == 0 ? s[1] : i == 1 ? -s[0] : 0.0;
    D[4 * i] = 2.0 * p[0] * s[i] + 2.0 * pxs[i];
    for (j = 0; j < 3; j++)
      D[4 * i + 1 + j] = -2.0 * s[i] * pb[j] + (i == j ? 2.0 * ps : 0.0) + 2.0 * pb[i] * s[j] -
                         2.0 * p[0] * st[j];
  }
}

/* Phi(q) (4 n) and, if B != NULL, B = dPhi/dq (4 n x 7 n row-major, dense) */
static void Constraints(const Chain *c, const double *q, double *phi, double *B)
{
  const int n = c->n, nq = 7 * n;
  double Pa[3], Pb[3], Da[12], Db[12];
  int j, i, k;
  if (B != NULL) memset(B, 0, (size_t)(4 * n * nq) * sizeof(double));
  for (j = 0; j < n; j++) {
    if (j == 0) Pa[0] = Pa[1] = Pa[2] = 0.0;
    else BodyPoint(q + 7 * (j - 1), BOTTOM, Pa, B ? Da : NULL);
    BodyPoint(q + 7 * j, TOP, Pb, B ? Db : NULL);
    for (i = 0; i < 3; i++) {
      phi[3 * j + i] = Pa[i] - Pb[i];
      if (B == NULL) continue;
      if (j > 0) {
        double *row = B + (size_t)(3 * j + i) * nq + 7 * (j - 1);
        row[i] = 1.0;
        for (k = 0; k < 4; k++) row[3 + k] = Da[4 * i + k];
      }
      {
        double *row = B + (size_t)(3 * j + i) * nq + 7 * j;
        row[i] = -1.0;
        for (k = 0; k < 4; k++) row[3 + k] = -Db[4 * i + k];
      }
    }
  }
  for (j = 0; j < n; j++) {
    const double *p = q + 7 * j + 3;
    phi[3 * n + j] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1.0;
    if (B != NULL)
      for (k = 0; k < 4; k++) B[(size_t)(3 * n + j) * nq + 7 * j + 3 + k] = 2.0 * p[k];
  }
}

/* 4 G(p)^T J G(p) w + 8 G(pd)^T J G(p) pd (4) */
static void RotDynamics(const double J[3], const double *p, const double *pd, const double *w,
                        double out[4])
{
  double G[12], Gd[12], a[3], e[3];
  int i, k;
  ep_matrix_g(p, G);
  ep_matrix_g(pd, Gd);
  ep_g_vec(G, w, a);
  ep_g_vec(G, pd, e);
  for (k = 0; k < 3; k++) {
    a[k] *= J[k];
    e[k] *= J[k];
  }
  for (i = 0; i < 4; i++)
    out[i] = 4.0 * (G[i] * a[0] + G[4 + i] * a[1] + G[8 + i] * a[2]) +
             8.0 * (Gd[i] * e[0] + Gd[4 + i] * e[1] + Gd[8 + i] * e[2]);
}

/* F(t, y, y') (22 n); B is work space (4 n x 7 n) */
static void Residual(const Chain *c, const double *y, const double *yp, double *F, double *B)
{
  const int n = c->n, nq = 7 * n, nl = 4 * n;
  const double *q = y + OQ(n), *v = y + OV(n), *l = y + OL(n), *mu = y + OM(n);
  const double *qd = yp + OQ(n), *vd = yp + OV(n);
  int i, j, k;
  Constraints(c, q, F + OL(n), B);
  for (i = 0; i < nq; i++) {
    double btm = 0.0, btl = 0.0;
    for (j = 0; j < nl; j++) {
      const double b = B[(size_t)j * nq + i];
      btm += b * mu[j];
      btl += b * l[j];
    }
    F[OQ(n) + i] = qd[i] - v[i] - btm;
    F[OV(n) + i] = btl;
  }
  for (k = 0; k < n; k++) {
    double rot[4];
    for (i = 0; i < 3; i++)
      F[OV(n) + 7 * k + i] += c->mass[k] * (vd[7 * k + i] - c->gravity[i]);
    RotDynamics(c->J + 3 * k, q + 7 * k + 3, v + 7 * k + 3, vd + 7 * k + 3, rot);
    for (i = 0; i < 4; i++) F[OV(n) + 7 * k + 3 + i] += rot[i];
  }
  for (j = 0; j < nl; j++) {
    double s = 0.0;
    for (i = 0; i < nq; i++) s += B[(size_t)j * nq + i] * v[i];
    F[OM(n) + j] = s;
  }
}

/* =============================================================================
 * Analytic Jacobian dF/dy + c_j dF/dy'.  l . R(p) s = p^T A(l, s) p with
 *   A00 = l.s,  A0m = Am0 = (s x l)_m,  Amm' = -(l.s) delta + l_m s_m' + s_m l_m',
 * so the Hessian of l . Phi_joint in p is +-2 A(l, s) (zero in x), that of
 * the norm 2 I; the rotational dynamics' derivatives are those of
 * ida_heavy_top.c (K and C).
 * ===========================================================================*/

static void AddA(const double l[3], const double s[3], double f, double *J, int ld)
{
  const double ls = l[0] * s[0] + l[1] * s[1] + l[2] * s[2];
  double sxl[3];
  int m, k;
  sxl[0] = s[1] * l[2] - s[2] * l[1];
  sxl[1] = s[2] * l[0] - s[0] * l[2];
  sxl[2] = s[0] * l[1] - s[1] * l[0];
  J[0] += f * ls;
  for (m = 0; m < 3; m++) {
    J[1 + m] += f * sxl[m];
    J[(size_t)(1 + m) * ld] += f * sxl[m];
    for (k = 0; k < 3; k++)
      J[(size_t)(1 + m) * ld + 1 + k] += f * ((m == k ? -ls : 0.0) + l[m] * s[k] + s[m] * l[k]);
  }
}

/* J[rows of q or v, cols of q] += f * sum_r w_r Hess(Phi_r) (ld = row stride) */
static void AddWeightedHessian(const Chain *c, const double *w, double f, double *J, int ld)
{
  const int n = c->n;
  int j, k;
  for (j = 0; j < n; j++) {
    if (j > 0) AddA(w + 3 * j, BOTTOM, 2.0 * f, J + (size_t)(7 * (j - 1) + 3) * ld + 7 * (j - 1) + 3, ld);
    AddA(w + 3 * j, TOP, -2.0 * f, J + (size_t)(7 * j + 3) * ld + 7 * j + 3, ld);
  }
  for (j = 0; j < n; j++)
    for (k = 0; k < 4; k++) J[(size_t)(7 * j + 3 + k) * ld + 7 * j + 3 + k] += 2.0 * f * w[3 * n + j];
}

static void Jacobian(const Chain *c, double cj, const double *y, const double *yp, double *Jd,
                     double *B)
{
  const int n = c->n, ny = 22 * n, nq = 7 * n, nl = 4 * n;
  const double *q = y + OQ(n), *v = y + OV(n), *l = y + OL(n), *mu = y + OM(n);
  double phi[4 * MAXN];
  int i, j, k;
#define JD(r, cc) Jd[(size_t)(r) * ny + (cc)]
  memset(Jd, 0, (size_t)ny * ny * sizeof(double));
  Constraints(c, q, phi, B);
  /* F_q = q' - v - B^T mu */
  AddWeightedHessian(c, mu, -1.0, &JD(OQ(n), OQ(n)), ny);
  for (i = 0; i < nq; i++) {
    JD(OQ(n) + i, OQ(n) + i) += cj;
    JD(OQ(n) + i, OV(n) + i) = -1.0;
    for (j = 0; j < nl; j++) JD(OQ(n) + i, OM(n) + j) = -B[j * nq + i];
  }
  /* F_v = M v' + g + B^T lambda */
  AddWeightedHessian(c, l, 1.0, &JD(OV(n), OQ(n)), ny);
  for (i = 0; i < nq; i++)
    for (j = 0; j < nl; j++) JD(OV(n) + i, OL(n) + j) = B[j * nq + i];
  for (k = 0; k < n; k++) {
    const double *p = q + 7 * k + 3, *pd = v + 7 * k + 3, *w = yp + OV(n) + 7 * k + 3;
    const double *Jb = c->J + 3 * k;
    double G[12], Gd[12], Gw[12], a[3], Mp[16], K[16], C[16];
    const int r0 = OV(n) + 7 * k;
    ep_matrix_g(p, G);
    ep_matrix_g(pd, Gd);
    ep_matrix_g(w, Gw);
    memset(K, 0, sizeof K);
    ep_g_vec(G, w, a);
    for (i = 0; i < 3; i++) a[i] *= Jb[i];
    ep_add_h(a, 4.0, K);
    ep_add_gt_j_g(G, Jb, Gw, -4.0, K);
    ep_add_gt_j_g(Gd, Jb, Gd, -8.0, K);
    memset(C, 0, sizeof C);
    ep_g_vec(G, pd, a);
    for (i = 0; i < 3; i++) a[i] *= Jb[i];
    ep_add_h(a, 8.0, C);
    ep_add_gt_j_g(Gd, Jb, G, 8.0, C);
    memset(Mp, 0, sizeof Mp);
    ep_add_gt_j_g(G, Jb, G, 4.0, Mp);
    for (i = 0; i < 4; i++)
      for (j = 0; j < 4; j++) {
        JD(r0 + 3 + i, OQ(n) + 7 * k + 3 + j) += K[4 * i + j];
        JD(r0 + 3 + i, OV(n) + 7 * k + 3 + j) = cj * Mp[4 * i + j] + C[4 * i + j];
      }
    for (i = 0; i < 3; i++) JD(r0 + i, OV(n) + 7 * k + i) = cj * c->mass[k];
  }
  /* Phi = 0: B;  B v = 0: d(Bv)/dq and B */
  for (i = 0; i < nl; i++)
    for (j = 0; j < nq; j++) {
      JD(OL(n) + i, OQ(n) + j) = B[i * nq + j];
      JD(OM(n) + i, OV(n) + j) = B[i * nq + j];
    }
  for (i = 0; i < nl; i++) { /* row i of d(Bv)/dq = v^T Hess(Phi_i) */
    double e[4 * MAXN], H[7 * MAXN * 7 * MAXN];
    memset(e, 0, sizeof e);
    e[i] = 1.0;
    memset(H, 0, (size_t)(nq * nq) * sizeof(double));
    AddWeightedHessian(c, e, 1.0, H, nq);
    for (j = 0; j < nq; j++) {
      double sum = 0.0;
      for (k = 0; k < nq; k++) sum += H[k * nq + j] * v[k];
      JD(OM(n) + i, OQ(n) + j) = sum;
    }
  }
#undef JD
}

typedef struct {
  Chain c;
  double B[4 * MAXN * 7 * MAXN];
  double Jd[22 * MAXN * 22 * MAXN];
  unsigned char P[22 * MAXN * 22 * MAXN]; /* structural pattern (KLU) */
  sunindextype nnz;
} UserData;

static int JacDense(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                    SUNMatrix Jac, void *ud, N_Vector t1, N_Vector t2, N_Vector t3)
{
  UserData *u = ud;
  const int ny = 22 * u->c.n;
  int i, j;
  (void)t; (void)rr; (void)t1; (void)t2; (void)t3;
  Jacobian(&u->c, cj, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp), u->Jd, u->B);
  for (j = 0; j < ny; j++) {
    sunrealtype *col = SUNDenseMatrix_Column(Jac, j);
    for (i = 0; i < ny; i++) col[i] = u->Jd[(size_t)i * ny + j];
  }
  return 0;
}

static int JacSparse(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                     SUNMatrix Jac, void *ud, N_Vector t1, N_Vector t2, N_Vector t3)
{
  UserData *u = ud;
  const int ny = 22 * u->c.n;
  sunindextype *cp = SUNSparseMatrix_IndexPointers(Jac);
  sunindextype *ri = SUNSparseMatrix_IndexValues(Jac);
  sunrealtype *d = SUNSparseMatrix_Data(Jac);
  sunindextype k = 0;
  int i, j;
  (void)t; (void)rr; (void)t1; (void)t2; (void)t3;
  Jacobian(&u->c, cj, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp), u->Jd, u->B);
  for (j = 0; j < ny; j++) {
    cp[j] = k;
    for (i = 0; i < ny; i++)
      if (u->P[(size_t)i * ny + j]) {
        ri[k] = i;
        d[k++] = u->Jd[(size_t)i * ny + j];
      }
  }
  cp[ny] = k;
  return 0;
}

static int ResFn(sunrealtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *ud)
{
  UserData *u = ud;
  (void)t;
  Residual(&u->c, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp), N_VGetArrayPointer(rr), u->B);
  return 0;
}

/* =============================================================================
 * Initial values: Lignum's chain_create() state; v0 = 0, so
 * [M B^T; B 0] [v'0; lambda0] = [-g; 0] with g = -m gravity (no gyroscopic
 * terms at rest); mu0 = 0, q'0 = v0 = 0.
 * ===========================================================================*/

static int SolveDense(int n, double *A, double *b)
{
  int i, j, k;
  for (k = 0; k < n; k++) {
    int piv = k;
    for (i = k + 1; i < n; i++)
      if (fabs(A[i * n + k]) > fabs(A[piv * n + k])) piv = i;
    if (A[piv * n + k] == 0.0) return 1;
    if (piv != k) {
      double tmp;
      for (j = 0; j < n; j++) {
        tmp = A[k * n + j];
        A[k * n + j] = A[piv * n + j];
        A[piv * n + j] = tmp;
      }
      tmp = b[k];
      b[k] = b[piv];
      b[piv] = tmp;
    }
    for (i = k + 1; i < n; i++) {
      const double f = A[i * n + k] / A[k * n + k];
      for (j = k; j < n; j++) A[i * n + j] -= f * A[k * n + j];
      b[i] -= f * b[k];
    }
  }
  for (k = n - 1; k >= 0; k--) {
    double s = b[k];
    for (j = k + 1; j < n; j++) s -= A[k * n + j] * b[j];
    b[k] = s / A[k * n + k];
  }
  return 0;
}

/* The model data and q0 from chain_create(); 0 on success. */
static int ChainSetup(int n, Chain *c, double *q0)
{
  SUNContext ctx = NULL;
  RigidSystem *sys;
  int k;
  if (n < 1 || n > MAXN || SUNContext_Create(NULL, &ctx) != 0) return 1;
  sys = chain_create(n, RB_R3XSO3, ctx);
  if (sys == NULL) {
    SUNContext_Free(&ctx);
    return 1;
  }
  c->n = n;
  for (k = 0; k < n; k++) c->mass[k] = sys->mass[k];
  for (k = 0; k < 3 * n; k++) c->J[k] = sys->inertia[k];
  for (k = 0; k < 3; k++) c->gravity[k] = sys->gravity[k];
  memcpy(q0, N_VGetArrayPointer(sys->q0), (size_t)(7 * n) * sizeof(double));
  rigid_free(&sys);
  SUNContext_Free(&ctx);
  return 0;
}

static int Initial(int n, Chain *c, double *y0, double *yp0, double *res_norm)
{
  const int nq = 7 * n, nl = 4 * n, m = nq + nl, ny = 22 * n;
  static double A[11 * MAXN * 11 * MAXN], B[4 * MAXN * 7 * MAXN];
  double b[11 * MAXN], F[22 * MAXN];
  int i, j, k;
  memset(y0, 0, (size_t)ny * sizeof(double));
  memset(yp0, 0, (size_t)ny * sizeof(double));
  if (ChainSetup(n, c, y0 + OQ(n)) != 0) return 1;
  Constraints(c, y0 + OQ(n), F, B);
  memset(A, 0, (size_t)(m * m) * sizeof(double));
  memset(b, 0, sizeof b);
  for (k = 0; k < n; k++) {
    double G[12], Mp[16];
    for (i = 0; i < 3; i++) {
      A[(7 * k + i) * m + 7 * k + i] = c->mass[k];
      b[7 * k + i] = c->mass[k] * c->gravity[i];
    }
    memset(Mp, 0, sizeof Mp);
    ep_matrix_g(y0 + 7 * k + 3, G);
    ep_add_gt_j_g(G, c->J + 3 * k, G, 4.0, Mp);
    for (i = 0; i < 4; i++)
      for (j = 0; j < 4; j++) A[(7 * k + 3 + i) * m + 7 * k + 3 + j] = Mp[4 * i + j];
  }
  for (i = 0; i < nl; i++)
    for (j = 0; j < nq; j++) A[(nq + i) * m + j] = A[j * m + nq + i] = B[i * nq + j];
  if (SolveDense(m, A, b) != 0) return 1;
  for (i = 0; i < nq; i++) yp0[OV(n) + i] = b[i];
  for (i = 0; i < nl; i++) y0[OL(n) + i] = b[nq + i];
  Residual(c, y0, yp0, F, B);
  *res_norm = 0.0;
  for (i = 0; i < ny; i++) *res_norm = fmax(*res_norm, fabs(F[i]));
  return 0;
}

int ida_chain_initial(int n, double *y0, double *yp0, double *res_norm)
{
  Chain c;
  return Initial(n, &c, y0, yp0, res_norm);
}

double ida_chain_check_constraint_jacobian(int n)
{
  static double B[4 * MAXN * 7 * MAXN], y[22 * MAXN], yp[22 * MAXN];
  double q[7 * MAXN], dq[7 * MAXN], pp[4 * MAXN], pm[4 * MAXN], rn, scale = 0.0, err = 0.0;
  const double e = 1e-6;
  Chain c;
  int i, j;
  memset(q, 0, sizeof q);
  if (Initial(n, &c, y, yp, &rn) != 0) return INFINITY;
  for (i = 0; i < 7 * n; i++) q[i] = y[i] + 0.1 * sin(1.0 + 2.7 * i); /* generic, |p| != 1 */
  Constraints(&c, q, pp, B);
  for (i = 0; i < 7 * n * 4 * n; i++) scale = fmax(scale, fabs(B[i]));
  for (j = 0; j < 7 * n; j++) {
    double qj = q[j];
    memset(dq, 0, sizeof dq);
    q[j] = qj + e;
    Constraints(&c, q, pp, NULL);
    q[j] = qj - e;
    Constraints(&c, q, pm, NULL);
    q[j] = qj;
    for (i = 0; i < 4 * n; i++)
      err = fmax(err, fabs((pp[i] - pm[i]) / (2.0 * e) - B[i * 7 * n + j]));
  }
  return err / (1.0 + scale);
}

/* a generic state (every block nonzero, |p| != 1, mu != 0) near the start */
static void Perturbed(int n, double *y, double *yp)
{
  int i;
  for (i = 0; i < 22 * n; i++) {
    y[i] += 0.1 * sin(1.0 + 2.7 * i) * (i >= OV(n) && i < OL(n) ? 10.0 : 1.0);
    yp[i] += 0.3 * cos(0.5 + 1.3 * i);
  }
}

double ida_chain_check_jacobian(int n, double cj)
{
  static UserData u;
  static double y[22 * MAXN], yp[22 * MAXN], Fp[22 * MAXN], Fm[22 * MAXN];
  const int ny = 22 * n;
  double rn, scale = 0.0, err = 0.0;
  int i, j;
  if (Initial(n, &u.c, y, yp, &rn) != 0) return INFINITY;
  Perturbed(n, y, yp);
  Jacobian(&u.c, cj, y, yp, u.Jd, u.B);
  for (j = 0; j < ny; j++) {
    const double yj = y[j], ypj = yp[j], d = 1e-6 * (1.0 + fabs(yj));
    y[j] = yj + d;
    yp[j] = ypj + cj * d;
    Residual(&u.c, y, yp, Fp, u.B);
    y[j] = yj - d;
    yp[j] = ypj - cj * d;
    Residual(&u.c, y, yp, Fm, u.B);
    y[j] = yj;
    yp[j] = ypj;
    for (i = 0; i < ny; i++) {
      const double a = u.Jd[(size_t)i * ny + j];
      err = fmax(err, fabs((Fp[i] - Fm[i]) / (2.0 * d) - a));
      scale = fmax(scale, fabs(a));
    }
  }
  return err / (1.0 + scale);
}

/* The structural pattern: the nonzeros of the Jacobian at a generic state
 * (its entries are polynomials in y, y', so a generic state misses none). */
static sunindextype Pattern(UserData *u, const double *y0, const double *yp0)
{
  static double y[22 * MAXN], yp[22 * MAXN];
  const int ny = 22 * u->c.n;
  sunindextype nnz = 0;
  int i;
  memcpy(y, y0, (size_t)ny * sizeof(double));
  memcpy(yp, yp0, (size_t)ny * sizeof(double));
  Perturbed(u->c.n, y, yp);
  Jacobian(&u->c, 1.0, y, yp, u->Jd, u->B);
  for (i = 0; i < ny * ny; i++) {
    u->P[i] = u->Jd[i] != 0.0;
    nnz += u->P[i];
  }
  return nnz;
}

const char *ida_chain_linsol_name(IdaChainLinSol ls)
{
  return ls == IDACH_DENSE_DQ ? "dense-DQ" : ls == IDACH_DENSE_JAC ? "dense-Jac" : "KLU";
}

void ida_chain_tip(int n, const double *q, double tip[3])
{
  BodyPoint(q + 7 * (n - 1), BOTTOM, tip, NULL);
}

/* =============================================================================
 * Driver
 * ===========================================================================*/

void ida_chain_default_options(IdaChainOptions *opt)
{
  memset(opt, 0, sizeof *opt);
  opt->n = 3;
  opt->rtol = 1e-6;
  opt->t_end = 1.0;
  opt->h0 = 1e-6;
  opt->linsol = IDACH_DENSE_DQ;
}

int ida_chain_run(const IdaChainOptions *opt, IdaChainResult *res)
{
  const int n = opt->n, ny = 22 * n;
  SUNContext ctx = NULL;
  N_Vector y = NULL, yp = NULL, id = NULL, atol = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  UserData *ud = NULL;
  double *yy, *pp, *ii, *aa, rn, tret = 0.0, phi[4 * MAXN];
  clock_t c0;
  int flag = -100, i;

  memset(res, 0, sizeof *res);
  res->flag = -100;
  if (n < 1 || n > MAXN || SUNContext_Create(NULL, &ctx) != 0) return -100;
  ud = calloc(1, sizeof *ud);
  y = N_VNew_Serial(ny, ctx);
  yp = N_VNew_Serial(ny, ctx);
  id = N_VNew_Serial(ny, ctx);
  atol = N_VNew_Serial(ny, ctx);
  if (!ud || !y || !yp || !id || !atol) goto done;
  yy = N_VGetArrayPointer(y);
  pp = N_VGetArrayPointer(yp);
  ii = N_VGetArrayPointer(id);
  aa = N_VGetArrayPointer(atol);
  if (Initial(n, &ud->c, yy, pp, &rn) != 0) goto done;
  for (i = 0; i < ny; i++) {
    ii[i] = i < OL(n) ? 1.0 : 0.0;
    aa[i] = opt->rtol * (i < OV(n) ? 1.0
                         : i < OL(n) ? (opt->scale_v > 0.0 ? opt->scale_v : 5.0)
                                     : 1e3);
  }
  if (opt->linsol == IDACH_KLU) {
    ud->nnz = Pattern(ud, yy, pp);
    A = SUNSparseMatrix(ny, ny, ud->nnz, CSC_MAT, ctx);
    LS = A ? SUNLinSol_KLU(y, A, ctx) : NULL;
  } else {
    A = SUNDenseMatrix(ny, ny, ctx);
    LS = A ? SUNLinSol_Dense(y, A, ctx) : NULL;
  }
  mem = IDACreate(ctx);
  if (!A || !LS || !mem) goto done;
  flag = IDAInit(mem, ResFn, 0.0, y, yp);
  if (flag == 0) flag = IDASVtolerances(mem, opt->rtol, atol);
  if (flag == 0) flag = IDASetUserData(mem, ud);
  if (flag == 0) flag = IDASetId(mem, id);
  if (flag == 0) flag = IDASetSuppressAlg(mem, SUNTRUE);
  if (flag == 0) flag = IDASetStopTime(mem, opt->t_end);
  if (flag == 0) flag = IDASetMaxNumSteps(mem, opt->max_steps > 0 ? opt->max_steps : 1000000L);
  if (flag == 0 && opt->h0 > 0.0) flag = IDASetInitStep(mem, opt->h0);
  if (flag == 0) flag = IDASetLinearSolver(mem, LS, A);
  if (flag == 0 && opt->linsol != IDACH_DENSE_DQ)
    flag = IDASetJacFn(mem, opt->linsol == IDACH_KLU ? JacSparse : JacDense);
  if (flag != 0) goto done;

  c0 = clock();
  flag = IDASolve(mem, opt->t_end, &tret, y, yp, IDA_NORMAL);
  res->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
  res->t = tret;
  ida_chain_tip(n, yy + OQ(n), res->tip);
  Constraints(&ud->c, yy + OQ(n), phi, NULL);
  for (i = 0; i < 4 * n; i++) res->max_phi_end = fmax(res->max_phi_end, fabs(phi[i]));
  {
    long int nre = 0, nreLS = 0;
    IDAGetNumSteps(mem, &res->nsteps);
    IDAGetNumNonlinSolvIters(mem, &res->nniters);
    IDAGetNumResEvals(mem, &nre);
    IDAGetNumLinResEvals(mem, &nreLS);
    IDAGetNumJacEvals(mem, &res->njevals);
    res->nres = nre + nreLS;
  }

done:
  res->flag = flag;
  if (mem) IDAFree(&mem);
  if (LS) SUNLinSolFree(LS);
  if (A) SUNMatDestroy(A);
  if (y) N_VDestroy(y);
  if (yp) N_VDestroy(yp);
  if (id) N_VDestroy(id);
  if (atol) N_VDestroy(atol);
  free(ud);
  SUNContext_Free(&ctx);
  return flag;
}
