/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Unit test of the prismatic and cylindrical joints (lignum_joints.h):
 *  - Phi = 0 at configurations built to satisfy them (body b placed from
 *    body a with an independently computed relative rotation exp(phi)
 *    taking axis_b to axis_a, a slide t along the axis and, for the
 *    cylindrical joint, a turn about it);
 *  - on R^3xSO(3) x SE(3) x R^3xSO(3) x SE(3) at random configurations,
 *    against central differences along the group:
 *      B w = d/de Phi(q o exp(e w)), Z(q)(v, v) = d/de B(q o exp(e v)) v,
 *      K w = d/de B(q o exp(e w))^T lambda,
 *    f = B^T lambda without B, and the sparse B and K (CSC, CSR) against
 *    the dense ones entry by entry;
 *  - the labels of LGNJoints_DescribeConstraint;
 *  - a slider: a body on a prismatic joint to the ground along a tilted
 *    axis under gravity, integrated by Lignum (M, g from lignum_bodies.h),
 *    against s(t) = s0 + v0 t + (gvec . a) t^2 / 2 along the axis.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "rigid_test_util.h"

static int failures = 0;

static void Check(const char *what, double err, double tol)
{
  printf("%-52s max error %.3e (tol %.1e) %s\n", what, err, tol, err <= tol ? "ok" : "FAIL");
  if (!(err <= tol)) failures++;
}

static const double sa[3] = {0.1, -0.2, 0.5}, sb[3] = {-0.3, 0.2, -0.4};
static const double ax[3] = {0, 0, 1}, axy[3] = {1, 1, 0.5}, ay[3] = {0, 2, 0};

/* quaternion of the rotation taking unit c to unit n (axis c x n) */
static void AlignQuat(const double *c, const double *n, double *p)
{
  double k[3] = {c[1] * n[2] - c[2] * n[1], c[2] * n[0] - c[0] * n[2], c[0] * n[1] - c[1] * n[0]};
  double s = sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]), ang = atan2(s, c[0] * n[0] + c[1] * n[1] + c[2] * n[2]);
  double phi[3] = {0, 0, 0};
  int i;
  if (s > 0)
    for (i = 0; i < 3; i++) phi[i] = ang * k[i] / s;
  LGNQuaternionFromRotationVector(phi, p);
}

static void Unit(const double *x, double *y)
{
  double n = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  y[0] = x[0] / n; y[1] = x[1] / n; y[2] = x[2] / n;
}

/* Place body b (qb: x, p) from body a (qa) so that the joint holds: R_b =
 * R_a exp(phi) exp(alpha c) (phi takes c to n), p_b = p_a + t R_a n. */
static void Place(const double *qa, const double *axis_a, const double *axis_b, double t,
                  double alpha, double *qb)
{
  double n[3], c[3], p0[4], pr[4], Ra[9], Rb[9], ya[3], yb[3], rot[3];
  int i;
  Unit(axis_a, n);
  Unit(axis_b, c);
  AlignQuat(c, n, p0);
  for (i = 0; i < 3; i++) rot[i] = alpha * c[i];
  LGNQuaternionFromRotationVector(rot, pr);
  LGNQuaternionMultiply(qa + 3, p0, qb + 3);
  LGNQuaternionMultiply(qb + 3, pr, qb + 3);
  LGNQuaternionToRotation(qa + 3, Ra);
  LGNQuaternionToRotation(qb + 3, Rb);
  for (i = 0; i < 3; i++) {
    ya[i] = Ra[3 * i] * sa[0] + Ra[3 * i + 1] * sa[1] + Ra[3 * i + 2] * sa[2];
    yb[i] = Rb[3 * i] * sb[0] + Rb[3 * i + 1] * sb[1] + Rb[3 * i + 2] * sb[2];
  }
  for (i = 0; i < 3; i++)
    qb[i] = qa[i] + ya[i] + t * (Ra[3 * i] * n[0] + Ra[3 * i + 1] * n[1] + Ra[3 * i + 2] * n[2]) - yb[i];
}

static int RunSlider(SUNContext ctx);

int main(void)
{
  SUNContext ctx;
  LGNGroup body[2], G, f4[4];
  LGNJoints J;
  sunindextype nv, m, i, j;
  N_Vector q, qp, qm, v, lam, phi_p, phi_m, z, fvec;
  SUNMatrix B, Bp, Bm, K, S;
  int trial;
  char buf[128];
  double *qd;

  SUNContext_Create(NULL, &ctx);
  srand(21);
  body[0] = LGNGroup_R3xSO3();
  body[1] = LGNGroup_SE3();
  f4[0] = body[0]; f4[1] = body[1]; f4[2] = body[0]; f4[3] = body[1];
  G  = LGNGroup_Product(4, f4);
  nv = G->nv;

  /* --- residual zero at consistent configurations ------------------------ */
  {
    double err = 0;
    q = N_VNew_Serial(G->nq, ctx);
    qd = N_VGetArrayPointer(q);
    for (trial = 0; trial < 10; trial++) {
      LGNJoints Jp = LGNJoints_Create(G), Jc = LGNJoints_Create(G);
      N_Vector ph;
      RandomConfiguration(4, qd);
      Place(qd, axy, ax, 0.7 * Rand(), 0.0, qd + 7);        /* 0 -> 1 prismatic */
      Place(qd + 14, ax, ax, 0.7 * Rand(), 0.0, qd + 21);   /* 2 -> 3 prismatic */
      LGNJoints_AddPrismatic(Jp, 0, sa, axy, 1, sb, ax);
      LGNJoints_AddPrismatic(Jp, 2, sa, ax, 3, sb, ax);
      ph = N_VNew_Serial(LGNJoints_NumConstraints(Jp), ctx);
      LGNJoints_Residual(Jp, 0.0, q, ph);
      err = fmax(err, N_VMaxNorm(ph));
      N_VDestroy(ph);
      Place(qd, ay, axy, 0.7 * Rand(), 3 * Rand(), qd + 7);  /* cylindrical */
      Place(qd + 14, ax, ax, 0.7 * Rand(), 3 * Rand(), qd + 21);
      LGNJoints_AddCylindrical(Jc, 0, sa, ay, 1, sb, axy);
      LGNJoints_AddCylindrical(Jc, 2, sa, ax, 3, sb, ax);
      ph = N_VNew_Serial(LGNJoints_NumConstraints(Jc), ctx);
      LGNJoints_Residual(Jc, 0.0, q, ph);
      err = fmax(err, N_VMaxNorm(ph));
      N_VDestroy(ph);
      if (LGNJoints_NumConstraints(Jp) != 10 || LGNJoints_NumConstraints(Jc) != 8) failures++;
      /* and not zero when the body turns about the axis (prismatic only) */
      if (trial == 0) {
        LGNJoints_Destroy(&Jc);
        Place(qd, axy, ax, 0.3, 0.2, qd + 7);
        ph = N_VNew_Serial(10, ctx);
        LGNJoints_Residual(Jp, 0.0, q, ph);
        printf("prismatic turned by 0.2 about its axis: |Phi| = %.3e\n", N_VMaxNorm(ph));
        if (!(N_VMaxNorm(ph) > 0.05)) failures++;
        N_VDestroy(ph);
      }
      LGNJoints_Destroy(&Jp);
      LGNJoints_Destroy(&Jc);
    }
    Check("Phi = 0 at consistent configurations (10 each)", err, 1e-14);
  }

  /* --- derivatives ------------------------------------------------------ */
  J = LGNJoints_Create(G);
  LGNJoints_AddPrismatic(J, 0, sa, axy, 1, sb, ax);
  LGNJoints_AddCylindrical(J, 1, sb, ay, 2, sa, axy);
  LGNJoints_AddPrismatic(J, LGN_GROUND, sa, ax, 3, sb, ay);
  LGNJoints_AddCylindrical(J, 2, sa, ay, LGN_GROUND, sb, ax);
  LGNJoints_AddRevolute(J, 3, sa, ax, 0, sb, ay); /* mixed with the old kinds */
  m = LGNJoints_NumConstraints(J);
  if (m != 5 + 4 + 5 + 4 + 5) {
    printf("m = %lld\n", (long long)m);
    failures++;
  }
  qp = N_VNew_Serial(G->nq, ctx);
  qm = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(nv, ctx);
  lam = N_VNew_Serial(m, ctx);
  phi_p = N_VNew_Serial(m, ctx);
  phi_m = N_VNew_Serial(m, ctx);
  z = N_VNew_Serial(m, ctx);
  fvec = N_VNew_Serial(nv, ctx);
  B = SUNDenseMatrix(m, nv, ctx);
  Bp = SUNDenseMatrix(m, nv, ctx);
  Bm = SUNDenseMatrix(m, nv, ctx);
  K = SUNDenseMatrix(nv, nv, ctx);
  {
    double errB = 0, errZ = 0, errK = 0, errF = 0, errS = 0, scaleB = 0, scaleZ = 0, scaleK = 0;
    const double eps = 1e-6;
    double w[24], yp[24], ym[24], btl[24];
    for (trial = 0; trial < 5; trial++) {
      RandomConfiguration(4, qd);
      for (i = 0; i < nv; i++) N_VGetArrayPointer(v)[i] = 2 * Rand();
      for (i = 0; i < m; i++) N_VGetArrayPointer(lam)[i] = 10 * Rand();
      SUNMatZero(B);
      LGNJoints_Jacobian(J, 0.0, q, B);
      SUNMatZero(K);
      LGNJoints_Stiffness(J, 0.0, q, lam, K);
      LGNJoints_Curvature(J, 0.0, q, v, z);
      for (j = 0; j < nv; j++) {
        for (i = 0; i < nv; i++) w[i] = (i == j) ? eps : 0.0;
        LGNGroup_ComposeExp(G, qd, w, N_VGetArrayPointer(qp));
        for (i = 0; i < nv; i++) w[i] = -w[i];
        LGNGroup_ComposeExp(G, qd, w, N_VGetArrayPointer(qm));
        LGNJoints_Residual(J, 0.0, qp, phi_p);
        LGNJoints_Residual(J, 0.0, qm, phi_m);
        for (i = 0; i < m; i++) {
          const double dq = (N_VGetArrayPointer(phi_p)[i] - N_VGetArrayPointer(phi_m)[i]) / (2 * eps);
          errB = fmax(errB, fabs(dq - SM_ELEMENT_D(B, i, j)));
          scaleB = fmax(scaleB, fabs(SM_ELEMENT_D(B, i, j)));
        }
        SUNMatZero(Bp);
        SUNMatZero(Bm);
        LGNJoints_Jacobian(J, 0.0, qp, Bp);
        LGNJoints_Jacobian(J, 0.0, qm, Bm);
        DenseApply(Bp, N_VGetArrayPointer(lam), yp, 1);
        DenseApply(Bm, N_VGetArrayPointer(lam), ym, 1);
        for (i = 0; i < nv; i++) {
          const double dq = (yp[i] - ym[i]) / (2 * eps);
          errK = fmax(errK, fabs(dq - SM_ELEMENT_D(K, i, j)));
          scaleK = fmax(scaleK, fabs(SM_ELEMENT_D(K, i, j)));
        }
      }
      /* Z = d/de B(q o exp(e v)) v */
      for (i = 0; i < nv; i++) w[i] = eps * N_VGetArrayPointer(v)[i];
      LGNGroup_ComposeExp(G, qd, w, N_VGetArrayPointer(qp));
      for (i = 0; i < nv; i++) w[i] = -w[i];
      LGNGroup_ComposeExp(G, qd, w, N_VGetArrayPointer(qm));
      SUNMatZero(Bp);
      SUNMatZero(Bm);
      LGNJoints_Jacobian(J, 0.0, qp, Bp);
      LGNJoints_Jacobian(J, 0.0, qm, Bm);
      DenseApply(Bp, N_VGetArrayPointer(v), yp, 0);
      DenseApply(Bm, N_VGetArrayPointer(v), ym, 0);
      for (i = 0; i < m; i++) {
        errZ = fmax(errZ, fabs((yp[i] - ym[i]) / (2 * eps) - N_VGetArrayPointer(z)[i]));
        scaleZ = fmax(scaleZ, fabs(N_VGetArrayPointer(z)[i]));
      }
      /* f = B^T lambda */
      DenseApply(B, N_VGetArrayPointer(lam), btl, 1);
      N_VConst(NAN, fvec);
      LGNJoints_ConstraintForce(J, 0.0, q, lam, fvec);
      for (i = 0; i < nv; i++) errF = fmax(errF, fabs(N_VGetArrayPointer(fvec)[i] - btl[i]));
      /* sparse B and K, CSC and CSR, from too small matrices */
      {
        int fmt;
        for (fmt = 0; fmt < 2; fmt++) {
          const int type = fmt == 0 ? CSC_MAT : CSR_MAT;
          S = SUNSparseMatrix(m, nv, 1, type, ctx);
          LGNJoints_Jacobian(J, 0.0, q, S);
          errS = fmax(errS, SparseVsDense(S, B));
          if (SUNSparseMatrix_IndexPointers(S)[SUNSparseMatrix_NP(S)] != LGNJoints_JacobianNnz(J)) failures++;
          SUNMatDestroy(S);
          S = SUNSparseMatrix(nv, nv, 1, type, ctx);
          LGNJoints_Stiffness(J, 0.0, q, lam, S);
          errS = fmax(errS, SparseVsDense(S, K));
          if (SUNSparseMatrix_IndexPointers(S)[SUNSparseMatrix_NP(S)] != LGNJoints_StiffnessNnz(J)) failures++;
          SUNMatDestroy(S);
        }
      }
    }
    Check("B against DQ of Phi (rel.)", errB / scaleB, 1e-8);
    Check("Z against DQ of B v (rel.)", errZ / scaleZ, 1e-8);
    Check("K against DQ of B^T lambda (rel.)", errK / scaleK, 1e-8);
    Check("f = B^T lambda without B", errF, 1e-13);
    Check("sparse B and K (CSC, CSR) = dense", errS, 0.0);
  }
  /* labels */
  LGNJoints_DescribeConstraint(J, 0, buf, sizeof buf);
  printf("row 0: %s\n", buf);
  if (strcmp(buf, "prismatic joint 0 (body 0 - body 1), its constraint 1 of 5") != 0) failures++;
  LGNJoints_DescribeConstraint(J, 8, buf, sizeof buf);
  printf("row 8: %s\n", buf);
  if (strcmp(buf, "cylindrical joint 1 (body 1 - body 2), its constraint 4 of 4") != 0) failures++;
  LGNJoints_DescribeConstraint(J, 9, buf, sizeof buf);
  if (strcmp(buf, "prismatic joint 2 (the ground - body 3), its constraint 1 of 5") != 0) failures++;
  /* bad input */
  {
    const double zero[3] = {0, 0, 0};
    LGNJoints_SetErrFile(J, NULL);
    if (LGNJoints_AddPrismatic(J, 0, sa, zero, 1, sb, ax) != LGN_ILL_INPUT ||
        LGNJoints_AddPrismatic(J, 0, sa, ax, 0, sb, ax) != LGN_ILL_INPUT ||
        LGNJoints_AddCylindrical(J, 0, NULL, ax, 1, sb, ax) != LGN_ILL_INPUT ||
        LGNJoints_AddCylindrical(NULL, 0, sa, ax, 1, sb, ax) != LGN_ILL_INPUT ||
        LGNJoints_NumConstraints(J) != m) {
      printf("bad input accepted\n");
      failures++;
    }
  }

  LGNJoints_Destroy(&J);
  N_VDestroy(q); N_VDestroy(qp); N_VDestroy(qm); N_VDestroy(v); N_VDestroy(lam);
  N_VDestroy(phi_p); N_VDestroy(phi_m); N_VDestroy(z); N_VDestroy(fvec);
  SUNMatDestroy(B); SUNMatDestroy(Bp); SUNMatDestroy(Bm); SUNMatDestroy(K);
  LGNGroup_Destroy(G);

  if (RunSlider(ctx) != 0) failures++;
  LGNGroup_Destroy(body[0]);
  LGNGroup_Destroy(body[1]);
  SUNContext_Free(&ctx);
  printf("%s\n", failures == 0 ? "PASSED" : "FAILED");
  return failures == 0 ? 0 : 1;
}

/* --- the slider --------------------------------------------------------- */

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Slider;

static int SMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Slider *)ud)->bodies);
}
static int SForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Slider *)ud)->bodies);
}
static int SConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Slider *)ud)->joints, t, q, phi) == 0 ? 0 : -1;
}
static int SJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Slider *)ud)->joints, t, q, B) == 0 ? 0 : -1;
}
static int SStiff(sunrealtype t, N_Vector q, N_Vector v, N_Vector vd, N_Vector lam,
                  SUNMatrix K, void *ud)
{
  Slider *s = (Slider *)ud;
  (void)vd;
  if (LGNJoints_Stiffness(s->joints, t, q, lam, K) != 0) return -1;
  return LGNBodies_Stiffness(s->bodies, q, v, K) == 0 ? 0 : -1;
}
static int SDamp(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  return LGNBodies_DampingFn(t, q, v, C, ((Slider *)ud)->bodies);
}
static int SCurv(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Slider *)ud)->joints, t, q, v, z) == 0 ? 0 : -1;
}

/* One SE(3) body (the harder case: gravity in body axes) sliding along the
 * tilted axis a (ground) with its frame turned: s(t) along a. */
static int RunSlider(SUNContext ctx)
{
  const double axis[3] = {1.0, 0.5, 2.0}, grav[3] = {0.3, -1.0, -9.81}, o[3] = {0.2, 0.1, -0.3};
  const double Jp[3] = {0.3, 0.5, 0.7}, s0 = 0.25, v0 = 0.8, tend = 1.0;
  double a[3], errmax = 0, ga;
  const sunindextype m = 5;
  int f, i, kind;
  for (kind = 0; kind < 2; kind++) {
    LGNGroup G = kind == 0 ? LGNGroup_SE3() : LGNGroup_R3xSO3();
    Slider sl;
    N_Vector q = N_VNew_Serial(7, ctx), v = N_VNew_Serial(6, ctx), tmpl = N_VNew_Serial(6 + m, ctx);
    SUNMatrix A = SUNDenseMatrix(6 + m, 6 + m, ctx);
    SUNLinearSolver LS = SUNLinSol_Dense(tmpl, A, ctx);
    void *mem = LGNCreate(ctx);
    double *qd = N_VGetArrayPointer(q), *vd = N_VGetArrayPointer(v), R[9];
    double ab[3], abraw[3] = {0.3, -0.5, 1.0}, t = 0, s, sexact;
    const double zero[3] = {0, 0, 0};
    Unit(axis, a);
    Unit(abraw, ab);
    ga = a[0] * grav[0] + a[1] * grav[1] + a[2] * grav[2];
    sl.bodies = LGNBodies_Create(G);
    sl.joints = LGNJoints_Create(G);
    LGNBodies_SetPrincipalInertia(sl.bodies, 0, 2.0, Jp);
    LGNBodies_SetGravity(sl.bodies, grav);
    /* the axis is ab in the body's frame: the joint locks R = R0, the
     * smallest rotation taking ab to a; the centre of mass (sb = 0) slides
     * on the line through o along a */
    AlignQuat(ab, a, qd + 3);
    LGNQuaternionToRotation(qd + 3, R);
    (void)R;
    LGNJoints_AddPrismatic(sl.joints, LGN_GROUND, o, a, 0, zero, ab);
    for (i = 0; i < 3; i++) qd[i] = o[i] + s0 * a[i];
    N_VConst(0.0, v);
    for (i = 0; i < 3; i++) vd[i] = v0 * (kind == 0 ? ab[i] : a[i]); /* SE(3): U = R^T xdot */
    f = LGNSetGroup(mem, G);
    if (!f) f = LGNSetUserData(mem, &sl);
    if (!f) f = LGNSetMassFn(mem, SMass);
    if (!f) f = LGNSetForceFn(mem, SForce);
    if (!f) f = LGNSetConstraints(mem, m, SConstr, SJac);
    if (!f) f = LGNSetStiffnessFn(mem, SStiff);
    if (!f) f = LGNSetDampingFn(mem, SDamp);
    if (!f) f = LGNSetCurvatureFn(mem, SCurv);
    if (!f) f = LGNInit(mem, 0.0, q, v);
    if (!f) f = LGNSetLinearSolver(mem, LS, A);
    if (!f) f = LGNSetGenAlpha(mem, 0.9);
    if (!f) f = LGNSetStepSize(mem, 0.01);
    if (!f) f = LGNSolve(mem, tend, &t, q, v, LGN_NORMAL);
    s = (qd[0] - o[0]) * a[0] + (qd[1] - o[1]) * a[1] + (qd[2] - o[2]) * a[2];
    sexact = s0 + v0 * t + 0.5 * ga * t * t;
    {
      double off = 0, d[3];
      for (i = 0; i < 3; i++) d[i] = qd[i] - o[i] - s * a[i];
      off = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      printf("slider (%s): flag %d, t = %g, s = %.15f, exact %.15f, off the line %.2e\n",
             kind == 0 ? "SE(3)" : "R^3 x SO(3)", f, t, s, sexact, off);
      errmax = fmax(errmax, fabs(s - sexact) + off + (f != 0 ? 1.0 : 0.0) + fabs(t - tend));
    }
    LGNFree(&mem);
    SUNLinSolFree(LS);
    SUNMatDestroy(A);
    N_VDestroy(q); N_VDestroy(v); N_VDestroy(tmpl);
    LGNBodies_Destroy(&sl.bodies);
    LGNJoints_Destroy(&sl.joints);
    LGNGroup_Destroy(G);
  }
  Check("slider: s(t) = s0 + v0 t + (g.a) t^2/2 at t = 1", errmax, 1e-9);
  return 0;
}
