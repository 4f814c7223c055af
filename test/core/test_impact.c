/* -----------------------------------------------------------------------------
 * Lignum test: impacts on constrained systems (LGNApplyImpact,
 * LGNJoints_PointPlaneContact).
 *
 *  (a) a free rigid body (R^3 x SO(3), turned, spinning) whose point hits a
 *      plane: v+ against the closed form of Newton's law (the impulse
 *      j = -(1 + e) v_n / (1/m + r.J^{-1} r), r = s x R^T n), e = 0, 0.5, 1;
 *      P = -j; the contact row against central differences of the gap;
 *  (b) a rod falling flat on a floor, both ends at once (two contacts):
 *      v+ = -e v- exactly, no spin;
 *  (c) a chain of 4 rods on spherical joints, pinned at the top, its tip
 *      hitting a wall and a second rod's end a floor at once: B v+ = 0,
 *      G v+ = -e G v- at each contact, the kinetic energy kept (e = 1) or
 *      reduced by exactly dv^T M dv / 2 (e = 0), the momentum balance
 *      M dv + G^T P in the range of B^T; the integration goes on from v+
 *      (B v = 0 after 0.1 s); dense, and KLU (CSR) against dense for a
 *      chain of 40 (the sparse solve of the impulse system);
 *  (d) bad input refused with the state unchanged: e outside [0, 1],
 *      nc <= 0, G NULL, P of the wrong length, before LGNSolve; two equal
 *      contact rows (a singular system): LGN_LSETUP_FAIL.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

#include "test_util.h"


static char last_msg[1024];
static void Capture(int code, const char *module, const char *fn, const char *msg, void *d)
{
  (void)code; (void)module; (void)d;
  snprintf(last_msg, sizeof last_msg, "%s: %s", fn, msg);
}

/* ---- the model: bodies, joints, contacts (point of body against plane) -- */

#define MAXC 4
typedef struct {
  LGNBodies B;
  LGNJoints J;
  int nc, body[MAXC];
  double s[MAXC][3], n[MAXC][3], d[MAXC];
  int twice; /* (d): the first contact's row twice */
} Model;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t;
  return LGNBodies_Mass(((Model *)ud)->B, q, M);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t;
  return LGNBodies_Force(((Model *)ud)->B, q, v, g);
}
static int Phi(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->J, t, q, phi);
}
static int Jac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->J, t, q, B);
}
static int Curv(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->J, t, q, v, z);
}

/* the contact rows, dense or CSR */
static int Contacts(sunrealtype t, N_Vector q, SUNMatrix G, void *ud)
{
  const Model *md = (const Model *)ud;
  const sunindextype nv = 6 * LGNJoints_NumBodies(md->J);
  double row[6 * 64], gap;
  int c, k, nz = 0;
  (void)t;
  for (c = 0; c < md->nc + md->twice; c++) {
    const int i = c < md->nc ? c : 0;
    if (LGNJoints_PointPlaneContact(md->J, q, md->body[i], md->s[i], md->n[i], md->d[i], &gap,
                                    row) != LGN_SUCCESS)
      return -1;
    if (SUNMatGetID(G) == SUNMATRIX_DENSE) {
      for (k = 0; k < nv; k++) SM_ELEMENT_D(G, c, k) = row[k];
    } else { /* CSR: the body's six entries */
      sunindextype *ptr = SUNSparseMatrix_IndexPointers(G), *ind = SUNSparseMatrix_IndexValues(G);
      sunrealtype *val = SUNSparseMatrix_Data(G);
      ptr[c] = nz;
      for (k = 0; k < 6; k++, nz++) {
        ind[nz] = 6 * md->body[i] + k;
        val[nz] = row[6 * md->body[i] + k];
      }
      ptr[c + 1] = nz;
    }
  }
  return 0;
}

/* ---- the integrator around a model -------------------------------------- */

typedef struct {
  SUNContext ctx;
  void *mem;
  SUNMatrix A;
  SUNLinearSolver LS;
  N_Vector q, v;
  sunindextype m, nv;
} Run;

static int RunCreate(Run *r, Model *md, N_Vector q0, N_Vector v0, int sparse)
{
  const sunindextype n = N_VGetLength(v0) + LGNJoints_NumConstraints(md->J);
  N_Vector y;
  int flag;
  memset(r, 0, sizeof *r);
  SUNContext_Create(NULL, &r->ctx);
  r->m  = LGNJoints_NumConstraints(md->J);
  r->nv = N_VGetLength(v0);
  r->q  = N_VClone(q0);
  r->v  = N_VClone(v0);
  y     = N_VNew_Serial(n, r->ctx);
  if (!sparse) {
    r->A  = SUNDenseMatrix(n, n, r->ctx);
    r->LS = SUNLinSol_Dense(y, r->A, r->ctx);
  } else {
#if defined(LGN_HAVE_KLU)
    r->A  = SUNSparseMatrix(n, n, 40 * n, CSR_MAT, r->ctx);
    r->LS = SUNLinSol_KLU(y, r->A, r->ctx);
#endif
  }
  N_VDestroy(y);
  r->mem = LGNCreate(r->ctx);
  flag   = LGNSetErrHandlerFn(r->mem, Capture, NULL);
  return flag;
}

/* the group is set by the caller (it owns it) */
static int RunSetup(Run *r, Model *md, LGNGroup G, N_Vector q0, N_Vector v0)
{
  int flag = LGNSetGroup(r->mem, G);
  if (!flag) flag = LGNSetUserData(r->mem, md);
  if (!flag) flag = LGNSetMassFn(r->mem, Mass);
  if (!flag) flag = LGNSetForceFn(r->mem, Force);
  if (!flag && r->m > 0) flag = LGNSetConstraints(r->mem, r->m, Phi, Jac);
  if (!flag && r->m > 0) flag = LGNSetCurvatureFn(r->mem, Curv);
  if (!flag) flag = LGNInit(r->mem, 0.0, q0, v0);
  if (!flag) flag = LGNSetLinearSolver(r->mem, r->LS, r->A);
  if (!flag) flag = LGNSetStepSize(r->mem, 1e-3);
  if (!flag) flag = LGNCalcIC(r->mem, LGN_IC_PROJECT_V); /* sets the integrator up */
  if (!flag) flag = LGNGetConsistentIC(r->mem, r->q, r->v);
  return flag;
}

static void RunFree(Run *r)
{
  LGNFree(&r->mem);
  SUNLinSolFree(r->LS);
  SUNMatDestroy(r->A);
  N_VDestroy(r->q);
  N_VDestroy(r->v);
  SUNContext_Free(&r->ctx);
}

static void Rotation(const double *p, double R[9]) { LGNQuaternionToRotation(p, R); }

/* =============================================================================
 * (a) a free body
 * ===========================================================================*/

static void FreeBody(void)
{
  SUNContext ctx;
  LGNGroup G = LGNGroup_R3xSO3();
  Model md;
  Run r;
  const double mass = 2.0, J[3] = {0.1, 0.2, 0.3};
  const double quat[4] = {0.8, 0.2, -0.4, 0.4}; /* normalised below */
  const double u0[3] = {0.3, -1.0, 0.2}, W0[3] = {0.5, -0.2, 0.1};
  double e, *qd, R[9], x[3], Rs[3], row[6], nrm;
  N_Vector q, v, P;
  int i, k, flag;
  SUNContext_Create(NULL, &ctx);
  q  = N_VNew_Serial(7, ctx);
  v  = N_VNew_Serial(6, ctx);
  P  = N_VNew_Serial(1, ctx);
  qd = N_VGetArrayPointer(q);
  nrm = sqrt(quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3]);
  qd[0] = 0.1; qd[1] = 0.5; qd[2] = -0.2;
  for (i = 0; i < 4; i++) qd[3 + i] = quat[i] / nrm;
  for (i = 0; i < 3; i++) {
    N_VGetArrayPointer(v)[i]     = u0[i];
    N_VGetArrayPointer(v)[3 + i] = W0[i];
  }
  md.B = LGNBodies_Create(G);
  md.J = LGNJoints_Create(G);
  md.nc = 1;
  md.twice = 0;
  md.body[0] = 0;
  md.s[0][0] = 0.2; md.s[0][1] = -0.3; md.s[0][2] = 0.1;
  md.n[0][0] = 0.0; md.n[0][1] = 1.0; md.n[0][2] = 0.0;
  LGNBodies_SetPrincipalInertia(md.B, 0, mass, J);
  Rotation(qd + 3, R);
  for (i = 0; i < 3; i++) Rs[i] = R[3 * i] * md.s[0][0] + R[3 * i + 1] * md.s[0][1] + R[3 * i + 2] * md.s[0][2];
  for (i = 0; i < 3; i++) x[i] = qd[i] + Rs[i];
  md.d[0] = x[1]; /* the point on the plane y = d */

  /* the row against central differences of the gap along q o exp(e w) */
  {
    double err = 0.0, g0;
    CHECK(LGNJoints_PointPlaneContact(md.J, q, 0, md.s[0], md.n[0], md.d[0], &g0, row) == 0 &&
              fabs(g0) < 1e-15, "the gap is 0 at the contact (%g)", g0);
    for (k = 0; k < 6; k++) {
      N_Vector qp = N_VClone(q), w = N_VNew_Serial(6, ctx);
      double gp, gm, rowp[6], h = 1e-6;
      N_VConst(0.0, w);
      N_VGetArrayPointer(w)[k] = h;
      LGNGroup_ComposeExp(G, qd, N_VGetArrayPointer(w), N_VGetArrayPointer(qp));
      LGNJoints_PointPlaneContact(md.J, qp, 0, md.s[0], md.n[0], md.d[0], &gp, rowp);
      N_VGetArrayPointer(w)[k] = -h;
      LGNGroup_ComposeExp(G, qd, N_VGetArrayPointer(w), N_VGetArrayPointer(qp));
      LGNJoints_PointPlaneContact(md.J, qp, 0, md.s[0], md.n[0], md.d[0], &gm, rowp);
      err = fmax(err, fabs((gp - gm) / (2 * h) - row[k]));
      N_VDestroy(qp);
      N_VDestroy(w);
    }
    CHECK(err < 1e-8, "the contact row = central differences of the gap (%.1e)", err);
  }

  for (e = 0.0; e <= 1.0; e += 0.5) {
    /* closed form: r = s x R^T n, 1/m_eff = 1/m + r . J^-1 r, vn = n . (u + R (W x s)) */
    double r3[3], Rtn[3], vn, meff, j, u[3], W[3], err = 0.0, Wxs[3];
    for (i = 0; i < 3; i++) Rtn[i] = R[i] * md.n[0][0] + R[3 + i] * md.n[0][1] + R[6 + i] * md.n[0][2];
    r3[0] = md.s[0][1] * Rtn[2] - md.s[0][2] * Rtn[1];
    r3[1] = md.s[0][2] * Rtn[0] - md.s[0][0] * Rtn[2];
    r3[2] = md.s[0][0] * Rtn[1] - md.s[0][1] * Rtn[0];
    Wxs[0] = W0[1] * md.s[0][2] - W0[2] * md.s[0][1];
    Wxs[1] = W0[2] * md.s[0][0] - W0[0] * md.s[0][2];
    Wxs[2] = W0[0] * md.s[0][1] - W0[1] * md.s[0][0];
    vn = 0.0;
    for (i = 0; i < 3; i++)
      vn += md.n[0][i] * (u0[i] + R[3 * i] * Wxs[0] + R[3 * i + 1] * Wxs[1] + R[3 * i + 2] * Wxs[2]);
    meff = 1.0 / (1.0 / mass + r3[0] * r3[0] / J[0] + r3[1] * r3[1] / J[1] + r3[2] * r3[2] / J[2]);
    j    = -(1.0 + e) * vn * meff;
    for (i = 0; i < 3; i++) {
      u[i] = u0[i] + j * md.n[0][i] / mass;
      W[i] = W0[i] + j * r3[i] / J[i];
    }
    flag = RunCreate(&r, &md, q, v, 0);
    if (!flag) flag = RunSetup(&r, &md, G, q, v);
    if (!flag) flag = LGNApplyImpact(r.mem, 1, Contacts, e, NULL, P);
    if (!flag) flag = LGNGetConsistentIC(r.mem, r.q, r.v);
    for (i = 0; i < 3; i++) {
      err = fmax(err, fabs(N_VGetArrayPointer(r.v)[i] - u[i]));
      err = fmax(err, fabs(N_VGetArrayPointer(r.v)[3 + i] - W[i]));
    }
    printf("(a) free body, e = %.1f: %s, v_n = %.4f, |v+ - closed form| = %.1e, P = %.6f "
           "(j = %.6f)\n", e, LGNGetReturnFlagName(flag), vn, err, N_VGetArrayPointer(P)[0], j);
    CHECK(flag == LGN_SUCCESS, "free body: %s (%s)", LGNGetReturnFlagName(flag), last_msg);
    CHECK(vn < -0.1 && err < 1e-13, "v+ = the closed form (%.2e)", err);
    CHECK(fabs(N_VGetArrayPointer(P)[0] + j) < 1e-13, "P = -j (%g, %g)",
          N_VGetArrayPointer(P)[0], j);
    RunFree(&r);
  }
  LGNBodies_Destroy(&md.B);
  LGNJoints_Destroy(&md.J);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(P);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
}

/* =============================================================================
 * (b) a rod falling flat on two contacts
 * ===========================================================================*/

static void FlatRod(void)
{
  SUNContext ctx;
  LGNGroup G = LGNGroup_R3xSO3();
  Model md;
  Run r;
  const double J[3] = {0.01, 0.1, 0.1};
  N_Vector q, v, P;
  double e = 0.7, err = 0.0;
  int i, flag;
  SUNContext_Create(NULL, &ctx);
  q = N_VNew_Serial(7, ctx);
  v = N_VNew_Serial(6, ctx);
  P = N_VNew_Serial(2, ctx);
  N_VConst(0.0, q);
  N_VGetArrayPointer(q)[3] = 1.0;
  N_VConst(0.0, v);
  N_VGetArrayPointer(v)[1] = -1.0; /* falling flat, along y */
  md.B = LGNBodies_Create(G);
  md.J = LGNJoints_Create(G);
  md.nc = 2;
  md.twice = 0;
  LGNBodies_SetPrincipalInertia(md.B, 0, 1.0, J);
  for (i = 0; i < 2; i++) {
    md.body[i] = 0;
    md.s[i][0] = i ? 0.5 : -0.5; md.s[i][1] = 0.0; md.s[i][2] = 0.0;
    md.n[i][0] = 0.0; md.n[i][1] = 1.0; md.n[i][2] = 0.0;
    md.d[i] = 0.0;
  }
  flag = RunCreate(&r, &md, q, v, 0);
  if (!flag) flag = RunSetup(&r, &md, G, q, v);
  if (!flag) flag = LGNApplyImpact(r.mem, 2, Contacts, e, NULL, P);
  if (!flag) flag = LGNGetConsistentIC(r.mem, r.q, r.v);
  for (i = 0; i < 6; i++) err = fmax(err, fabs(N_VGetArrayPointer(r.v)[i] - (i == 1 ? e : 0.0)));
  printf("(b) rod flat on two contacts, e = %.1f: %s, |v+ - (0, e, 0, 0)| = %.1e, P = %.4f, "
         "%.4f\n", e, LGNGetReturnFlagName(flag), err, N_VGetArrayPointer(P)[0],
         N_VGetArrayPointer(P)[1]);
  CHECK(flag == LGN_SUCCESS && err < 1e-14, "two contacts at once: v+ = -e v- (%.1e)", err);
  CHECK(fabs(N_VGetArrayPointer(P)[0] + 0.5 * (1 + e)) < 1e-14 &&
            fabs(N_VGetArrayPointer(P)[1] + 0.5 * (1 + e)) < 1e-14,
        "each end takes half the impulse, pushing (P = -(1 + e)/2)");
  RunFree(&r);
  LGNBodies_Destroy(&md.B);
  LGNJoints_Destroy(&md.J);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(P);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
}

/* =============================================================================
 * (c) a chain: rods on spherical joints, pinned at the top
 * ===========================================================================*/

/* nb rods of length 1 hanging along -y from the origin, turned out in x
 * by the angle th (rod k from P_k to P_{k+1}), unit masses; contacts: the
 * tip against the wall x = xw (n = (-1, 0, 0)) and, with two contacts, the
 * lower end of rod 1 against the plane z = 0 (n = (0, 0, 1)) */
static void BuildChain(Model *md, LGNGroup G, int nb, N_Vector q, N_Vector v, int nc)
{
  const double th = 0.6, J[3] = {1.0 / 12, 0.001, 1.0 / 12}, gvec[3] = {0, -9.81, 0};
  double *qd = N_VGetArrayPointer(q), *vd = N_VGetArrayPointer(v), P[3] = {0, 0, 0};
  const double dir[3] = {sin(th), -cos(th), 0.0};
  const double half[3] = {0.5 * sin(th), -0.5 * cos(th), 0.0};
  const double sb[3] = {0, 0.5, 0}, sa[3] = {0, -0.5, 0}; /* rod along body y */
  int k, i;
  (void)G;
  md->B = LGNBodies_Create(G);
  md->J = LGNJoints_Create(G);
  LGNBodies_SetGravity(md->B, gvec);
  for (k = 0; k < nb; k++) {
    const double c = cos(0.5 * th), s = sin(0.5 * th);
    LGNBodies_SetPrincipalInertia(md->B, k, 1.0, J);
    /* R = rotation about z by th: body y = -dir */
    for (i = 0; i < 3; i++) qd[7 * k + i] = P[i] + half[i];
    qd[7 * k + 3] = c; qd[7 * k + 4] = 0; qd[7 * k + 5] = 0; qd[7 * k + 6] = s;
    if (k == 0) {
      const double O[3] = {0, 0, 0};
      LGNJoints_AddSpherical(md->J, LGN_GROUND, O, 0, sb);
    } else {
      LGNJoints_AddSpherical(md->J, k - 1, sa, k, sb);
    }
    for (i = 0; i < 3; i++) P[i] += dir[i];
  }
  /* a swing towards the wall (+x) and the floor (-z): projected onto B v = 0 */
  N_VConst(0.0, v);
  for (k = 0; k < nb; k++) {
    vd[6 * k]     = 1.0 + 0.3 * k;
    vd[6 * k + 2] = -0.5 - 0.2 * k;
  }
  md->nc = nc;
  md->twice = 0;
  md->body[0] = nb - 1;
  md->s[0][0] = 0; md->s[0][1] = -0.5; md->s[0][2] = 0;
  md->n[0][0] = -1; md->n[0][1] = 0; md->n[0][2] = 0;
  md->d[0] = -P[0]; /* -x = -x_tip: the tip on the wall */
  md->body[1] = 1;
  md->s[1][0] = 0; md->s[1][1] = -0.5; md->s[1][2] = 0;
  md->n[1][0] = 0; md->n[1][1] = 0; md->n[1][2] = 1;
  md->d[1] = 0.0;
}

/* x^T M y */
static double MNorm(Model *md, N_Vector q, const double *x, const double *y, sunindextype nv,
                    SUNContext ctx)
{
  SUNMatrix M = SUNDenseMatrix(nv, nv, ctx);
  double s = 0.0;
  sunindextype i, j;
  SUNMatZero(M);
  LGNBodies_Mass(md->B, q, M);
  for (i = 0; i < nv; i++)
    for (j = 0; j < nv; j++) s += x[i] * SM_ELEMENT_D(M, i, j) * y[j];
  SUNMatDestroy(M);
  return s;
}

/* |M dv + G^T P + B^T L| with L the least-squares fit (normal equations) */
static double MomentumResidual(Model *md, N_Vector q, const double *dv, const double *P, int nc,
                               sunindextype nv, sunindextype m, SUNContext ctx)
{
  SUNMatrix M = SUNDenseMatrix(nv, nv, ctx), B = SUNDenseMatrix(m, nv, ctx);
  SUNMatrix G = SUNDenseMatrix(nc, nv, ctx);
  double r[256], BBt[64][65], L[64], res = 0.0;
  sunindextype i, j, k;
  SUNMatZero(M);
  SUNMatZero(B);
  SUNMatZero(G);
  LGNBodies_Mass(md->B, q, M);
  LGNJoints_Jacobian(md->J, 0.0, q, B);
  Contacts(0.0, q, G, md);
  for (i = 0; i < nv; i++) {
    r[i] = 0.0;
    for (j = 0; j < nv; j++) r[i] += SM_ELEMENT_D(M, i, j) * dv[j];
    for (k = 0; k < nc; k++) r[i] += SM_ELEMENT_D(G, k, i) * P[k];
  }
  /* B B^T L = -B r, Gauss-Jordan */
  for (i = 0; i < m; i++) {
    for (j = 0; j < m; j++) {
      BBt[i][j] = 0.0;
      for (k = 0; k < nv; k++) BBt[i][j] += SM_ELEMENT_D(B, i, k) * SM_ELEMENT_D(B, j, k);
    }
    BBt[i][m] = 0.0;
    for (k = 0; k < nv; k++) BBt[i][m] -= SM_ELEMENT_D(B, i, k) * r[k];
  }
  for (i = 0; i < m; i++) {
    for (j = 0; j < m; j++) {
      double f;
      if (j == i) continue;
      f = BBt[j][i] / BBt[i][i];
      for (k = i; k <= m; k++) BBt[j][k] -= f * BBt[i][k];
    }
  }
  for (i = 0; i < m; i++) L[i] = BBt[i][m] / BBt[i][i];
  for (i = 0; i < nv; i++) {
    double x = r[i];
    for (k = 0; k < m; k++) x += SM_ELEMENT_D(B, k, i) * L[k];
    res = fmax(res, fabs(x));
  }
  SUNMatDestroy(M);
  SUNMatDestroy(B);
  SUNMatDestroy(G);
  return res;
}

static void Chain(double e)
{
  SUNContext ctx;
  LGNGroup body = LGNGroup_R3xSO3(), G, f[4];
  Model md;
  Run r;
  const int nb = 4, nc = 2;
  const sunindextype nv = 6 * nb;
  N_Vector q, v, P, vout;
  double vm[24], vp[24], dv[24], gm[2], gp[2], bv = 0.0, Tm, Tp, loss, mom, t;
  SUNMatrix Bm, Gm;
  int i, k, flag;
  SUNContext_Create(NULL, &ctx);
  for (k = 0; k < nb; k++) f[k] = body;
  G = LGNGroup_Product(nb, f);
  q = N_VNew_Serial(7 * nb, ctx);
  v = N_VNew_Serial(nv, ctx);
  P = N_VNew_Serial(nc, ctx);
  vout = N_VNew_Serial(nv, ctx);
  BuildChain(&md, G, nb, q, v, nc);
  flag = RunCreate(&r, &md, q, v, 0);
  if (!flag) flag = RunSetup(&r, &md, G, q, v);
  memcpy(vm, N_VGetArrayPointer(r.v), sizeof vm);
  if (!flag) flag = LGNApplyImpact(r.mem, nc, Contacts, e, vout, P);
  if (!flag) flag = LGNGetConsistentIC(r.mem, r.q, r.v);
  memcpy(vp, N_VGetArrayPointer(r.v), sizeof vp);
  CHECK(memcmp(vp, N_VGetArrayPointer(vout), sizeof vp) == 0, "v+ given back in v");
  for (i = 0; i < nv; i++) dv[i] = vp[i] - vm[i];
  Bm = SUNDenseMatrix(r.m, nv, ctx);
  Gm = SUNDenseMatrix(nc, nv, ctx);
  SUNMatZero(Bm);
  SUNMatZero(Gm);
  LGNJoints_Jacobian(md.J, 0.0, r.q, Bm);
  Contacts(0.0, r.q, Gm, &md);
  for (k = 0; k < r.m; k++) {
    double s = 0.0;
    for (i = 0; i < nv; i++) s += SM_ELEMENT_D(Bm, k, i) * vp[i];
    bv = fmax(bv, fabs(s));
  }
  for (k = 0; k < nc; k++) {
    gm[k] = gp[k] = 0.0;
    for (i = 0; i < nv; i++) {
      gm[k] += SM_ELEMENT_D(Gm, k, i) * vm[i];
      gp[k] += SM_ELEMENT_D(Gm, k, i) * vp[i];
    }
  }
  Tm   = 0.5 * MNorm(&md, r.q, vm, vm, nv, ctx);
  Tp   = 0.5 * MNorm(&md, r.q, vp, vp, nv, ctx);
  loss = 0.5 * MNorm(&md, r.q, dv, dv, nv, ctx);
  mom  = MomentumResidual(&md, r.q, dv, N_VGetArrayPointer(P), nc, nv, r.m, ctx);
  printf("(c) chain of %d, two contacts, e = %.1f: %s; G v- = (%.4f, %.4f), G v+ = (%.4f, %.4f); "
         "|B v+| = %.1e; T- = %.6f, T+ = %.6f, dv^T M dv / 2 = %.6f; momentum residual %.1e\n",
         nb, e, LGNGetReturnFlagName(flag), gm[0], gm[1], gp[0], gp[1], bv, Tm, Tp, loss, mom);
  CHECK(flag == LGN_SUCCESS, "chain: %s (%s)", LGNGetReturnFlagName(flag), last_msg);
  CHECK(gm[0] < -0.1 && gm[1] < -0.1, "both contacts closing before (%g, %g)", gm[0], gm[1]);
  CHECK(fabs(gp[0] + e * gm[0]) < 1e-12 && fabs(gp[1] + e * gm[1]) < 1e-12,
        "Newton's law at each contact");
  CHECK(bv < 1e-12, "B v+ = 0 (%.1e)", bv);
  if (e == 1.0) CHECK(fabs(Tp - Tm) < 1e-12 * Tm, "e = 1 keeps the kinetic energy (%.2e)", Tp - Tm);
  if (e == 0.0) CHECK(fabs(Tm - Tp - loss) < 1e-12 * Tm, "e = 0 loses dv^T M dv / 2 (%.2e)",
                      Tm - Tp - loss);
  CHECK(mom < 1e-12, "momentum balance: M dv + G^T P in the range of B^T (%.1e)", mom);
  CHECK(N_VGetArrayPointer(P)[0] < 0.0 && N_VGetArrayPointer(P)[1] < 0.0,
        "both contacts push (P < 0): %g, %g", N_VGetArrayPointer(P)[0], N_VGetArrayPointer(P)[1]);
  /* the integration goes on from v+ */
  if (!flag) flag = LGNSolve(r.mem, 0.1, &t, r.q, r.v, LGN_NORMAL);
  CHECK(flag == LGN_SUCCESS, "LGNSolve after the impact: %s", LGNGetReturnFlagName(flag));
  SUNMatDestroy(Bm);
  SUNMatDestroy(Gm);
  RunFree(&r);
  LGNBodies_Destroy(&md.B);
  LGNJoints_Destroy(&md.J);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(P);
  N_VDestroy(vout);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
}

#if defined(LGN_HAVE_KLU)
/* a chain of 40 (the impulse system: 240 + 120 + 2 unknowns): KLU on CSR
 * against dense LAPACK */
static void ChainSparse(void)
{
  SUNContext ctx;
  LGNGroup body = LGNGroup_R3xSO3(), G, f[40];
  Model md;
  Run r[2];
  const int nb = 40, nc = 2;
  N_Vector q, v, P[2];
  double diff = 0.0, dp = 0.0, scale = 0.0;
  int k, s, flag[2];
  SUNContext_Create(NULL, &ctx);
  for (k = 0; k < nb; k++) f[k] = body;
  G = LGNGroup_Product(nb, f);
  q = N_VNew_Serial(7 * nb, ctx);
  v = N_VNew_Serial(6 * nb, ctx);
  BuildChain(&md, G, nb, q, v, nc);
  for (s = 0; s < 2; s++) {
    P[s]    = N_VNew_Serial(nc, ctx);
    flag[s] = RunCreate(&r[s], &md, q, v, s);
    if (!flag[s]) flag[s] = RunSetup(&r[s], &md, G, q, v);
    if (!flag[s]) flag[s] = LGNApplyImpact(r[s].mem, nc, Contacts, 0.5, NULL, P[s]);
    if (!flag[s]) flag[s] = LGNGetConsistentIC(r[s].mem, r[s].q, r[s].v);
  }
  for (k = 0; k < 6 * nb; k++) {
    diff  = fmax(diff, fabs(N_VGetArrayPointer(r[0].v)[k] - N_VGetArrayPointer(r[1].v)[k]));
    scale = fmax(scale, fabs(N_VGetArrayPointer(r[0].v)[k]));
  }
  for (k = 0; k < nc; k++)
    dp = fmax(dp, fabs(N_VGetArrayPointer(P[0])[k] - N_VGetArrayPointer(P[1])[k]));
  printf("(c) chain of %d: KLU (CSR) %s, dense %s: |v+_KLU - v+_dense| = %.1e (|v+| %.1f), "
         "|P_KLU - P_dense| = %.1e\n", nb, LGNGetReturnFlagName(flag[1]),
         LGNGetReturnFlagName(flag[0]), diff, scale, dp);
  CHECK(flag[0] == LGN_SUCCESS && flag[1] == LGN_SUCCESS, "both solves: %s", last_msg);
  CHECK(diff < 1e-10 * scale && dp < 1e-10 && scale > 1.0, "KLU = dense (%.1e, %.1e)", diff, dp);
  for (s = 0; s < 2; s++) {
    RunFree(&r[s]);
    N_VDestroy(P[s]);
  }
  LGNBodies_Destroy(&md.B);
  LGNJoints_Destroy(&md.J);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
}
#endif

/* =============================================================================
 * (d) bad input
 * ===========================================================================*/

static void BadInput(void)
{
  SUNContext ctx;
  LGNGroup body = LGNGroup_R3xSO3(), G, f[2];
  Model md;
  Run r;
  N_Vector q, v, P3;
  double before[12];
  int k, flag, same = 1;
  SUNContext_Create(NULL, &ctx);
  f[0] = f[1] = body;
  G  = LGNGroup_Product(2, f);
  q  = N_VNew_Serial(14, ctx);
  v  = N_VNew_Serial(12, ctx);
  P3 = N_VNew_Serial(3, ctx);
  BuildChain(&md, G, 2, q, v, 1);
  RunCreate(&r, &md, q, v, 0);
  LGNSetGroup(r.mem, G);
  LGNSetUserData(r.mem, &md);
  LGNSetMassFn(r.mem, Mass);
  LGNSetForceFn(r.mem, Force);
  LGNSetConstraints(r.mem, r.m, Phi, Jac);
  CHECK(LGNApplyImpact(r.mem, 1, Contacts, 0.5, NULL, NULL) == LGN_NO_MALLOC, "before LGNInit");
  LGNInit(r.mem, 0.0, q, v);
  LGNSetLinearSolver(r.mem, r.LS, r.A);
  LGNSetStepSize(r.mem, 1e-3);
  CHECK(LGNApplyImpact(r.mem, 1, Contacts, 0.5, NULL, NULL) == LGN_ILL_INPUT &&
            strstr(last_msg, "after LGNSolve") != NULL,
        "before the integrator is set up: %s", last_msg);
  flag = LGNCalcIC(r.mem, LGN_IC_PROJECT_V);
  LGNGetConsistentIC(r.mem, r.q, r.v);
  memcpy(before, N_VGetArrayPointer(r.v), sizeof before);
  CHECK(flag == LGN_SUCCESS, "set up");
  CHECK(LGNApplyImpact(r.mem, 1, Contacts, 1.5, NULL, NULL) == LGN_ILL_INPUT &&
            strstr(last_msg, "e = 1.5") != NULL, "e = 1.5 refused: %s", last_msg);
  CHECK(LGNApplyImpact(r.mem, 1, Contacts, NAN, NULL, NULL) == LGN_ILL_INPUT, "e = NaN refused");
  CHECK(LGNApplyImpact(r.mem, 0, Contacts, 0.5, NULL, NULL) == LGN_ILL_INPUT, "nc = 0 refused");
  CHECK(LGNApplyImpact(r.mem, 1, NULL, 0.5, NULL, NULL) == LGN_ILL_INPUT &&
            strstr(last_msg, "G = NULL") != NULL, "G = NULL refused: %s", last_msg);
  CHECK(LGNApplyImpact(r.mem, 1, Contacts, 0.5, NULL, P3) == LGN_ILL_INPUT &&
            strstr(last_msg, "P") != NULL, "P of length 3 for 1 contact refused: %s", last_msg);
  CHECK(LGNApplyImpact(NULL, 1, Contacts, 0.5, NULL, NULL) == LGN_MEM_NULL, "mem NULL");
  md.twice = 1; /* the same row twice: a singular system */
  CHECK(LGNApplyImpact(r.mem, 2, Contacts, 0.5, NULL, NULL) == LGN_LSETUP_FAIL &&
            strstr(last_msg, "singular") != NULL, "two equal contact rows: %s", last_msg);
  md.twice = 0;
  LGNGetConsistentIC(r.mem, r.q, r.v);
  for (k = 0; k < 12; k++) same = same && N_VGetArrayPointer(r.v)[k] == before[k];
  CHECK(same, "the velocity unchanged by the refused calls");
  RunFree(&r);
  LGNBodies_Destroy(&md.B);
  LGNJoints_Destroy(&md.J);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(P3);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
}

int main(void)
{
  FreeBody();
  FlatRod();
  Chain(1.0);
  Chain(0.0);
  Chain(0.5);
#if defined(LGN_HAVE_KLU)
  ChainSparse();
#endif
  BadInput();
  return test_summary("test_impact");
}
