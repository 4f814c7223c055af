/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Unit test of the joint helpers (lignum_joints.h) on a product
 * R^3xSO(3) x SE(3) x R^3xSO(3) x SE(3) at random configurations, against
 * central differences along the group (an independent computation from Phi
 * alone):
 *   B w          = d/de Phi(q o exp(e w))
 *   Z(q)(v, v)   = d/de B(q o exp(e v)) v
 *   K w          = d/de B(q o exp(e w))^T lambda
 * and the sparse B and K (CSC and CSR) against the dense ones, entry by entry.
 * The constraint forces f = B^T lambda, computed without B, are checked
 * against the dense B times lambda to round-off, on f garbled before each
 * call, also with bodies in no joint (f = 0 there) and no joints at all.
 * The sparse B keeps its pattern between calls: it is checked at new
 * configurations on matrices left empty and garbled between calls, CSC and
 * CSR in turn with the same joints, after joints are added, and on
 * matrices too small for it.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "rigid_test_util.h"

static int failures = 0;

static void Check(const char *what, double err, double tol)
{
  printf("%-44s max error %.3e (tol %.1e) %s\n", what, err, tol,
         err <= tol ? "ok" : "FAIL");
  if (!(err <= tol)) failures++;
}

/* Leave a sparse matrix as a caller may between calls: no entries (index
 * pointers zeroed, as Lignum does before an LGNConstrJacFn), wrong but
 * valid indices and NaN data in all of its capacity. */
static void Garble(SUNMatrix S)
{
  const sunindextype n = SUNSparseMatrix_SparseType(S) == CSC_MAT
                             ? SUNSparseMatrix_Rows(S) : SUNSparseMatrix_Columns(S);
  sunindextype k;
  for (k = 0; k <= SUNSparseMatrix_NP(S); k++) SUNSparseMatrix_IndexPointers(S)[k] = 0;
  for (k = 0; k < SUNSparseMatrix_NNZ(S); k++) {
    SUNSparseMatrix_IndexValues(S)[k] = (7 * k + 3) % n;
    SUNSparseMatrix_Data(S)[k] = NAN;
  }
}

/* max |S - D| of the sparse B of J at q against the dense one D, S first
 * garbled; -1 if S does not hold exactly LGNJoints_JacobianNnz(J) entries
 * or has less room. */
static double SparseJacobianError(LGNJoints J, N_Vector q, SUNMatrix S, SUNMatrix D)
{
  const sunindextype nnz = LGNJoints_JacobianNnz(J);
  SUNMatZero(D);
  if (LGNJoints_Jacobian(J, 0.0, q, D) != LGN_SUCCESS) return -1;
  Garble(S);
  if (LGNJoints_Jacobian(J, 0.0, q, S) != LGN_SUCCESS ||
      SUNSparseMatrix_IndexPointers(S)[SUNSparseMatrix_NP(S)] != nnz ||
      SUNSparseMatrix_NNZ(S) < nnz)
    return -1;
  return SparseVsDense(S, D);
}

/* Check("...", err, 0) of a SparseJacobianError maximum, failing on -1. */
static void CheckExact(const char *what, double err, int bad)
{
  if (bad) printf("%s: wrong number of entries or call failed\n", what);
  Check(what, bad ? HUGE_VAL : err, 0.0);
}

/* Attachment points and axes of the test mechanisms. */
static const double pa[3] = {0.1, -0.2, 0.5}, pb[3] = {-0.3, 0.2, -0.4};
static const double ax[3] = {0, 0, 1}, ay[3] = {0, 1, 0}, axy[3] = {1, 1, 0.5};

/* The mechanism of the main checks on four bodies: S, R, U, R, S joints
 * (20 constraints). */
static void AddTestJoints(LGNJoints J)
{
  LGNJoints_AddSpherical(J, LGN_GROUND, pa, 0, pb);
  LGNJoints_AddRevolute(J, 0, pa, axy, 1, pb, ax);
  LGNJoints_AddUniversal(J, 1, pb, ay, 2, pa, axy);
  LGNJoints_AddRevolute(J, 3, pa, ax, LGN_GROUND, pb, ay);
  LGNJoints_AddSpherical(J, 2, pb, 3, pa);
}

int main(void)
{
  SUNContext ctx;
  LGNGroup body[2], G;
  LGNGroup factors[4];
  LGNJoints J;
  N_Vector q, qp, qm, v, phi_p, phi_m, z, lam;
  SUNMatrix B, Bp, Bm, K, S;
  sunindextype nq, nv, m, i, k;
  const double eps = 1e-5;
  double w[24], Bw[32], fd[32], errB = 0, errZ = 0, errK = 0, scale;
  int trial, type;

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body[0] = LGNGroup_R3xSO3();
  body[1] = LGNGroup_SE3();
  for (k = 0; k < 4; k++) factors[k] = body[k % 2];
  G  = LGNGroup_Product(4, factors);
  nq = G->nq;
  nv = G->nv;

  J = LGNJoints_Create(G);
  if (J == NULL || LGNJoints_NumBodies(J) != 4) return 1;
  /* the bad input below is refused on purpose: keep stderr quiet (the
   * messages are checked in test_joints_errors.c) */
  LGNJoints_SetErrFile(J, NULL);
  AddTestJoints(J);
  m = LGNJoints_NumConstraints(J);
  if (m != 3 + 5 + 4 + 5 + 3) {
    printf("m = %lld, expected 20\n", (long long)m);
    return 1;
  }
  /* bad input is refused */
  if (LGNJoints_AddSpherical(J, 0, pa, 0, pb) != LGN_ILL_INPUT ||
      LGNJoints_AddSpherical(J, 7, pa, 0, pb) != LGN_ILL_INPUT ||
      LGNJoints_AddRevolute(J, 0, pa, (const double[3]){0, 0, 0}, 1, pb, ax) != LGN_ILL_INPUT) {
    printf("bad joint input accepted\n");
    failures++;
  }

  q = N_VNew_Serial(nq, ctx);   qp = N_VClone(q);  qm = N_VClone(q);
  v = N_VNew_Serial(nv, ctx);   lam = N_VNew_Serial(m, ctx);
  phi_p = N_VClone(lam);        phi_m = N_VClone(lam);  z = N_VClone(lam);
  B  = SUNDenseMatrix(m, nv, ctx);
  Bp = SUNDenseMatrix(m, nv, ctx);
  Bm = SUNDenseMatrix(m, nv, ctx);
  K  = SUNDenseMatrix(nv, nv, ctx);

  srand(12345);
  for (trial = 0; trial < 5; trial++) {
    double *qd = N_VGetArrayPointer(q);
    RandomConfiguration(4, qd);
    for (i = 0; i < nv; i++) { N_VGetArrayPointer(v)[i] = 3 * Rand(); w[i] = Rand(); }
    for (i = 0; i < m; i++) N_VGetArrayPointer(lam)[i] = 10 * Rand();

    SUNMatZero(B);
    LGNJoints_Jacobian(J, 0.0, q, B);
    /* B w vs Phi */
    for (i = 0; i < nv; i++) fd[i] = eps * w[i];
    G->ops.compose_exp(G, qd, fd, N_VGetArrayPointer(qp));
    for (i = 0; i < nv; i++) fd[i] = -eps * w[i];
    G->ops.compose_exp(G, qd, fd, N_VGetArrayPointer(qm));
    LGNJoints_Residual(J, 0.0, qp, phi_p);
    LGNJoints_Residual(J, 0.0, qm, phi_m);
    DenseApply(B, w, Bw, 0);
    for (i = 0; i < m; i++)
      errB = fmax(errB, fabs(Bw[i] - (N_VGetArrayPointer(phi_p)[i] - N_VGetArrayPointer(phi_m)[i]) / (2 * eps)));
    /* K w vs B^T lambda */
    SUNMatZero(Bp); SUNMatZero(Bm); SUNMatZero(K);
    LGNJoints_Jacobian(J, 0.0, qp, Bp);
    LGNJoints_Jacobian(J, 0.0, qm, Bm);
    LGNJoints_Stiffness(J, 0.0, q, lam, K);
    DenseApply(K, w, Bw, 0);
    {
      double rp[24], rm[24];
      DenseApply(Bp, N_VGetArrayPointer(lam), rp, 1);
      DenseApply(Bm, N_VGetArrayPointer(lam), rm, 1);
      scale = 0;
      for (i = 0; i < nv; i++) scale = fmax(scale, fabs(rp[i]));
      for (i = 0; i < nv; i++) errK = fmax(errK, fabs(Bw[i] - (rp[i] - rm[i]) / (2 * eps)) / scale);
    }
    /* Z(v, v) vs B v along v */
    for (i = 0; i < nv; i++) fd[i] = eps * N_VGetArrayPointer(v)[i];
    G->ops.compose_exp(G, qd, fd, N_VGetArrayPointer(qp));
    for (i = 0; i < nv; i++) fd[i] = -eps * N_VGetArrayPointer(v)[i];
    G->ops.compose_exp(G, qd, fd, N_VGetArrayPointer(qm));
    SUNMatZero(Bp); SUNMatZero(Bm);
    LGNJoints_Jacobian(J, 0.0, qp, Bp);
    LGNJoints_Jacobian(J, 0.0, qm, Bm);
    LGNJoints_Curvature(J, 0.0, q, v, z);
    {
      double zp[32], zm[32];
      DenseApply(Bp, N_VGetArrayPointer(v), zp, 0);
      DenseApply(Bm, N_VGetArrayPointer(v), zm, 0);
      for (i = 0; i < m; i++)
        errZ = fmax(errZ, fabs(N_VGetArrayPointer(z)[i] - (zp[i] - zm[i]) / (2 * eps)) / 10);
    }
  }
  Check("B w = d/de Phi(q o exp(e w))", errB, 1e-8);
  Check("K w = d/de B(q o exp(e w))^T lambda (rel.)", errK, 1e-8);
  Check("Z(v,v) = d/de B(q o exp(e v)) v (/|v|^2)", errZ, 1e-8);

  for (type = 0; type < 2; type++) {
    const int st = type == 0 ? CSC_MAT : CSR_MAT;
    S = SUNSparseMatrix(m, nv, 4, st, ctx); /* too small: must grow */
    LGNJoints_Jacobian(J, 0.0, q, S);
    Check(type == 0 ? "sparse CSC B = dense B" : "sparse CSR B = dense B",
          SparseVsDense(S, B), 0.0);
    if (SUNSparseMatrix_IndexPointers(S)[type == 0 ? nv : m] != LGNJoints_JacobianNnz(J)) {
      printf("B nnz mismatch\n");
      failures++;
    }
    SUNMatDestroy(S);
    S = SUNSparseMatrix(nv, nv, 4, st, ctx);
    LGNJoints_Stiffness(J, 0.0, q, lam, S);
    Check(type == 0 ? "sparse CSC K = dense K" : "sparse CSR K = dense K",
          SparseVsDense(S, K), 0.0);
    SUNMatDestroy(S);
  }

  /* The kept pattern: CSC and CSR in turn with the same joints, at new
   * configurations, each call on a garbled matrix (the first ones with
   * room for one entry). */
  {
    SUNMatrix Sc = SUNSparseMatrix(m, nv, 1, CSC_MAT, ctx);
    SUNMatrix Sr = SUNSparseMatrix(m, nv, 1, CSR_MAT, ctx);
    double errc = 0, errr = 0, e;
    int bad = 0;
    for (trial = 0; trial < 4; trial++) {
      RandomConfiguration(4, N_VGetArrayPointer(q));
      e = SparseJacobianError(J, q, Sc, B);
      bad += e < 0;
      errc = fmax(errc, e);
      e = SparseJacobianError(J, q, Sr, B);
      bad += e < 0;
      errr = fmax(errr, e);
    }
    CheckExact("kept CSC B = dense B (4 q, garbled)", errc, bad);
    CheckExact("kept CSR B = dense B (4 q, garbled)", errr, bad);
    SUNMatDestroy(Sc);
    SUNMatDestroy(Sr);
  }

  /* Joints added after a sparse B: the next B has the new pattern, in a
   * matrix with room for the old one only. */
  for (type = 0; type < 2; type++) {
    const int st = type == 0 ? CSC_MAT : CSR_MAT;
    LGNJoints J2 = LGNJoints_Create(G);
    SUNMatrix S2, D2;
    sunindextype m2, nnz2;
    double err, e;
    int bad = 0;
    LGNJoints_AddRevolute(J2, 0, pa, axy, 1, pb, ax);
    LGNJoints_AddSpherical(J2, 2, pb, 3, pa);
    m2   = LGNJoints_NumConstraints(J2);
    nnz2 = LGNJoints_JacobianNnz(J2);
    S2 = SUNSparseMatrix(m2, nv, nnz2, st, ctx);
    D2 = SUNDenseMatrix(m2, nv, ctx);
    err = SparseJacobianError(J2, q, S2, D2);
    bad += err < 0;
    SUNMatDestroy(S2);
    SUNMatDestroy(D2);
    /* new rows, and columns of body 2 between those of 1 and 3 */
    LGNJoints_AddUniversal(J2, 3, pa, ax, 1, pb, ay);
    LGNJoints_AddSpherical(J2, LGN_GROUND, pb, 2, pa);
    m2 = LGNJoints_NumConstraints(J2);
    S2 = SUNSparseMatrix(m2, nv, nnz2, st, ctx);
    D2 = SUNDenseMatrix(m2, nv, ctx);
    RandomConfiguration(4, N_VGetArrayPointer(q));
    e = SparseJacobianError(J2, q, S2, D2);
    /* universal between SE(3) bodies: 2 x 18 point and 2 x 3 perpendicular
     * entries; spherical to R^3 x SO(3) body 2: 12 point entries */
    bad += e < 0 || LGNJoints_JacobianNnz(J2) != nnz2 + (36 + 6) + 12;
    err = fmax(err, e);
    CheckExact(type == 0 ? "CSC B after adding joints = dense B"
                         : "CSR B after adding joints = dense B", err, bad);
    SUNMatDestroy(S2);
    SUNMatDestroy(D2);
    LGNJoints_Destroy(&J2);
  }

  /* f = B^T lambda without forming B, against the dense B times lambda,
   * relative to max |B^T lambda|: J at new configurations and multipliers;
   * J3 with bodies 0 and 2 in no joint, whose entries must become 0; J4
   * without joints (m = 0), where f = 0. f is NaN before each call. */
  {
    LGNJoints J3 = LGNJoints_Create(G), J4 = LGNJoints_Create(G);
    N_Vector f = N_VNew_Serial(nv, ctx), lam3, lam0 = N_VNew_Serial(0, ctx);
    SUNMatrix B3;
    double btl[24], errF = 0, errF3 = 0, free0 = 0, e;
    int bad = 0;
    for (trial = 0; trial < 20; trial++) {
      RandomConfiguration(4, N_VGetArrayPointer(q));
      for (i = 0; i < m; i++) N_VGetArrayPointer(lam)[i] = 10 * Rand();
      SUNMatZero(B);
      bad += LGNJoints_Jacobian(J, 0.0, q, B) != LGN_SUCCESS;
      DenseApply(B, N_VGetArrayPointer(lam), btl, 1);
      N_VConst(NAN, f);
      bad += LGNJoints_ConstraintForce(J, 0.0, q, lam, f) != LGN_SUCCESS;
      scale = 0;
      for (i = 0; i < nv; i++) scale = fmax(scale, fabs(btl[i]));
      for (i = 0; i < nv; i++) {
        e    = fabs(N_VGetArrayPointer(f)[i] - btl[i]) / scale;
        errF = fmax(errF, isnan(e) ? HUGE_VAL : e);
      }
    }
    Check("f = B^T lambda, no B (rel., 20 q, garbled)", bad ? HUGE_VAL : errF, 1e-14);

    LGNJoints_AddRevolute(J3, 1, pa, ax, LGN_GROUND, pb, ay);
    LGNJoints_AddSpherical(J3, 1, pb, 3, pa);
    lam3 = N_VNew_Serial(LGNJoints_NumConstraints(J3), ctx);
    B3   = SUNDenseMatrix(LGNJoints_NumConstraints(J3), nv, ctx);
    for (i = 0; i < LGNJoints_NumConstraints(J3); i++) N_VGetArrayPointer(lam3)[i] = 10 * Rand();
    SUNMatZero(B3);
    LGNJoints_Jacobian(J3, 0.0, q, B3);
    DenseApply(B3, N_VGetArrayPointer(lam3), btl, 1);
    N_VConst(NAN, f);
    bad = LGNJoints_ConstraintForce(J3, 0.0, q, lam3, f) != LGN_SUCCESS;
    scale = 0;
    for (i = 0; i < nv; i++) scale = fmax(scale, fabs(btl[i]));
    for (i = 0; i < nv; i++) {
      const sunindextype bk = i / 6; /* every body has 6 velocity entries */
      e = fabs(N_VGetArrayPointer(f)[i] - (bk == 0 || bk == 2 ? 0.0 : btl[i]));
      if (isnan(e)) e = HUGE_VAL;
      if (bk == 0 || bk == 2) free0 = fmax(free0, e);
      else errF3 = fmax(errF3, e / scale);
    }
    Check("f = B^T lambda, bodies 1, 3 only (rel.)", bad ? HUGE_VAL : errF3, 1e-14);
    Check("f = 0 at bodies 0, 2 (in no joint)", bad ? HUGE_VAL : free0, 0.0);
    N_VConst(NAN, f);
    bad = LGNJoints_ConstraintForce(J4, 0.0, q, lam0, f) != LGN_SUCCESS;
    e   = 0;
    for (i = 0; i < nv; i++) e = fmax(e, isnan(N_VGetArrayPointer(f)[i]) ? HUGE_VAL : fabs(N_VGetArrayPointer(f)[i]));
    Check("f = 0 without joints (m = 0)", bad ? HUGE_VAL : e, 0.0);

    /* bad input: no joint set, q, lambda or f of the wrong length or NULL */
    if (LGNJoints_ConstraintForce(NULL, 0.0, q, lam, f) != LGN_ILL_INPUT ||
        LGNJoints_ConstraintForce(J, 0.0, lam, lam, f) != LGN_ILL_INPUT ||
        LGNJoints_ConstraintForce(J, 0.0, q, v, f) != LGN_ILL_INPUT ||
        LGNJoints_ConstraintForce(J, 0.0, q, lam3, f) != LGN_ILL_INPUT ||
        LGNJoints_ConstraintForce(J, 0.0, q, lam, lam) != LGN_ILL_INPUT ||
        LGNJoints_ConstraintForce(J, 0.0, q, NULL, f) != LGN_ILL_INPUT ||
        LGNJoints_ConstraintForce(J, 0.0, q, lam, NULL) != LGN_ILL_INPUT ||
        LGNJoints_ConstraintForce(J, 0.0, NULL, lam, f) != LGN_ILL_INPUT) {
      printf("bad ConstraintForce input accepted\n");
      failures++;
    }
    N_VDestroy(f);
    N_VDestroy(lam3);
    N_VDestroy(lam0);
    SUNMatDestroy(B3);
    LGNJoints_Destroy(&J3);
    LGNJoints_Destroy(&J4);
  }

  /* the rotations kept between calls: change one quaternion component at
   * a time in place (the others bit for bit the same) and compare Phi with
   * a fresh helper, which has nothing kept */
  {
    LGNJoints Jf;
    double *qd = N_VGetArrayPointer(q), err = 0;
    int c;
    RandomConfiguration(4, qd);
    LGNJoints_Residual(J, 0.0, q, phi_p);
    for (k = 0; k < 4; k++)
      for (c = 0; c < 4; c++) {
        double *p = qd + 7 * k + 3; /* both body types: (x, p), nq = 7 */
        p[c] = -p[c];
        Jf = LGNJoints_Create(G);
        AddTestJoints(Jf);
        LGNJoints_Residual(J, 0.0, q, phi_p);
        LGNJoints_Residual(Jf, 0.0, q, phi_m);
        for (i = 0; i < m; i++)
          err = fmax(err, fabs(N_VGetArrayPointer(phi_p)[i] - N_VGetArrayPointer(phi_m)[i]));
        LGNJoints_Destroy(&Jf);
      }
    Check("Phi after one quaternion component changed in place = fresh helper's", err, 0);
  }

  LGNJoints_Destroy(&J);
  if (J != NULL) failures++;
  N_VDestroy(q); N_VDestroy(qp); N_VDestroy(qm); N_VDestroy(v); N_VDestroy(lam);
  N_VDestroy(phi_p); N_VDestroy(phi_m); N_VDestroy(z);
  SUNMatDestroy(B); SUNMatDestroy(Bp); SUNMatDestroy(Bm); SUNMatDestroy(K);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body[0]);
  LGNGroup_Destroy(body[1]);
  SUNContext_Free(&ctx);
  printf("%s\n", failures == 0 ? "PASSED" : "FAILED");
  return failures == 0 ? 0 : 1;
}
