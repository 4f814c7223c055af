/* -----------------------------------------------------------------------------
 * Drivers (prescribed motion) of the joint helpers and the prismatic joint
 * given by frames:
 *  (a) the residuals mean what the header says: a rotation driver gives
 *      sin(theta - f(t)) for body b turned by theta about the axis, a
 *      translation driver the distance along the axis minus f(t); a
 *      prismatic joint from frames is satisfied where the frames align and
 *      violated when b turns about the axis;
 *  (b) derivatives on a product of R^3 x SO(3) and SE(3) bodies with both
 *      drivers (between bodies and to the ground) next to joints, at random
 *      configurations and t = 0.7: B against central quotients of Phi along
 *      the group, K against quotients of B^T lambda, f = B^T lambda, Phi_t
 *      against a quotient in t, and the curvature against the quotient of
 *      B v + Phi_t along (q exp(s v), t + s); sparse B and K equal dense;
 *  (c) a failing or non-finite time law: LGN_CONSTR_FAIL naming the driver,
 *      from every evaluation; bad arguments refused;
 *  (d) integration with Lignum (generalized-alpha, index 3 and 2): a body on
 *      a revolute joint to the ground turned by a motor theta = f(t) and a
 *      body on a prismatic joint pushed by an actuator s = g(t) follow the
 *      prescribed motion (to Newton's tolerance at index 3, to the O(h^2)
 *      drift at index 2), and the drivers' multipliers are the exact
 *      -J_z f'' and -m g'' (inverse dynamics) with order 2 +- 0.3 (with
 *      the perturbed start, which this start needs: f'''(0) != 0).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "rigid_test_util.h"

static int failures = 0;

static void Check(const char *what, double err, double tol)
{
  const int ok = err <= tol;
  printf("%-62s %.3e (tol %.0e) %s\n", what, err, tol, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/* Time laws: f = 0.3 sin 2t + 0.5 t (rotation), g = 0.2 t^2 + 0.1 cos 3t. */
static int RotLaw(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 0.3 * sin(2 * t) + 0.5 * t;
  f[1] = 0.6 * cos(2 * t) + 0.5;
  f[2] = -1.2 * sin(2 * t);
  return 0;
}

static int TransLaw(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 0.2 * t * t + 0.1 * cos(3 * t);
  f[1] = 0.4 * t - 0.3 * sin(3 * t);
  f[2] = 0.4 - 0.9 * cos(3 * t);
  return 0;
}

static int failing_law_mode = 0; /* 1: returns -1, 2: NaN */
static int FailingLaw(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)t; (void)data;
  f[0] = f[1] = f[2] = 0.0;
  if (failing_law_mode == 2) f[1] = NAN;
  return failing_law_mode == 1 ? -1 : 0;
}

/* Quaternion of the rotation by angle about the unit axis n. */
static void AxisAngle(const double *n, double angle, double *p)
{
  p[0] = cos(angle / 2);
  p[1] = sin(angle / 2) * n[0];
  p[2] = sin(angle / 2) * n[1];
  p[3] = sin(angle / 2) * n[2];
}

/* ---- (a) what the residuals mean --------------------------------------- */

static void CheckMeaning(SUNContext ctx)
{
  const double ez[3] = {0, 0, 1}, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
  const double origin[3] = {0, 0, 0}, t = 0.4;
  LGNGroup body = LGNGroup_R3xSO3(), f2[2], G;
  LGNJoints J;
  N_Vector q, phi;
  double *qd, fr[3], fg[3], err = 0;
  int trial;

  f2[0] = body;
  f2[1] = body;
  G  = LGNGroup_Product(2, f2);
  q  = N_VNew_Serial(G->nq, ctx);
  qd = N_VGetArrayPointer(q);
  RotLaw(t, fr, NULL);
  TransLaw(t, fg, NULL);
  for (trial = 0; trial < 5; trial++) {
    const double theta = 3 * Rand(), d = 2 * Rand();
    double pt[4], pa[4];
    RandomConfiguration(2, qd);
    /* body 1 = body 0 turned by theta about body 0's z, its origin moved
     * by d along body 0's x */
    memcpy(pa, qd + 3, sizeof pa);
    AxisAngle(ez, theta, pt);
    LGNQuaternionMultiply(pa, pt, qd + 10);
    {
      double R[9];
      int i;
      LGNQuaternionToRotation(pa, R);
      for (i = 0; i < 3; i++) qd[7 + i] = qd[i] + d * R[3 * i];
    }
    J = LGNJoints_Create(G);
    LGNJoints_AddRotationDriver(J, 0, ez, ex, 1, ex, RotLaw, NULL);
    LGNJoints_AddTranslationDriver(J, 0, origin, ex, 1, origin, TransLaw, NULL);
    LGNJoints_AddPrismaticFrames(J, 0, origin, ex, ey, 1, origin, ex, ey);
    phi = N_VNew_Serial(LGNJoints_NumConstraints(J), ctx);
    LGNJoints_Residual(J, t, q, phi);
    err = fmax(err, fabs(NV_Ith_S(phi, 0) - sin(theta - fr[0])));
    err = fmax(err, fabs(NV_Ith_S(phi, 1) - (d - fg[0])));
    if (trial == 0) {
      /* the prismatic rows (axis x, frames [x, y, z] on both bodies):
       * violated, since body 1 is turned about z */
      double viol = 0;
      int i;
      for (i = 2; i < 7; i++) viol = fmax(viol, fabs(NV_Ith_S(phi, i)));
      printf("prismatic from frames, body 1 turned by %.2f about z: |Phi| = %.3e\n", theta,
             viol);
      if (!(viol > 0.1 * fabs(sin(theta)))) failures++;
    }
    N_VDestroy(phi);
    LGNJoints_Destroy(&J);
    /* aligned frames: with R0 = R(p0), axis_b = R0^T x and ref_b = R0^T y
     * (plus a part along axis_b, which is ignored), body 1 at R_a R0 and
     * moved along x_a: the prismatic rows vanish */
    {
      double p0[4], R0[9], Ra[9], axis_b[3], ref_b[3], nrm = 0;
      int i;
      for (i = 0; i < 4; i++) { p0[i] = Rand(); nrm += p0[i] * p0[i]; }
      for (i = 0; i < 4; i++) p0[i] /= sqrt(nrm);
      LGNQuaternionToRotation(p0, R0);
      for (i = 0; i < 3; i++) {
        axis_b[i] = 2.0 * R0[i];                    /* (R0^T x)_i = R0[0][i] */
        ref_b[i]  = R0[3 + i] + 0.7 * R0[i];
      }
      LGNQuaternionMultiply(pa, p0, qd + 10);
      LGNQuaternionToRotation(pa, Ra);
      for (i = 0; i < 3; i++) qd[7 + i] = qd[i] + d * Ra[3 * i];
      J = LGNJoints_Create(G);
      LGNJoints_AddPrismaticFrames(J, 0, origin, ex, ey, 1, origin, axis_b, ref_b);
      phi = N_VNew_Serial(5, ctx);
      LGNJoints_Residual(J, t, q, phi);
      err = fmax(err, N_VMaxNorm(phi));
      N_VDestroy(phi);
      LGNJoints_Destroy(&J);
    }
  }
  Check("(a) driver residuals, prismatic frames aligned", err, 1e-14);
  N_VDestroy(q);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
}

/* ---- (b) derivatives ----------------------------------------------------- */

/* c = B(q', t') v + Phi_t(q', t') at q' = q o exp(s v), t' = t + s. */
static void VelocityConstraint(LGNJoints J, LGNGroup G, N_Vector q, N_Vector v,
                               double t, double s, N_Vector qs, SUNMatrix B,
                               N_Vector phit, double *c)
{
  double w[24];
  sunindextype i, m = LGNJoints_NumConstraints(J);
  for (i = 0; i < G->nv; i++) w[i] = s * NV_Ith_S(v, i);
  LGNGroup_ComposeExp(G, N_VGetArrayPointer(q), w, N_VGetArrayPointer(qs));
  SUNMatZero(B);
  LGNJoints_Jacobian(J, t + s, qs, B);
  DenseApply(B, N_VGetArrayPointer(v), c, 0);
  LGNJoints_TimeDerivative(J, t + s, qs, phit);
  for (i = 0; i < m; i++) c[i] += NV_Ith_S(phit, i);
}

static void CheckDerivatives(SUNContext ctx)
{
  const double sa[3] = {0.1, -0.2, 0.5}, sb[3] = {-0.3, 0.2, -0.4};
  const double ax[3] = {0, 0, 1}, axy[3] = {1, 1, 0.5}, ay[3] = {0, 2, 0};
  const double t = 0.7, eps = 1e-6;
  LGNGroup body[2], f4[4], G;
  LGNJoints J;
  N_Vector q, qp, qm, v, lam, phi_p, phi_m, z, fvec, phit;
  SUNMatrix B, Bp, Bm, K, S;
  sunindextype nv, m, i, j;
  double *qd, errB = 0, errZ = 0, errK = 0, errF = 0, errS = 0, errT = 0;
  double scaleB = 0, scaleZ = 0, scaleK = 0, scaleT = 0;
  int trial;

  body[0] = LGNGroup_R3xSO3();
  body[1] = LGNGroup_SE3();
  f4[0] = body[0]; f4[1] = body[1]; f4[2] = body[0]; f4[3] = body[1];
  G  = LGNGroup_Product(4, f4);
  nv = G->nv;
  J  = LGNJoints_Create(G);
  LGNJoints_AddRevolute(J, 0, sa, axy, 1, sb, ax);
  LGNJoints_AddRotationDriver(J, 0, axy, ay, 1, sa, RotLaw, NULL);
  LGNJoints_AddPrismaticFrames(J, 1, sb, ay, ax, 2, sa, axy, ay);
  LGNJoints_AddTranslationDriver(J, 1, sb, ay, 2, sa, TransLaw, NULL);
  LGNJoints_AddRotationDriver(J, LGN_GROUND, ax, ay, 3, axy, RotLaw, NULL);
  LGNJoints_AddTranslationDriver(J, 3, sa, axy, LGN_GROUND, sb, TransLaw, NULL);
  m = LGNJoints_NumConstraints(J);
  if (m != 5 + 1 + 5 + 1 + 1 + 1 || LGNJoints_NumDrivers(J) != 4) {
    printf("m = %lld, drivers %d\n", (long long)m, LGNJoints_NumDrivers(J));
    failures++;
  }
  q = N_VNew_Serial(G->nq, ctx);
  qd = N_VGetArrayPointer(q);
  qp = N_VNew_Serial(G->nq, ctx);
  qm = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(nv, ctx);
  lam = N_VNew_Serial(m, ctx);
  phi_p = N_VNew_Serial(m, ctx);
  phi_m = N_VNew_Serial(m, ctx);
  phit = N_VNew_Serial(m, ctx);
  z = N_VNew_Serial(m, ctx);
  fvec = N_VNew_Serial(nv, ctx);
  B = SUNDenseMatrix(m, nv, ctx);
  Bp = SUNDenseMatrix(m, nv, ctx);
  Bm = SUNDenseMatrix(m, nv, ctx);
  K = SUNDenseMatrix(nv, nv, ctx);
  for (trial = 0; trial < 5; trial++) {
    double w[24], yp[24], ym[24], btl[24], cp[24], cm[24];
    RandomConfiguration(4, qd);
    for (i = 0; i < nv; i++) NV_Ith_S(v, i) = 2 * Rand();
    for (i = 0; i < m; i++) NV_Ith_S(lam, i) = 10 * Rand();
    SUNMatZero(B);
    LGNJoints_Jacobian(J, t, q, B);
    SUNMatZero(K);
    LGNJoints_Stiffness(J, t, q, lam, K);
    LGNJoints_Curvature(J, t, q, v, z);
    LGNJoints_TimeDerivative(J, t, q, phit);
    /* Phi_t against d/dt Phi at fixed q */
    LGNJoints_Residual(J, t + eps, q, phi_p);
    LGNJoints_Residual(J, t - eps, q, phi_m);
    for (i = 0; i < m; i++) {
      const double d = (NV_Ith_S(phi_p, i) - NV_Ith_S(phi_m, i)) / (2 * eps);
      errT = fmax(errT, fabs(d - NV_Ith_S(phit, i)));
      scaleT = fmax(scaleT, fabs(NV_Ith_S(phit, i)));
    }
    for (j = 0; j < nv; j++) {
      for (i = 0; i < nv; i++) w[i] = (i == j) ? eps : 0.0;
      LGNGroup_ComposeExp(G, qd, w, N_VGetArrayPointer(qp));
      for (i = 0; i < nv; i++) w[i] = -w[i];
      LGNGroup_ComposeExp(G, qd, w, N_VGetArrayPointer(qm));
      LGNJoints_Residual(J, t, qp, phi_p);
      LGNJoints_Residual(J, t, qm, phi_m);
      for (i = 0; i < m; i++) {
        const double d = (NV_Ith_S(phi_p, i) - NV_Ith_S(phi_m, i)) / (2 * eps);
        errB = fmax(errB, fabs(d - SM_ELEMENT_D(B, i, j)));
        scaleB = fmax(scaleB, fabs(SM_ELEMENT_D(B, i, j)));
      }
      SUNMatZero(Bp);
      SUNMatZero(Bm);
      LGNJoints_Jacobian(J, t, qp, Bp);
      LGNJoints_Jacobian(J, t, qm, Bm);
      DenseApply(Bp, N_VGetArrayPointer(lam), yp, 1);
      DenseApply(Bm, N_VGetArrayPointer(lam), ym, 1);
      for (i = 0; i < nv; i++) {
        const double d = (yp[i] - ym[i]) / (2 * eps);
        errK = fmax(errK, fabs(d - SM_ELEMENT_D(K, i, j)));
        scaleK = fmax(scaleK, fabs(SM_ELEMENT_D(K, i, j)));
      }
    }
    /* z = d/ds (B v + Phi_t) along (q exp(s v), t + s) */
    VelocityConstraint(J, G, q, v, t, eps, qp, Bp, phi_p, cp);
    VelocityConstraint(J, G, q, v, t, -eps, qm, Bm, phi_m, cm);
    for (i = 0; i < m; i++) {
      errZ = fmax(errZ, fabs((cp[i] - cm[i]) / (2 * eps) - NV_Ith_S(z, i)));
      scaleZ = fmax(scaleZ, fabs(NV_Ith_S(z, i)));
    }
    DenseApply(B, N_VGetArrayPointer(lam), btl, 1);
    N_VConst(NAN, fvec);
    LGNJoints_ConstraintForce(J, t, q, lam, fvec);
    for (i = 0; i < nv; i++) errF = fmax(errF, fabs(NV_Ith_S(fvec, i) - btl[i]));
    {
      int fmt;
      for (fmt = 0; fmt < 2; fmt++) {
        const int type = fmt == 0 ? CSC_MAT : CSR_MAT;
        S = SUNSparseMatrix(m, nv, 1, type, ctx);
        LGNJoints_Jacobian(J, t, q, S);
        errS = fmax(errS, SparseVsDense(S, B));
        SUNMatDestroy(S);
        S = SUNSparseMatrix(nv, nv, 1, type, ctx);
        LGNJoints_Stiffness(J, t, q, lam, S);
        errS = fmax(errS, SparseVsDense(S, K));
        SUNMatDestroy(S);
      }
    }
  }
  Check("(b) B against DQ of Phi (rel.)", errB / scaleB, 1e-8);
  Check("(b) K against DQ of B^T lambda (rel.)", errK / scaleK, 1e-8);
  Check("(b) Phi_t against DQ of Phi in t (rel.)", errT / scaleT, 1e-8);
  Check("(b) curvature against DQ of B v + Phi_t along (v, 1) (rel.)", errZ / scaleZ, 1e-8);
  Check("(b) f = B^T lambda without B", errF, 1e-13);
  Check("(b) sparse B and K (CSC, CSR) = dense", errS, 0.0);
  {
    char buf[128];
    LGNJoints_DescribeConstraint(J, 5, buf, sizeof buf);
    printf("row 5: %s\n", buf);
    if (strcmp(buf, "rotation driver (joint 1: body 0 - body 1), its constraint 1 of 1") != 0)
      failures++;
  }

  /* (c) failing time laws and bad arguments */
  {
    const double zero[3] = {0, 0, 0};
    LGNJoints Jf = LGNJoints_Create(G);
    N_Vector phif;
    int mode, flags_ok = 1;
    LGNJoints_SetErrFile(Jf, NULL); /* messages not printed */
    LGNJoints_AddTranslationDriver(Jf, 0, sa, ax, 1, sb, FailingLaw, NULL);
    phif = N_VNew_Serial(1, ctx);
    for (mode = 1; mode <= 2; mode++) {
      failing_law_mode = mode;
      flags_ok = flags_ok && LGNJoints_Residual(Jf, t, q, phif) == LGN_CONSTR_FAIL &&
                 LGNJoints_TimeDerivative(Jf, t, q, phif) == LGN_CONSTR_FAIL &&
                 LGNJoints_Curvature(Jf, t, q, v, phif) == LGN_CONSTR_FAIL &&
                 LGNJoints_Jacobian(Jf, t, q, Bp) != LGN_SUCCESS;
    }
    failing_law_mode = 0;
    flags_ok = flags_ok && LGNJoints_Residual(Jf, NAN, q, phif) == LGN_ILL_INPUT &&
               LGNJoints_Residual(Jf, t, q, phif) == LGN_SUCCESS;
    flags_ok = flags_ok &&
               LGNJoints_AddRotationDriver(Jf, 0, ax, ax, 1, ay, RotLaw, NULL) == LGN_ILL_INPUT &&
               LGNJoints_AddRotationDriver(Jf, 0, ax, ay, 1, zero, RotLaw, NULL) == LGN_ILL_INPUT &&
               LGNJoints_AddRotationDriver(Jf, 0, ax, ay, 1, ay, NULL, NULL) == LGN_ILL_INPUT &&
               LGNJoints_AddTranslationDriver(Jf, 0, sa, zero, 1, sb, TransLaw, NULL) == LGN_ILL_INPUT &&
               LGNJoints_AddTranslationDriver(Jf, 0, sa, ax, 0, sb, TransLaw, NULL) == LGN_ILL_INPUT &&
               LGNJoints_AddPrismaticFrames(Jf, 0, sa, ax, ax, 1, sb, ax, ay) == LGN_ILL_INPUT &&
               LGNJoints_AddPrismaticFrames(Jf, 0, sa, ax, ay, 1, sb, ax, NULL) == LGN_ILL_INPUT &&
               LGNJoints_TimeDerivative(NULL, t, q, phif) == LGN_ILL_INPUT &&
               LGNJoints_NumConstraints(Jf) == 1 && LGNJoints_NumDrivers(Jf) == 1;
    printf("(c) failing time laws and bad arguments: %s\n", flags_ok ? "ok" : "FAIL");
    if (!flags_ok) failures++;
    N_VDestroy(phif);
    LGNJoints_Destroy(&Jf);
  }

  LGNJoints_Destroy(&J);
  N_VDestroy(q); N_VDestroy(qp); N_VDestroy(qm); N_VDestroy(v); N_VDestroy(lam);
  N_VDestroy(phi_p); N_VDestroy(phi_m); N_VDestroy(phit); N_VDestroy(z); N_VDestroy(fvec);
  SUNMatDestroy(B); SUNMatDestroy(Bp); SUNMatDestroy(Bm); SUNMatDestroy(K);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body[0]);
  LGNGroup_Destroy(body[1]);
}

/* ---- (d) integration: a motor and an actuator ------------------------------ */

#define JZ   0.3
#define MASS 2.0

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Model;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Model *)ud)->bodies);
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Model *)ud)->bodies);
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->joints, t, q, phi) ? -1 : 0;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->joints, t, q, B) ? -1 : 0;
}

static int ConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  return LGNJoints_TimeDerivative(((Model *)ud)->joints, t, q, phit) ? -1 : 0;
}

static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->joints, t, q, v, z) ? -1 : 0;
}

/* Max errors over t in (0, 1]: motor angle, actuator position, and the two
 * drivers' multipliers against the inverse dynamics. */
static void RunDriven(SUNContext ctx, int index, double h, double err[4])
{
  const double ez[3] = {0, 0, 1}, ex[3] = {1, 0, 0}, o[3] = {0, 0, 0};
  const double inertia[3] = {0.2, 0.25, JZ};
  LGNGroup body = LGNGroup_R3xSO3(), f2[2], G;
  Model md;
  N_Vector q, v, lam, y;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  sunindextype m;
  double t = 0.0, fr[3], fg[3], p0[4];
  int flag, k;

  f2[0] = body;
  f2[1] = body;
  G = LGNGroup_Product(2, f2);
  md.bodies = LGNBodies_Create(G);
  LGNBodies_SetPrincipalInertia(md.bodies, 0, 1.0, inertia);
  LGNBodies_SetPrincipalInertia(md.bodies, 1, MASS, inertia);
  md.joints = LGNJoints_Create(G);
  /* body 0: revolute about z at its centre, turned by the motor f(t) */
  LGNJoints_AddRevolute(md.joints, LGN_GROUND, o, ez, 0, o, ez);
  LGNJoints_AddRotationDriver(md.joints, LGN_GROUND, ez, ex, 0, ex, RotLaw, NULL);
  /* body 1: slides along x, pushed by the actuator g(t) */
  LGNJoints_AddPrismatic(md.joints, LGN_GROUND, o, ex, 1, o, ex);
  LGNJoints_AddTranslationDriver(md.joints, LGN_GROUND, o, ex, 1, o, TransLaw, NULL);
  m = LGNJoints_NumConstraints(md.joints);

  /* the consistent start: angle f(0), position g(0), rates f'(0), g'(0) */
  RotLaw(0.0, fr, NULL);
  TransLaw(0.0, fg, NULL);
  q = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(G->nv, ctx);
  lam = N_VNew_Serial(m, ctx);
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  AxisAngle(ez, fr[0], p0);
  memcpy(N_VGetArrayPointer(q) + 3, p0, sizeof p0);
  NV_Ith_S(q, 7) = fg[0];
  NV_Ith_S(q, 10) = 1.0;
  NV_Ith_S(v, 5) = fr[1];
  NV_Ith_S(v, 6) = fg[1];

  y = N_VNew_Serial(G->nv + m, ctx);
  A = SUNDenseMatrix(G->nv + m, G->nv + m, ctx);
  LS = SUNLinSol_Dense(y, A, ctx);
  mem = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetConstraintTimeFn(mem, ConstrTime);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNSetConstraintIndex(mem, index);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetStepSize(mem, h);
  /* the motor's f''' (0) != 0: without the perturbed start lambda has an
   * O(h) start-up error */
  if (!flag) flag = LGNSetPerturbedStart(mem, SUNTRUE);
  for (k = 0; k < 4; k++) err[k] = 0.0;
  while (!flag && t < 1.0 - 1e-12) {
    double R[9], angle;
    flag = LGNSolve(mem, 1.0, &t, q, v, LGN_ONE_STEP);
    if (!flag) flag = LGNGetMultipliers(mem, lam);
    if (flag) break;
    RotLaw(t, fr, NULL);
    TransLaw(t, fg, NULL);
    LGNQuaternionToRotation(N_VGetArrayPointer(q) + 3, R);
    angle = atan2(R[3], R[0]);
    err[0] = fmax(err[0], fabs(remainder(angle - fr[0], 2 * acos(-1.0))));
    err[1] = fmax(err[1], fabs(NV_Ith_S(q, 7) - fg[0]));
    /* rows: revolute 0-4, motor 5, prismatic 6-10, actuator 11; the ground
     * is body a, so B^T lambda acts on b with + sign: J_z f'' + lambda = 0 */
    err[2] = fmax(err[2], fabs(NV_Ith_S(lam, 5) + JZ * fr[2]));
    err[3] = fmax(err[3], fabs(NV_Ith_S(lam, 11) + MASS * fg[2]));
  }
  if (flag) {
    printf("driven run, index %d, h %g: flag %d at t = %g\n", index, h, flag, t);
    for (k = 0; k < 4; k++) err[k] = HUGE_VAL;
  }
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(lam);
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
}

static void CheckIntegration(SUNContext ctx)
{
  const int indices[2] = {LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2};
  int k;
  for (k = 0; k < 2; k++) {
    double e1[4], e2[4], order;
    int i;
    RunDriven(ctx, indices[k], 2e-3, e1);
    RunDriven(ctx, indices[k], 1e-3, e2);
    printf("(d) index %d, h = 1e-3: angle %.2e, position %.2e, motor lambda %.2e, "
           "actuator lambda %.2e\n", k == 0 ? 3 : 2, e2[0], e2[1], e2[2], e2[3]);
    /* the motion is prescribed: at index 3 Newton meets Phi to its
     * tolerance; at index 2 Phi drifts by O(h^2) */
    Check("(d) angle and position follow f, g", fmax(e2[0], e2[1]), k == 0 ? 1e-8 : 1e-6);
    for (i = 2; i < 4; i++) {
      order = log(e1[i] / e2[i]) / log(2.0);
      printf("    multiplier %d: error %.3e -> %.3e, order %.2f\n", i - 1, e1[i], e2[i], order);
      if (!(e2[i] < 1e-3 && (e2[i] < 1e-10 || fabs(order - 2.0) < 0.3))) {
        printf("    FAIL\n");
        failures++;
      }
    }
  }
}

int main(void)
{
  SUNContext ctx;
  SUNContext_Create(NULL, &ctx);
  srand(23);
  CheckMeaning(ctx);
  CheckDerivatives(ctx);
  CheckIntegration(ctx);
  SUNContext_Free(&ctx);
  printf("%s\n", failures == 0 ? "PASSED" : "FAILED");
  return failures == 0 ? 0 : 1;
}
