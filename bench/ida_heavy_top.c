/* -----------------------------------------------------------------------------
 * Lignum benchmarks: the heavy top as a stabilised index-2 (GGL) DAE in Euler
 * parameters for SUNDIALS IDA (see ida_heavy_top.h for the equations).
 *
 * The model formulas are those of HT_EULER_PARAMETERS in
 * models/heavy_top.c (doc/accuracy-study.md), written out again here
 * together with their second derivatives, which IDA's analytic Jacobian
 * needs:  with G(p) = [-pbar, -pbar~ + p0 I] (linear in p, G(p) p = 0, hence
 * G(p) a = -G(a) p), and H(c) defined by G(d)^T c = H(c) d,
 * H(c) = [[0, -c^T], [c, -c~]]:
 *
 *   d/dp [4 G(p)^T J G(p) w]      = 4 H(J G(p) w) - 4 G(p)^T J G(w)
 *   d/dp [8 G(pd)^T J G(p) pd]    = -8 G(pd)^T J G(pd)
 *   d/dpd[8 G(pd)^T J G(p) pd]    = 8 (H(J G(p) pd) + G(pd)^T J G(p))
 *
 * and for the joint, with s(x, p) = R(p)^T x and S_l = l . s, Phi = X - s,
 * B_joint = -ds/dq, so d(B^T l)/dq = -Hess(S_l) + 2 l_4 diag(0, I_4) and the
 * row i of d(B v)/dq is -(Hess(S_{e_i}) v)^T.  Hess(S_l) is in HessS().
 * The analytic Jacobian is checked against difference quotients by
 * ida_heavy_top_check_jacobian() (CTest bench_work_precision_quick).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include "ida_heavy_top.h"

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

#include "models/euler_parameters.h"
#include "models/heavy_top.h" /* HT_MASS, HT_J*, HT_GRAVITY, HT_OMEGA0_* */

#define N   IDAHT_N
#define OQ  IDAHT_OQ
#define OV  IDAHT_OV
#define OL  IDAHT_OL
#define OM  IDAHT_OM

static const double X_BODY[3] = {0.0, 1.0, 0.0};
static const double J_BODY[3] = {HT_J1, HT_J2, HT_J3};

/* =============================================================================
 * Model pieces
 * ===========================================================================*/

/* Phi(q) (4) */
static void Constraints(const double *q, double phi[4])
{
  const double *p = q + 3;
  double R[9];
  int i;
  ep_rotation(p, R);
  for (i = 0; i < 3; i++)
    phi[i] = X_BODY[i] - (R[i] * q[0] + R[3 + i] * q[1] + R[6 + i] * q[2]);
  phi[3] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1.0;
}

/* B = dPhi/dq, 4 x 7 row-major (as EPConstrJac) */
static void ConstraintJac(const double *q, double B[28])
{
  const double *x = q, *p = q + 3, *pb = p + 1;
  const double px = pb[0] * x[0] + pb[1] * x[1] + pb[2] * x[2];
  double R[9], pxx[3];
  int i, j;
  ep_rotation(p, R);
  pxx[0] = pb[1] * x[2] - pb[2] * x[1];
  pxx[1] = pb[2] * x[0] - pb[0] * x[2];
  pxx[2] = pb[0] * x[1] - pb[1] * x[0];
  for (i = 0; i < 3; i++) {
    double xt[3]; /* row i of x~ */
    xt[0] = i == 0 ? 0.0 : i == 1 ? x[2] : -x[1];
    xt[1] = i == 0 ? -x[2] : i == 1 ? 0.0 : x[0];
    xt[2] = i == 0 ? x[1] : i == 1 ? -x[0] : 0.0;
    for (j = 0; j < 3; j++) B[7 * i + j] = -R[3 * j + i];
    B[7 * i + 3] = -(2.0 * p[0] * x[i] - 2.0 * pxx[i]);
    for (j = 0; j < 3; j++)
      B[7 * i + 4 + j] = -(-2.0 * x[i] * pb[j] + (i == j ? 2.0 * px : 0.0) +
                           2.0 * pb[i] * x[j] + 2.0 * p[0] * xt[j]);
  }
  for (j = 0; j < 3; j++) B[21 + j] = 0.0;
  for (j = 0; j < 4; j++) B[21 + 3 + j] = 2.0 * p[j];
}

/* Hessian of S_l(q) = l . R(p)^T x, 7 x 7 row-major, symmetric:
 *   xx = 0,  x-p0 = 2 p0 l - 2 l x pbar,
 *   x-pbar = -2 l pbar^T + 2 pbar l^T + 2 (l.pbar) I - 2 p0 l~,
 *   p0p0 = 2 l.x,  p0-pbar = -2 x x l,  pbar-pbar = -2 (l.x) I + 2 (l x^T + x l^T). */
static void HessS(const double *q, const double l[3], double H[49])
{
  const double *x = q, p0 = q[3], *pb = q + 4;
  const double lx = l[0] * x[0] + l[1] * x[1] + l[2] * x[2];
  const double lp = l[0] * pb[0] + l[1] * pb[1] + l[2] * pb[2];
  double lxp[3], xxl[3], lt[9];
  int i, j;
  lxp[0] = l[1] * pb[2] - l[2] * pb[1];
  lxp[1] = l[2] * pb[0] - l[0] * pb[2];
  lxp[2] = l[0] * pb[1] - l[1] * pb[0];
  xxl[0] = x[1] * l[2] - x[2] * l[1];
  xxl[1] = x[2] * l[0] - x[0] * l[2];
  xxl[2] = x[0] * l[1] - x[1] * l[0];
  lt[0] = 0.0;   lt[1] = -l[2]; lt[2] = l[1];
  lt[3] = l[2];  lt[4] = 0.0;   lt[5] = -l[0];
  lt[6] = -l[1]; lt[7] = l[0];  lt[8] = 0.0;
  memset(H, 0, 49 * sizeof(double));
  for (i = 0; i < 3; i++) {
    H[7 * i + 3] = H[7 * 3 + i] = 2.0 * p0 * l[i] - 2.0 * lxp[i];
    for (j = 0; j < 3; j++) {
      const double v = -2.0 * l[i] * pb[j] + 2.0 * pb[i] * l[j] +
                       (i == j ? 2.0 * lp : 0.0) - 2.0 * p0 * lt[3 * i + j];
      H[7 * i + 4 + j] = H[7 * (4 + j) + i] = v;
    }
  }
  H[7 * 3 + 3] = 2.0 * lx;
  for (j = 0; j < 3; j++) H[7 * 3 + 4 + j] = H[7 * (4 + j) + 3] = -2.0 * xxl[j];
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++)
      H[7 * (4 + i) + 4 + j] =
          (i == j ? -2.0 * lx : 0.0) + 2.0 * (l[i] * x[j] + x[i] * l[j]);
}

/* M vd + g for the rotational part: 4 G^T J G w + 8 G(pd)^T J G pd (4) */
static void RotDynamics(const double *p, const double *pd, const double *w, double out[4])
{
  double G[12], Gd[12], c[3], e[3];
  int i, k;
  ep_matrix_g(p, G);
  ep_matrix_g(pd, Gd);
  ep_g_vec(G, w, c);
  ep_g_vec(G, pd, e);
  for (k = 0; k < 3; k++) {
    c[k] *= J_BODY[k];
    e[k] *= J_BODY[k];
  }
  for (i = 0; i < 4; i++)
    out[i] = 4.0 * (G[i] * c[0] + G[4 + i] * c[1] + G[8 + i] * c[2]) +
             8.0 * (Gd[i] * e[0] + Gd[4 + i] * e[1] + Gd[8 + i] * e[2]);
}

/* Mass matrix of the rotational part, 4 G^T J G (4x4) */
static void RotMass(const double *p, double Mp[16])
{
  double G[12];
  memset(Mp, 0, 16 * sizeof(double));
  ep_matrix_g(p, G);
  ep_add_gt_j_g(G, J_BODY, G, 4.0, Mp);
}

/* F(t, y, y'), all 22 components */
static void Residual(const double *y, const double *yp, double *F)
{
  const double *q = y + OQ, *v = y + OV, *l = y + OL, *mu = y + OM;
  const double *qd = yp + OQ, *vd = yp + OV;
  double B[28], rot[4];
  int i, j;
  ConstraintJac(q, B);
  for (i = 0; i < 7; i++) {
    double btm = 0.0, btl = 0.0;
    for (j = 0; j < 4; j++) {
      btm += B[7 * j + i] * mu[j];
      btl += B[7 * j + i] * l[j];
    }
    F[OQ + i] = qd[i] - v[i] - btm;
    F[OV + i] = btl;
  }
  for (i = 0; i < 3; i++) F[OV + i] += HT_MASS * vd[i];
  F[OV + 2] -= HT_MASS * HT_GRAVITY;
  RotDynamics(q + 3, v + 3, vd + 3, rot);
  for (i = 0; i < 4; i++) F[OV + 3 + i] += rot[i];
  Constraints(q, F + OL);
  for (i = 0; i < 4; i++) {
    double s = 0.0;
    for (j = 0; j < 7; j++) s += B[7 * i + j] * v[j];
    F[OM + i] = s;
  }
}

/* d(B v)/dq, 4 x 7 row-major */
static void DBvDq(const double *q, const double *v, double D[28])
{
  double H[49];
  int i, j, k;
  for (i = 0; i < 3; i++) {
    double e[3] = {0.0, 0.0, 0.0};
    e[i] = 1.0;
    HessS(q, e, H);
    for (k = 0; k < 7; k++) {
      double s = 0.0;
      for (j = 0; j < 7; j++) s += H[7 * k + j] * v[j];
      D[7 * i + k] = -s;
    }
  }
  for (k = 0; k < 3; k++) D[21 + k] = 0.0;
  for (k = 0; k < 4; k++) D[21 + 3 + k] = 2.0 * v[3 + k];
}

/* Full Jacobian dF/dy + cj dF/dy', dense row-major N x N into Jd. */
static void Jacobian(double cj, const double *y, const double *yp, double *Jd)
{
  const double *q = y + OQ, *v = y + OV, *l = y + OL, *mu = y + OM;
  const double *p = q + 3, *pd = v + 3, *w = yp + OV + 3;
  double B[28], H[49], D[28], G[12], Gd[12], Gw[12], c[3], Mp[16], K[16], C[16];
  int i, j;
#define JD(r, cc) Jd[(r) * N + (cc)]
  memset(Jd, 0, N * N * sizeof(double));
  ConstraintJac(q, B);
  ep_matrix_g(p, G);
  ep_matrix_g(pd, Gd);
  ep_matrix_g(w, Gw);

  /* F_q = q' - v - B^T mu */
  HessS(q, mu, H);
  for (i = 0; i < 7; i++) {
    for (j = 0; j < 7; j++) JD(OQ + i, OQ + j) = H[7 * i + j];
    JD(OQ + i, OQ + i) += cj;
    JD(OQ + i, OV + i) = -1.0;
    for (j = 0; j < 4; j++) JD(OQ + i, OM + j) = -B[7 * j + i];
  }
  for (i = 3; i < 7; i++) JD(OQ + i, OQ + i) -= 2.0 * mu[3];

  /* F_v = M v' + g + B^T lambda */
  HessS(q, l, H);
  for (i = 0; i < 7; i++) {
    for (j = 0; j < 7; j++) JD(OV + i, OQ + j) = -H[7 * i + j];
    for (j = 0; j < 4; j++) JD(OV + i, OL + j) = B[7 * j + i];
  }
  for (i = 3; i < 7; i++) JD(OV + i, OQ + i) += 2.0 * l[3];
  /* K = d/dp [4 G^T J G w + 8 G(pd)^T J G pd] */
  memset(K, 0, sizeof K);
  ep_g_vec(G, w, c);
  for (i = 0; i < 3; i++) c[i] *= J_BODY[i];
  ep_add_h(c, 4.0, K);
  ep_add_gt_j_g(G, J_BODY, Gw, -4.0, K);
  ep_add_gt_j_g(Gd, J_BODY, Gd, -8.0, K);
  /* C = d/dpd [8 G(pd)^T J G pd] */
  memset(C, 0, sizeof C);
  ep_g_vec(G, pd, c);
  for (i = 0; i < 3; i++) c[i] *= J_BODY[i];
  ep_add_h(c, 8.0, C);
  ep_add_gt_j_g(Gd, J_BODY, G, 8.0, C);
  RotMass(p, Mp);
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) {
      JD(OV + 3 + i, OQ + 3 + j) += K[4 * i + j];
      JD(OV + 3 + i, OV + 3 + j) = cj * Mp[4 * i + j] + C[4 * i + j];
    }
  for (i = 0; i < 3; i++) JD(OV + i, OV + i) = cj * HT_MASS;

  /* Phi = 0 and B v = 0 */
  DBvDq(q, v, D);
  for (i = 0; i < 4; i++)
    for (j = 0; j < 7; j++) {
      JD(OL + i, OQ + j) = B[7 * i + j];
      JD(OM + i, OQ + j) = D[7 * i + j];
      JD(OM + i, OV + j) = B[7 * i + j];
    }
#undef JD
}

/* Structural pattern of Jacobian() (for the CSC matrix), row-major N x N. */
static void Pattern(unsigned char *P)
{
  int i, j;
  memset(P, 0, N * N);
#define MARK(r0, c0, nr, nc)                                   \
  for (i = (r0); i < (r0) + (nr); i++)                         \
    for (j = (c0); j < (c0) + (nc); j++) P[i * N + j] = 1
  /* F_q: d/dq (Hessian: all but the xx block, plus cj I), -I, -B^T */
  MARK(OQ, OQ + 3, 7, 4);
  MARK(OQ + 3, OQ, 4, 3);
  for (i = 0; i < 7; i++) P[(OQ + i) * N + OQ + i] = P[(OQ + i) * N + OV + i] = 1;
  MARK(OQ, OM, 3, 3);
  MARK(OQ + 3, OM, 4, 4);
  /* F_v: d/dq, M cj + C, B^T */
  MARK(OV, OQ + 3, 3, 4);
  MARK(OV + 3, OQ, 4, 7);
  for (i = 0; i < 3; i++) P[(OV + i) * N + OV + i] = 1;
  MARK(OV + 3, OV + 3, 4, 4);
  MARK(OV, OL, 3, 3);
  MARK(OV + 3, OL, 4, 4);
  /* Phi: B;  B v: d(Bv)/dq and B */
  MARK(OL, OQ, 3, 7);
  MARK(OL + 3, OQ + 3, 1, 4);
  MARK(OM, OQ, 3, 7);
  MARK(OM + 3, OQ + 3, 1, 4);
  MARK(OM, OV, 3, 7);
  MARK(OM + 3, OV + 3, 1, 4);
#undef MARK
}

/* =============================================================================
 * IDA callbacks
 * ===========================================================================*/

typedef struct {
  double Jd[N * N];
  unsigned char P[N * N];
  sunindextype nnz;
} UserData;

static int ResFn(sunrealtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *ud)
{
  (void)t; (void)ud;
  Residual(N_VGetArrayPointer(yy), N_VGetArrayPointer(yp), N_VGetArrayPointer(rr));
  return 0;
}

static int JacDense(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yp,
                    N_Vector rr, SUNMatrix Jac, void *ud, N_Vector t1,
                    N_Vector t2, N_Vector t3)
{
  UserData *u = ud;
  int i, j;
  (void)t; (void)rr; (void)t1; (void)t2; (void)t3;
  Jacobian(cj, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp), u->Jd);
  for (j = 0; j < N; j++) {
    sunrealtype *col = SUNDenseMatrix_Column(Jac, j);
    for (i = 0; i < N; i++) col[i] = u->Jd[i * N + j];
  }
  return 0;
}

static int JacSparse(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yp,
                     N_Vector rr, SUNMatrix Jac, void *ud, N_Vector t1,
                     N_Vector t2, N_Vector t3)
{
  UserData *u = ud;
  sunindextype *cp = SUNSparseMatrix_IndexPointers(Jac);
  sunindextype *ri = SUNSparseMatrix_IndexValues(Jac);
  sunrealtype *d = SUNSparseMatrix_Data(Jac);
  sunindextype k = 0;
  int i, j;
  (void)t; (void)rr; (void)t1; (void)t2; (void)t3;
  Jacobian(cj, N_VGetArrayPointer(yy), N_VGetArrayPointer(yp), u->Jd);
  /* the whole structure every time: SUNMatZero also zeroes the indices */
  for (j = 0; j < N; j++) {
    cp[j] = k;
    for (i = 0; i < N; i++)
      if (u->P[i * N + j]) {
        ri[k] = i;
        d[k++] = u->Jd[i * N + j];
      }
  }
  cp[N] = k;
  return 0;
}

/* =============================================================================
 * Initial values: q0, v0 as in heavy_top.c (R0 = I, x0 = X, u0 = Omega0 x X,
 * pdot0 = G(p0)^T Omega0 / 2); [M B^T; B 0] [vd0; lambda0] = [-g; -Z],
 * Z = d(Bv)/dq v; mu0 = 0, q'0 = v0.
 * ===========================================================================*/

/* Solve A x = b (n x n row-major, overwritten) by Gaussian elimination with
 * partial pivoting; returns 0, or 1 if singular. */
static int SolveDense(int n, double *A, double *b)
{
  int i, j, k;
  for (k = 0; k < n; k++) {
    int piv = k;
    for (i = k + 1; i < n; i++)
      if (fabs(A[i * n + k]) > fabs(A[piv * n + k])) piv = i;
    if (A[piv * n + k] == 0.0) return 1;
    if (piv != k) {
      for (j = 0; j < n; j++) {
        double tmp = A[k * n + j];
        A[k * n + j] = A[piv * n + j];
        A[piv * n + j] = tmp;
      }
      {
        double tmp = b[k];
        b[k] = b[piv];
        b[piv] = tmp;
      }
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

int ida_heavy_top_initial(double *y0, double *yp0, double *res_norm)
{
  double *q = y0 + OQ, *v = y0 + OV;
  double A[11 * 11], b[11], B[28], D[28], Mp[16], rot[4], F[N];
  const double zero[4] = {0.0, 0.0, 0.0, 0.0};
  int i, j;
  memset(y0, 0, N * sizeof(double));
  memset(yp0, 0, N * sizeof(double));
  q[1] = X_BODY[1];
  q[3] = 1.0;
  v[0] = -HT_OMEGA0_Z;
  v[5] = 0.5 * HT_OMEGA0_Y;
  v[6] = 0.5 * HT_OMEGA0_Z;

  ConstraintJac(q, B);
  DBvDq(q, v, D);
  RotMass(q + 3, Mp);
  RotDynamics(q + 3, v + 3, zero, rot); /* g_rot */
  memset(A, 0, sizeof A);
  for (i = 0; i < 3; i++) A[11 * i + i] = HT_MASS;
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++) A[11 * (3 + i) + 3 + j] = Mp[4 * i + j];
  for (i = 0; i < 4; i++)
    for (j = 0; j < 7; j++) A[11 * (7 + i) + j] = A[11 * j + 7 + i] = B[7 * i + j];
  b[0] = b[1] = 0.0;
  b[2] = HT_MASS * HT_GRAVITY;
  for (i = 0; i < 4; i++) b[3 + i] = -rot[i];
  for (i = 0; i < 4; i++) {
    double z = 0.0;
    for (j = 0; j < 7; j++) z += D[7 * i + j] * v[j];
    b[7 + i] = -z;
  }
  if (SolveDense(11, A, b) != 0) return 1;
  for (i = 0; i < 7; i++) {
    yp0[OQ + i] = v[i];
    yp0[OV + i] = b[i];
  }
  for (i = 0; i < 4; i++) y0[OL + i] = b[7 + i];
  Residual(y0, yp0, F);
  *res_norm = 0.0;
  for (i = 0; i < N; i++) *res_norm = fmax(*res_norm, fabs(F[i]));
  return 0;
}

double ida_heavy_top_check_jacobian(double cj)
{
  static double Ja[N * N];
  double y[N], yp[N], Fp[N], Fm[N], rn, scale = 0.0, err = 0.0;
  int i, j;
  if (ida_heavy_top_initial(y, yp, &rn) != 0) return INFINITY;
  /* a generic state: perturb everything (incl. unit-norm p, mu != 0) */
  for (i = 0; i < N; i++) {
    y[i] += 0.1 * sin(1.0 + 2.7 * i) * (i >= OV && i < OL ? 10.0 : 1.0);
    yp[i] += 0.3 * cos(0.5 + 1.3 * i);
  }
  Jacobian(cj, y, yp, Ja);
  for (j = 0; j < N; j++) {
    const double yj = y[j], ypj = yp[j];
    const double d = 1e-6 * (1.0 + fabs(yj));
    y[j] = yj + d;
    yp[j] = ypj + cj * d; /* y' moves with c_j along the BDF corrector */
    Residual(y, yp, Fp);
    y[j] = yj - d;
    yp[j] = ypj - cj * d;
    Residual(y, yp, Fm);
    y[j] = yj;
    yp[j] = ypj;
    for (i = 0; i < N; i++) {
      const double dq = (Fp[i] - Fm[i]) / (2.0 * d);
      err = fmax(err, fabs(dq - Ja[i * N + j]));
      scale = fmax(scale, fabs(Ja[i * N + j]));
    }
  }
  return err / (1.0 + scale);
}

/* =============================================================================
 * Driver
 * ===========================================================================*/

void ida_heavy_top_default_options(IdaHTOptions *opt)
{
  memset(opt, 0, sizeof *opt);
  opt->linsol = IDAHT_DENSE_JAC;
  opt->rtol = 1e-6;
  opt->t_end = 1.0;
}

const char *ida_heavy_top_linsol_name(IdaHTLinSol ls)
{
  return ls == IDAHT_DENSE_DQ ? "dense-DQ" : ls == IDAHT_DENSE_JAC ? "dense-Jac" : "KLU";
}

static double Or(double v, double def) { return v > 0.0 ? v : def; }

int ida_heavy_top_run(const IdaHTOptions *opt, IdaHTResult *res)
{
  SUNContext ctx = NULL;
  N_Vector y = NULL, yp = NULL, id = NULL, atol = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  UserData *ud = NULL;
  double *yy, *pp, *ii, *aa, rn, tret = 0.0, phi[4];
  clock_t c0;
  int flag = -100, i;

  memset(res, 0, sizeof *res);
  res->flag = -100;
  if (SUNContext_Create(NULL, &ctx) != 0) return -100;
  ud = calloc(1, sizeof *ud);
  y = N_VNew_Serial(N, ctx);
  yp = N_VNew_Serial(N, ctx);
  id = N_VNew_Serial(N, ctx);
  atol = N_VNew_Serial(N, ctx);
  if (!ud || !y || !yp || !id || !atol) goto done;
  yy = N_VGetArrayPointer(y);
  pp = N_VGetArrayPointer(yp);
  ii = N_VGetArrayPointer(id);
  aa = N_VGetArrayPointer(atol);
  if (ida_heavy_top_initial(yy, pp, &rn) != 0) goto done;
  for (i = 0; i < N; i++) {
    double s;
    ii[i] = i < OL ? 1.0 : 0.0;
    if (i < 3) s = Or(opt->scale_x, 1.0);
    else if (i < OV) s = Or(opt->scale_p, 1.0);
    else if (i < OV + 3) s = Or(opt->scale_xd, 5.0);
    else if (i < OL) s = Or(opt->scale_pd, 75.0);
    else if (i < OM) s = Or(opt->scale_lambda, 1e3);
    else s = Or(opt->scale_mu, 1.0);
    aa[i] = opt->rtol * s;
  }

  Pattern(ud->P);
  ud->nnz = 0;
  for (i = 0; i < N * N; i++) ud->nnz += ud->P[i];
  if (opt->linsol == IDAHT_KLU) {
    A = SUNSparseMatrix(N, N, ud->nnz, CSC_MAT, ctx);
    LS = A ? SUNLinSol_KLU(y, A, ctx) : NULL;
  } else {
    A = SUNDenseMatrix(N, N, ctx);
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
  if (flag == 0 && opt->maxord > 0) flag = IDASetMaxOrd(mem, opt->maxord);
  if (flag == 0 && opt->h0 > 0.0) flag = IDASetInitStep(mem, opt->h0);
  if (flag == 0 && opt->epcon > 0.0) flag = IDASetNonlinConvCoef(mem, opt->epcon);
  if (flag == 0 && opt->dcj > 0.0) flag = IDASetDeltaCjLSetup(mem, opt->dcj);
  if (flag == 0 && opt->maxcor > 0) flag = IDASetMaxNonlinIters(mem, opt->maxcor);
  if (flag == 0) flag = IDASetLinearSolver(mem, LS, A);
  if (flag == 0 && opt->no_ls_scaling) flag = IDASetLinearSolutionScaling(mem, SUNFALSE);
  if (flag == 0 && opt->linsol != IDAHT_DENSE_DQ)
    flag = IDASetJacFn(mem, opt->linsol == IDAHT_KLU ? JacSparse : JacDense);
  if (flag != 0) goto done;

  c0 = clock();
  flag = IDASolve(mem, opt->t_end, &tret, y, yp, IDA_NORMAL);
  res->cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
  res->t = tret;
  for (i = 0; i < 3; i++) res->x[i] = yy[OQ + i];
  for (i = 0; i < 4; i++) res->p[i] = yy[OQ + 3 + i];
  Constraints(yy + OQ, phi);
  for (i = 0; i < 4; i++) res->max_phi_end = fmax(res->max_phi_end, fabs(phi[i]));
  {
    long int nre = 0, nreLS = 0;
    IDAGetNumSteps(mem, &res->nsteps);
    IDAGetNumNonlinSolvIters(mem, &res->nniters);
    IDAGetNumResEvals(mem, &nre);
    IDAGetNumLinResEvals(mem, &nreLS);
    res->nres = nre + nreLS;
    IDAGetNumJacEvals(mem, &res->njevals);
    IDAGetNumErrTestFails(mem, &res->netf);
    IDAGetNumNonlinSolvConvFails(mem, &res->nncf);
  }

done:
  res->flag = flag;
  IDAFree(&mem);
  if (LS) SUNLinSolFree(LS);
  if (A) SUNMatDestroy(A);
  if (y) N_VDestroy(y);
  if (yp) N_VDestroy(yp);
  if (id) N_VDestroy(id);
  if (atol) N_VDestroy(atol);
  free(ud);
  if (ctx) SUNContext_Free(&ctx);
  return flag;
}
