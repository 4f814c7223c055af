/* -----------------------------------------------------------------------------
 * Planar bodies, force elements and joints (lignum_planar.h) on a product
 * of SE(2) and R^2 x SO(2) bodies, at random configurations:
 *  (a) joints (revolute, prismatic, both drivers, to bodies and to the
 *      ground): B against central quotients of Phi along the group, K
 *      against quotients of B^T lambda, f = B^T lambda, Phi_t against a
 *      quotient in t, the curvature against the quotient of B v + Phi_t
 *      along (q exp(s v), t + s); the revolute and prismatic rows vanish
 *      where the joints hold; sparse B and K (CSC, CSR) equal dense;
 *  (b) bodies: g at v = 0 against the quotients of the potential energy,
 *      K_t and C_t against quotients of g, sparse M, K, C equal dense; the
 *      SE(2) body's g against the R^2 x SO(2) body's for the same motion
 *      (U = R^T u: g_SE2 = R^T (g_R2 - m d/dt u) + m d/dt U, the same
 *      physics in two velocity coordinates);
 *  (c) bad input: spatial joints on a planar set and planar ones on a
 *      spatial set, bodies out of range, a mixed planar and spatial group,
 *      points off the plane, ghosts: all refused with LGN_ILL_INPUT.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_planar.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

static int failures = 0;

static void Check(const char *what, double err, double tol)
{
  const int ok = err <= tol;
  printf("%-64s %.3e (tol %.0e) %s\n", what, err, tol, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

static double Rand(void) { return 2.0 * rand() / (double)RAND_MAX - 1.0; }

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

#define NB 4
#define NV (3 * NB)

/* a sparse matrix as a dense array (column-major n x m) */
static void SparseToArray(SUNMatrix S, double *A, int rows, int cols)
{
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(S);
  const sunindextype *ind = SUNSparseMatrix_IndexValues(S);
  const sunrealtype *val = SUNSparseMatrix_Data(S);
  const int csc = SUNSparseMatrix_SparseType(S) == CSC_MAT;
  const int nmaj = csc ? cols : rows;
  int j;
  sunindextype p;
  memset(A, 0, sizeof(double) * (size_t)rows * (size_t)cols);
  for (j = 0; j < nmaj; j++)
    for (p = ptr[j]; p < ptr[j + 1]; p++) {
      if (csc) A[ind[p] + rows * j] += val[p];
      else A[j + rows * ind[p]] += val[p];
    }
}

static double DenseDiff(SUNMatrix D, const double *A, int rows, int cols)
{
  double e = 0;
  int i, j;
  for (j = 0; j < cols; j++)
    for (i = 0; i < rows; i++) e = fmax(e, fabs(SM_ELEMENT_D(D, i, j) - A[i + rows * j]));
  return e;
}

/* q o exp(s w) into qs */
static void Move(LGNGroup G, N_Vector q, const double *w, double s, N_Vector qs)
{
  double ws[NV];
  int i;
  for (i = 0; i < NV; i++) ws[i] = s * w[i];
  LGNGroup_ComposeExp(G, NV_DATA_S(q), ws, NV_DATA_S(qs));
}

static void JointChecks(SUNContext ctx, LGNGroup G, LGNJoints J, N_Vector q, N_Vector v,
                        double t)
{
  const sunindextype m = LGNJoints_NumConstraints(J);
  const double e = 1e-6;
  N_Vector qs = N_VClone(q), ph1 = N_VNew_Serial(m, ctx), ph2 = N_VNew_Serial(m, ctx);
  N_Vector lam = N_VNew_Serial(m, ctx), f1 = N_VClone(v), f2 = N_VClone(v), f = N_VClone(v);
  N_Vector z = N_VNew_Serial(m, ctx), pt = N_VNew_Serial(m, ctx), pt1 = N_VNew_Serial(m, ctx);
  N_Vector pt2 = N_VNew_Serial(m, ctx);
  SUNMatrix B = SUNDenseMatrix(m, NV, ctx), K = SUNDenseMatrix(NV, NV, ctx);
  SUNMatrix B1 = SUNDenseMatrix(m, NV, ctx), B2 = SUNDenseMatrix(m, NV, ctx);
  SUNMatrix Bs, Ks;
  double errB = 0, errK = 0, errF = 0, errZ = 0, errT = 0, *A, bv1, bv2;
  int i, j, fmt;
  for (i = 0; i < m; i++) NV_Ith_S(lam, i) = Rand();
  SUNMatZero(B);
  LGNJoints_Jacobian(J, t, q, B);
  SUNMatZero(K);
  LGNJoints_Stiffness(J, t, q, lam, K);
  for (j = 0; j < NV; j++) {
    double w[NV] = {0};
    w[j] = 1;
    Move(G, q, w, e, qs);
    LGNJoints_Residual(J, t, qs, ph1);
    LGNJoints_ConstraintForce(J, t, qs, lam, f1);
    Move(G, q, w, -e, qs);
    LGNJoints_Residual(J, t, qs, ph2);
    LGNJoints_ConstraintForce(J, t, qs, lam, f2);
    for (i = 0; i < m; i++)
      errB = fmax(errB, fabs((NV_Ith_S(ph1, i) - NV_Ith_S(ph2, i)) / (2 * e) -
                             SM_ELEMENT_D(B, i, j)));
    for (i = 0; i < NV; i++)
      errK = fmax(errK, fabs((NV_Ith_S(f1, i) - NV_Ith_S(f2, i)) / (2 * e) -
                             SM_ELEMENT_D(K, i, j)));
  }
  Check("joints: B against quotients of Phi", errB, 1e-8);
  Check("joints: K against quotients of B^T lambda", errK, 1e-8);
  LGNJoints_ConstraintForce(J, t, q, lam, f);
  for (j = 0; j < NV; j++) {
    double s = 0;
    for (i = 0; i < m; i++) s += SM_ELEMENT_D(B, i, j) * NV_Ith_S(lam, i);
    errF = fmax(errF, fabs(s - NV_Ith_S(f, j)));
  }
  Check("joints: ConstraintForce = B^T lambda", errF, 1e-14);
  /* Phi_t against a quotient in t */
  LGNJoints_TimeDerivative(J, t, q, pt);
  LGNJoints_Residual(J, t + e, q, ph1);
  LGNJoints_Residual(J, t - e, q, ph2);
  for (i = 0; i < m; i++)
    errT = fmax(errT, fabs((NV_Ith_S(ph1, i) - NV_Ith_S(ph2, i)) / (2 * e) - NV_Ith_S(pt, i)));
  Check("joints: Phi_t against a quotient in t", errT, 1e-8);
  /* curvature: d/ds (B v + Phi_t) along (q exp(s v), t + s) */
  LGNJoints_Curvature(J, t, q, v, z);
  Move(G, q, NV_DATA_S(v), e, qs);
  SUNMatZero(B1);
  LGNJoints_Jacobian(J, t + e, qs, B1);
  LGNJoints_TimeDerivative(J, t + e, qs, pt1);
  Move(G, q, NV_DATA_S(v), -e, qs);
  SUNMatZero(B2);
  LGNJoints_Jacobian(J, t - e, qs, B2);
  LGNJoints_TimeDerivative(J, t - e, qs, pt2);
  for (i = 0; i < m; i++) {
    bv1 = NV_Ith_S(pt1, i);
    bv2 = NV_Ith_S(pt2, i);
    for (j = 0; j < NV; j++) {
      bv1 += SM_ELEMENT_D(B1, i, j) * NV_Ith_S(v, j);
      bv2 += SM_ELEMENT_D(B2, i, j) * NV_Ith_S(v, j);
    }
    errZ = fmax(errZ, fabs((bv1 - bv2) / (2 * e) - NV_Ith_S(z, i)));
  }
  Check("joints: curvature against d/ds (B v + Phi_t)", errZ, 1e-7);
  /* sparse = dense, both formats, twice (the pattern is reused) */
  A = (double *)malloc(sizeof(double) * (size_t)(NV * (m > NV ? m : NV)));
  for (fmt = 0; fmt < 2; fmt++) {
    const int sp = fmt == 0 ? CSC_MAT : CSR_MAT;
    double eb = 0, ek = 0;
    Bs = SUNSparseMatrix(m, NV, 1, sp, ctx);
    Ks = SUNSparseMatrix(NV, NV, 1, sp, ctx);
    for (i = 0; i < 2; i++) {
      LGNJoints_Jacobian(J, t, q, Bs);
      SparseToArray(Bs, A, (int)m, NV);
      eb = fmax(eb, DenseDiff(B, A, (int)m, NV));
      SUNMatZero(Ks); /* a sparse term is added to what Ks holds */
      LGNJoints_Stiffness(J, t, q, lam, Ks);
      SparseToArray(Ks, A, NV, NV);
      ek = fmax(ek, DenseDiff(K, A, NV, NV));
    }
    /* the one rule: a second K added to the first = 2 K */
    LGNJoints_Stiffness(J, t, q, lam, Ks);
    SparseToArray(Ks, A, NV, NV);
    for (i = 0; i < NV * NV; i++) A[i] *= 0.5;
    Check(fmt == 0 ? "joints: K added to a sparse K (CSC) = 2 K"
                   : "joints: K added to a sparse K (CSR) = 2 K",
          DenseDiff(K, A, NV, NV), 1e-14);
    Check(fmt == 0 ? "joints: sparse B, K (CSC) = dense" : "joints: sparse B, K (CSR) = dense",
          fmax(eb, ek), 1e-15);
    Check("joints: JacobianNnz = stored entries of B",
          fabs((double)LGNJoints_JacobianNnz(J) -
               (double)SUNSparseMatrix_IndexPointers(Bs)[fmt == 0 ? NV : m]), 0);
    Check("joints: StiffnessNnz = stored entries of K",
          fabs((double)LGNJoints_StiffnessNnz(J) - (double)SUNSparseMatrix_IndexPointers(Ks)[NV]),
          0);
    SUNMatDestroy(Bs);
    SUNMatDestroy(Ks);
  }
  free(A);
  N_VDestroy(qs); N_VDestroy(ph1); N_VDestroy(ph2); N_VDestroy(lam); N_VDestroy(f1);
  N_VDestroy(f2); N_VDestroy(f); N_VDestroy(z); N_VDestroy(pt); N_VDestroy(pt1);
  N_VDestroy(pt2);
  SUNMatDestroy(B); SUNMatDestroy(K); SUNMatDestroy(B1); SUNMatDestroy(B2);
}

static void BodyChecks(SUNContext ctx, LGNGroup G, LGNBodies Bd, N_Vector q, N_Vector v)
{
  const double e = 1e-6;
  N_Vector qs = N_VClone(q), g = N_VClone(v), g1 = N_VClone(v), g2 = N_VClone(v);
  N_Vector vs = N_VClone(v), v0 = N_VClone(v);
  SUNMatrix K = SUNDenseMatrix(NV, NV, ctx), C = SUNDenseMatrix(NV, NV, ctx);
  SUNMatrix M = SUNDenseMatrix(NV, NV, ctx), S;
  double errK = 0, errC = 0, errP = 0, V1, V2, A[NV * NV], gmax = 1, kmax = 1;
  int i, j, fmt;
  N_VConst(0, v0);
  SUNMatZero(K);
  LGNBodies_Stiffness(Bd, q, v, K);
  SUNMatZero(C);
  LGNBodies_Damping(Bd, q, v, C);
  SUNMatZero(M);
  LGNBodies_Mass(Bd, q, M);
  LGNBodies_Force(Bd, q, v0, g);
  for (j = 0; j < NV; j++) {
    double w[NV] = {0};
    w[j] = 1;
    Move(G, q, w, e, qs);
    LGNBodies_Force(Bd, qs, v, g1);
    LGNBodies_Energy(Bd, qs, v0, NULL, &V1);
    Move(G, q, w, -e, qs);
    LGNBodies_Force(Bd, qs, v, g2);
    LGNBodies_Energy(Bd, qs, v0, NULL, &V2);
    for (i = 0; i < NV; i++)
      errK = fmax(errK, fabs((NV_Ith_S(g1, i) - NV_Ith_S(g2, i)) / (2 * e) -
                             SM_ELEMENT_D(K, i, j)));
    errP = fmax(errP, fabs((V1 - V2) / (2 * e) - NV_Ith_S(g, j)));
    N_VScale(1, v, vs);
    NV_Ith_S(vs, j) += e;
    LGNBodies_Force(Bd, q, vs, g1);
    NV_Ith_S(vs, j) -= 2 * e;
    LGNBodies_Force(Bd, q, vs, g2);
    for (i = 0; i < NV; i++)
      errC = fmax(errC, fabs((NV_Ith_S(g1, i) - NV_Ith_S(g2, i)) / (2 * e) -
                             SM_ELEMENT_D(C, i, j)));
  }
  /* relative to the largest entry: the quotients lose eps |V| / e */
  for (i = 0; i < NV; i++) {
    gmax = fmax(gmax, fabs(NV_Ith_S(g, i)));
    for (j = 0; j < NV; j++)
      kmax = fmax(kmax, fmax(fabs(SM_ELEMENT_D(K, i, j)), fabs(SM_ELEMENT_D(C, i, j))));
  }
  Check("bodies: g(q, 0) against quotients of the potential (rel.)", errP / gmax, 1e-9);
  Check("bodies: K_t against quotients of g (relative)", errK / kmax, 1e-9);
  Check("bodies: C_t against quotients of g (relative)", errC / kmax, 1e-9);
  for (fmt = 0; fmt < 2; fmt++) {
    const int sp = fmt == 0 ? CSC_MAT : CSR_MAT;
    double em, ek, ec;
    S = SUNSparseMatrix(NV, NV, 1, sp, ctx);
    LGNBodies_Mass(Bd, q, S);
    SparseToArray(S, A, NV, NV);
    em = DenseDiff(M, A, NV, NV);
    SUNMatZero(S); /* a sparse term is added to what S holds */
    LGNBodies_Stiffness(Bd, q, v, S);
    SparseToArray(S, A, NV, NV);
    ek = DenseDiff(K, A, NV, NV);
    SUNMatZero(S);
    LGNBodies_Damping(Bd, q, v, S);
    SparseToArray(S, A, NV, NV);
    ec = DenseDiff(C, A, NV, NV);
    Check(fmt == 0 ? "bodies: sparse M, K, C (CSC) = dense" : "bodies: sparse M, K, C (CSR) = dense",
          fmax(em, fmax(ek, ec)), 1e-15);
    Check("bodies: TangentNnz = stored entries",
          fabs((double)LGNBodies_TangentNnz(Bd) - (double)SUNSparseMatrix_IndexPointers(S)[NV]), 0);
    /* the one rule: K_t then C_t into one sparse matrix = their dense sum */
    SUNMatZero(S);
    LGNBodies_Stiffness(Bd, q, v, S);
    LGNBodies_Damping(Bd, q, v, S);
    SparseToArray(S, A, NV, NV);
    {
      SUNMatrix KC = SUNDenseMatrix(NV, NV, ctx);
      SUNMatZero(KC);
      LGNBodies_Stiffness(Bd, q, v, KC);
      LGNBodies_Damping(Bd, q, v, KC);
      Check(fmt == 0 ? "bodies: K_t + C_t added into one sparse (CSC) = dense sum"
                     : "bodies: K_t + C_t added into one sparse (CSR) = dense sum",
            DenseDiff(KC, A, NV, NV), 1e-14);
      SUNMatDestroy(KC);
    }
    SUNMatDestroy(S);
  }
  N_VDestroy(qs); N_VDestroy(g); N_VDestroy(g1); N_VDestroy(g2); N_VDestroy(vs); N_VDestroy(v0);
  SUNMatDestroy(K); SUNMatDestroy(C); SUNMatDestroy(M);
}

/* One free body under gravity and a spring to the ground, on SE(2) and on
 * R^2 x SO(2), with the same motion: u = R U. M vdot + g = 0 on both, so
 * vdot_SE2 = R^T (vdot_R2 - omega J u) must hold (d/dt U = R^T (udot -
 * omega J u)): the two g's describe the same dynamics. */
static void SE2AgainstR2(SUNContext ctx)
{
  LGNGroup G2 = LGNGroup_SE2(), G1 = LGNGroup_R2xSO2();
  LGNBodies B2 = LGNBodies_Create(G2), B1 = LGNBodies_Create(G1);
  const sunrealtype grav[3] = {0.3, -9.81, 0}, s[2] = {0.4, -0.2}, o[2] = {1, 2};
  N_Vector q = N_VNew_Serial(3, ctx), u1 = N_VNew_Serial(3, ctx), u2 = N_VNew_Serial(3, ctx);
  N_Vector g1 = N_VNew_Serial(3, ctx), g2 = N_VNew_Serial(3, ctx);
  const double th = 0.7, m = 2.5, Jz = 0.3, c = cos(th), sn = sin(th);
  double a1[3], a2[3], r0, r1, err;
  NV_Ith_S(q, 0) = 0.3;
  NV_Ith_S(q, 1) = -0.4;
  NV_Ith_S(q, 2) = th;
  NV_Ith_S(u1, 0) = 1.1;
  NV_Ith_S(u1, 1) = -0.6;
  NV_Ith_S(u1, 2) = 0.9;
  NV_Ith_S(u2, 0) = c * 1.1 + sn * -0.6; /* U = R^T u */
  NV_Ith_S(u2, 1) = -sn * 1.1 + c * -0.6;
  NV_Ith_S(u2, 2) = 0.9;
  LGNBodies_SetPlanarMass(B1, 0, m, Jz);
  LGNBodies_SetPlanarMass(B2, 0, m, Jz);
  LGNBodies_SetGravity(B1, grav);
  LGNBodies_SetGravity(B2, grav);
  LGNBodies_AddPlanarSpringDamper(B1, LGN_GROUND, o, 0, s, 40, 0.7, 0.5);
  LGNBodies_AddPlanarSpringDamper(B2, LGN_GROUND, o, 0, s, 40, 0.7, 0.5);
  LGNBodies_Force(B1, q, u1, g1);
  LGNBodies_Force(B2, q, u2, g2);
  a1[0] = -NV_Ith_S(g1, 0) / m; /* udot */
  a1[1] = -NV_Ith_S(g1, 1) / m;
  a1[2] = -NV_Ith_S(g1, 2) / Jz;
  a2[0] = -NV_Ith_S(g2, 0) / m; /* Udot */
  a2[1] = -NV_Ith_S(g2, 1) / m;
  a2[2] = -NV_Ith_S(g2, 2) / Jz;
  /* R^T (udot - omega J u), J u = (-u1, u0) */
  r0 = a1[0] + 0.9 * -0.6;
  r1 = a1[1] - 0.9 * 1.1;
  err = fmax(fabs(c * r0 + sn * r1 - a2[0]), fabs(-sn * r0 + c * r1 - a2[1]));
  err = fmax(err, fabs(a1[2] - a2[2]));
  Check("bodies: SE(2) dynamics = R^2 x SO(2) dynamics (same motion)", err, 1e-13);
  N_VDestroy(q); N_VDestroy(u1); N_VDestroy(u2); N_VDestroy(g1); N_VDestroy(g2);
  LGNBodies_Destroy(&B1);
  LGNBodies_Destroy(&B2);
  LGNGroup_Destroy(G1);
  LGNGroup_Destroy(G2);
}

static void Silent(int code, const char *module, const char *function, const char *msg, void *d)
{
  (void)code; (void)module; (void)function; (void)msg;
  ++*(int *)d;
}

static void BadInput(SUNContext ctx, LGNJoints J, LGNBodies Bd)
{
  const sunrealtype p3[3] = {0, 0, 0}, z3[3] = {0, 0, 1}, x3[3] = {1, 0, 0}, off[3] = {0, 0, 1};
  const sunrealtype p2[2] = {0, 0}, a2[2] = {1, 0}, nan2[2] = {NAN, 0}, zero2[2] = {0, 0};
  const sunrealtype inert[3] = {1, 1, 1}, g3[3] = {0, 0, -9.81};
  LGNGroup se3 = LGNGroup_SE3(), se2 = LGNGroup_SE2(), mix[2], Gm;
  LGNJoints Js = LGNJoints_Create(se3);
  LGNBodies Bs = LGNBodies_Create(se3);
  const sunindextype m0 = LGNJoints_NumConstraints(J);
  int n = 0, bad = 0;
  N_Vector q = N_VNew_Serial(NV, ctx), phi = N_VNew_Serial(m0 + 1, ctx);
  (void)LGNJoints_SetErrHandlerFn(Js, Silent, &n);
  (void)LGNBodies_SetErrHandlerFn(Bs, Silent, &n);
  (void)LGNJoints_SetErrHandlerFn(J, Silent, &n);
  (void)LGNBodies_SetErrHandlerFn(Bd, Silent, &n);
  bad += LGNJoints_AddSpherical(J, 0, p3, 1, p3) != LGN_ILL_INPUT;
  bad += LGNJoints_AddUniversal(J, 0, p3, z3, 1, p3, x3) != LGN_ILL_INPUT;
  bad += LGNJoints_AddPrismatic(J, 0, p3, x3, 1, p3, x3) != LGN_ILL_INPUT;
  bad += LGNJoints_AddRevolute(J, 0, p3, x3, 1, p3, x3) != LGN_ILL_INPUT; /* axis not z */
  bad += LGNJoints_AddRevolute(J, 0, off, z3, 1, p3, z3) != LGN_ILL_INPUT; /* off the plane */
  bad += LGNJoints_AddPlanarRevolute(J, 0, p2, NB, p2) != LGN_ILL_INPUT;   /* out of range */
  bad += LGNJoints_AddPlanarRevolute(J, -2, p2, 1, p2) != LGN_ILL_INPUT;
  bad += LGNJoints_AddPlanarRevolute(J, 1, p2, 1, p2) != LGN_ILL_INPUT;    /* a = b */
  bad += LGNJoints_AddPlanarRevolute(J, 0, nan2, 1, p2) != LGN_ILL_INPUT;
  bad += LGNJoints_AddPlanarPrismatic(J, 0, p2, zero2, 1, p2, 0) != LGN_ILL_INPUT;
  bad += LGNJoints_AddPlanarPrismatic(J, 0, p2, a2, 1, p2, NAN) != LGN_ILL_INPUT;
  bad += LGNJoints_AddPlanarRotationDriver(J, 0, 1, NULL, NULL) != LGN_ILL_INPUT;
  bad += LGNJoints_AddPlanarTranslationDriver(J, 0, p2, a2, 7, p2, TransLaw, NULL) != LGN_ILL_INPUT;
  bad += LGNJoints_AddPlanarRevolute(Js, 0, p2, LGN_GROUND, p2) != LGN_ILL_INPUT; /* spatial */
  bad += LGNJoints_AddPlanarRevolute(NULL, 0, p2, LGN_GROUND, p2) != LGN_ILL_INPUT;
  bad += LGNJoints_Residual(J, 0, q, phi) != LGN_ILL_INPUT; /* wrong length */
  bad += LGNJoints_NumConstraints(J) != m0;                 /* nothing added */
  bad += LGNBodies_SetPlanarMass(Bd, NB, 1, 1) != LGN_ILL_INPUT;
  bad += LGNBodies_SetPlanarMass(Bd, 0, -1, 1) != LGN_ILL_INPUT;
  bad += LGNBodies_SetPlanarMass(Bd, 0, 1, 0) != LGN_ILL_INPUT;
  bad += LGNBodies_SetPlanarMass(Bs, 0, 1, 1) != LGN_ILL_INPUT; /* spatial set */
  bad += LGNBodies_SetPrincipalInertia(Bs, 0, 1, inert) != LGN_SUCCESS;
  bad += LGNBodies_SetGravity(Bd, g3) != LGN_ILL_INPUT;          /* off the plane */
  bad += LGNBodies_AddSpringDamper(Bd, 0, off, 1, p3, 1, 0, 0) != LGN_ILL_INPUT;
  bad += LGNBodies_AddPlanarSpringDamper(Bd, 0, p2, 0, p2, 1, 0, 0) != LGN_ILL_INPUT;
  bad += LGNBodies_AddPlanarSpringDamper(Bd, 0, p2, 1, p2, -1, 0, 0) != LGN_ILL_INPUT;
  bad += LGNBodies_AddPlanarRotationalSpringDamper(Bd, 0, NB, 1, 0, 0) != LGN_ILL_INPUT;
  bad += LGNBodies_AddPlanarRotationalSpringDamper(Bs, 0, 1, 1, 0, 0) != LGN_ILL_INPUT;
  bad += LGNBodies_SetGhosts(Bd, 1) != LGN_ILL_INPUT;
  Check("bad input refused (count of wrong answers)", bad, 0);
  /* 29 calls: all but three (the valid spatial SetPrincipalInertia, the
   * count, and J = NULL, which goes to stderr) report through a handler */
  Check("every refusal reported through the set's handler", fabs(n - 26.0), 0);
  /* a group mixing planar and spatial bodies has no body or joint set */
  mix[0] = se2;
  mix[1] = se3;
  Gm = LGNGroup_Product(2, mix);
  fprintf(stderr, "(two messages expected next)\n");
  Check("mixed planar and spatial group refused",
        (LGNJoints_Create(Gm) != NULL) + (LGNBodies_Create(Gm) != NULL), 0);
  LGNGroup_Destroy(Gm);
  LGNJoints_Destroy(&Js);
  LGNBodies_Destroy(&Bs);
  LGNGroup_Destroy(se3);
  LGNGroup_Destroy(se2);
  N_VDestroy(q);
  N_VDestroy(phi);
}

int main(void)
{
  SUNContext ctx;
  LGNGroup se2 = LGNGroup_SE2(), r2 = LGNGroup_R2xSO2(), fac[NB], G;
  LGNJoints J;
  LGNBodies Bd;
  N_Vector q, v;
  const sunrealtype s0[2] = {0.3, -0.1}, s1[2] = {-0.5, 0.2}, s2[2] = {0.1, 0.4};
  const sunrealtype ax[2] = {0.6, 0.8}, ax2[2] = {-1, 0.3}, o[2] = {1.0, -0.5};
  const sunrealtype grav[3] = {0.5, -9.81, 0};
  int r, k;
  srand(2026);
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  fac[0] = se2;
  fac[1] = r2;
  fac[2] = se2;
  fac[3] = r2;
  G  = LGNGroup_Product(NB, fac);
  J  = LGNJoints_Create(G);
  Bd = LGNBodies_Create(G);
  if (J == NULL || Bd == NULL) return 1;
  /* joints to the ground and between SE(2) and R^2 x SO(2) bodies */
  LGNJoints_AddPlanarRevolute(J, LGN_GROUND, o, 0, s0);
  LGNJoints_AddPlanarRevolute(J, 0, s1, 1, s2);
  LGNJoints_AddPlanarPrismatic(J, 1, s0, ax, 2, s1, 0.3);
  LGNJoints_AddPlanarPrismatic(J, LGN_GROUND, o, ax2, 3, s2, -0.2);
  LGNJoints_AddPlanarRotationDriver(J, 2, 3, RotLaw, NULL);
  LGNJoints_AddPlanarRotationDriver(J, LGN_GROUND, 0, RotLaw, NULL);
  LGNJoints_AddPlanarTranslationDriver(J, 3, s2, ax, 0, s1, TransLaw, NULL);
  LGNJoints_AddPlanarTranslationDriver(J, 2, s0, ax2, LGN_GROUND, o, TransLaw, NULL);
  {
    const sunrealtype z3[3] = {0, 0, 2}, p3[3] = {0.2, 0.1, 0}, p3b[3] = {-0.3, 0, 0};
    LGNJoints_AddRevolute(J, 1, p3, z3, 3, p3b, z3); /* the spatial call, planar axes */
  }
  Check("joints: 2+2+2+2+1+1+1+1+2 rows", fabs((double)LGNJoints_NumConstraints(J) - 14), 0);
  Check("joints: 4 drivers", fabs((double)LGNJoints_NumDrivers(J) - 4), 0);
  {
    char buf[128];
    LGNJoints_DescribeConstraint(J, 3, buf, sizeof buf);
    printf("row 3: %s\n", buf);
    Check("describe: row 3 is the revolute joint 1's second",
          strcmp(buf, "planar revolute joint 1 (body 0 - body 1), its constraint 2 of 2") != 0, 0);
  }
  for (k = 0; k < NB; k++) LGNBodies_SetPlanarMass(Bd, k, 1 + k, 0.2 + 0.1 * k);
  LGNBodies_SetGravity(Bd, grav);
  LGNBodies_AddPlanarSpringDamper(Bd, LGN_GROUND, o, 0, s1, 30, 0.4, 0.3);
  LGNBodies_AddPlanarSpringDamper(Bd, 1, s0, 2, s2, 20, 0.7, 0.1);
  LGNBodies_AddPlanarSpringDamper(Bd, 3, s0, 0, s2, 10, 0.0, 0.8);
  LGNBodies_AddPlanarRotationalSpringDamper(Bd, 0, 3, 5, 0.3, 0.4);
  LGNBodies_AddPlanarRotationalSpringDamper(Bd, LGN_GROUND, 2, 3, 0.2, -0.1);
  q = N_VNew_Serial(NV, ctx);
  v = N_VNew_Serial(NV, ctx);
  for (r = 0; r < 3; r++) {
    for (k = 0; k < NV; k++) {
      NV_Ith_S(q, k) = 2 * Rand();
      NV_Ith_S(v, k) = 2 * Rand();
    }
    JointChecks(ctx, G, J, q, v, 0.7 + r);
    BodyChecks(ctx, G, Bd, q, v);
  }
  /* where the joints hold, their rows vanish */
  {
    LGNGroup G1 = LGNGroup_Product(2, fac);
    LGNJoints J1 = LGNJoints_Create(G1);
    N_Vector q1 = N_VNew_Serial(6, ctx), ph = N_VNew_Serial(4, ctx);
    const double th0 = 0.4, th1 = 1.1, c0 = cos(th0), sn0 = sin(th0);
    const double x1 = 0.7, y1 = -0.2;
    LGNJoints_AddPlanarRevolute(J1, 0, s0, 1, s1);
    LGNJoints_AddPlanarPrismatic(J1, 0, s0, ax, 1, s1, th1 - th0);
    NV_Ith_S(q1, 0) = x1; NV_Ith_S(q1, 1) = y1; NV_Ith_S(q1, 2) = th0;
    /* body 1 with p_1 = p_0: x_1 = x_0 + R0 s0 - R1 s1 */
    NV_Ith_S(q1, 3) = x1 + c0 * s0[0] - sn0 * s0[1] - (cos(th1) * s1[0] - sin(th1) * s1[1]);
    NV_Ith_S(q1, 4) = y1 + sn0 * s0[0] + c0 * s0[1] - (sin(th1) * s1[0] + cos(th1) * s1[1]);
    NV_Ith_S(q1, 5) = th1;
    LGNJoints_Residual(J1, 0, q1, ph);
    Check("joints hold: revolute and prismatic rows vanish", N_VMaxNorm(ph), 1e-15);
    N_VDestroy(q1);
    N_VDestroy(ph);
    LGNJoints_Destroy(&J1);
    LGNGroup_Destroy(G1);
  }
  SE2AgainstR2(ctx);
  BadInput(ctx, J, Bd);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNJoints_Destroy(&J);
  LGNBodies_Destroy(&Bd);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(se2);
  LGNGroup_Destroy(r2);
  SUNContext_Free(&ctx);
  printf("%s: %d failure(s)\n", failures ? "FAILED" : "PASSED", failures);
  return failures ? 1 : 0;
}
