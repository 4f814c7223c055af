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
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

static int failures = 0;

static void Check(const char *what, double err, double tol)
{
  printf("%-44s max error %.3e (tol %.1e) %s\n", what, err, tol,
         err <= tol ? "ok" : "FAIL");
  if (!(err <= tol)) failures++;
}

static double Rand(void) { return 2.0 * rand() / (double)RAND_MAX - 1.0; }

/* y = A x for dense A, or A^T x. */
static void DenseApply(SUNMatrix A, const double *x, double *y, int transpose)
{
  sunindextype i, j, M = SM_ROWS_D(A), N = SM_COLUMNS_D(A);
  for (i = 0; i < (transpose ? N : M); i++) y[i] = 0;
  for (j = 0; j < N; j++)
    for (i = 0; i < M; i++) {
      if (transpose) y[j] += SM_ELEMENT_D(A, i, j) * x[i];
      else y[i] += SM_ELEMENT_D(A, i, j) * x[j];
    }
}

/* max |S - D| over all entries, S sparse. */
static double SparseVsDense(SUNMatrix S, SUNMatrix D)
{
  sunindextype k, p, n;
  const int csc = SUNSparseMatrix_SparseType(S) == CSC_MAT;
  double err = 0;
  SUNMatrix T = SUNDenseMatrix(SM_ROWS_D(D), SM_COLUMNS_D(D), S->sunctx);
  SUNMatZero(T);
  n = csc ? SUNSparseMatrix_Columns(S) : SUNSparseMatrix_Rows(S);
  for (k = 0; k < n; k++)
    for (p = SUNSparseMatrix_IndexPointers(S)[k]; p < SUNSparseMatrix_IndexPointers(S)[k + 1]; p++) {
      sunindextype o = SUNSparseMatrix_IndexValues(S)[p];
      SM_ELEMENT_D(T, csc ? o : k, csc ? k : o) += SUNSparseMatrix_Data(S)[p];
    }
  for (k = 0; k < SM_ROWS_D(D) * SM_COLUMNS_D(D); k++)
    err = fmax(err, fabs(SM_DATA_D(T)[k] - SM_DATA_D(D)[k]));
  SUNMatDestroy(T);
  return err;
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
  const double pa[3] = {0.1, -0.2, 0.5}, pb[3] = {-0.3, 0.2, -0.4};
  const double ax[3] = {0, 0, 1}, ay[3] = {0, 1, 0}, axy[3] = {1, 1, 0.5};

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body[0] = LGNGroup_R3xSO3();
  body[1] = LGNGroup_SE3();
  for (k = 0; k < 4; k++) factors[k] = body[k % 2];
  G  = LGNGroup_Product(4, factors);
  nq = G->nq;
  nv = G->nv;

  J = LGNJoints_Create(NULL, G);
  if (J == NULL || LGNJoints_NumBodies(J) != 4) return 1;
  LGNJoints_AddSpherical(J, LGN_GROUND, pa, 0, pb);
  LGNJoints_AddRevolute(J, 0, pa, axy, 1, pb, ax);
  LGNJoints_AddUniversal(J, 1, pb, ay, 2, pa, axy);
  LGNJoints_AddRevolute(J, 3, pa, ax, LGN_GROUND, pb, ay);
  LGNJoints_AddSpherical(J, 2, pb, 3, pa);
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
    for (k = 0; k < 4; k++) {
      double p[4], n = 0;
      for (i = 0; i < 3; i++) qd[7 * k + i] = Rand();
      for (i = 0; i < 4; i++) { p[i] = Rand(); n += p[i] * p[i]; }
      for (i = 0; i < 4; i++) qd[7 * k + 3 + i] = p[i] / sqrt(n);
    }
    for (i = 0; i < nv; i++) { N_VGetArrayPointer(v)[i] = 3 * Rand(); w[i] = Rand(); }
    for (i = 0; i < m; i++) N_VGetArrayPointer(lam)[i] = 10 * Rand();

    SUNMatZero(B);
    LGNJoints_Jacobian(J, q, B);
    /* B w vs Phi */
    for (i = 0; i < nv; i++) fd[i] = eps * w[i];
    G->ops.compose_exp(G, qd, fd, N_VGetArrayPointer(qp));
    for (i = 0; i < nv; i++) fd[i] = -eps * w[i];
    G->ops.compose_exp(G, qd, fd, N_VGetArrayPointer(qm));
    LGNJoints_Residual(J, qp, phi_p);
    LGNJoints_Residual(J, qm, phi_m);
    DenseApply(B, w, Bw, 0);
    for (i = 0; i < m; i++)
      errB = fmax(errB, fabs(Bw[i] - (N_VGetArrayPointer(phi_p)[i] - N_VGetArrayPointer(phi_m)[i]) / (2 * eps)));
    /* K w vs B^T lambda */
    SUNMatZero(Bp); SUNMatZero(Bm); SUNMatZero(K);
    LGNJoints_Jacobian(J, qp, Bp);
    LGNJoints_Jacobian(J, qm, Bm);
    LGNJoints_Stiffness(J, q, lam, K);
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
    LGNJoints_Jacobian(J, qp, Bp);
    LGNJoints_Jacobian(J, qm, Bm);
    LGNJoints_Curvature(J, q, v, z);
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
    LGNJoints_Jacobian(J, q, S);
    Check(type == 0 ? "sparse CSC B = dense B" : "sparse CSR B = dense B",
          SparseVsDense(S, B), 0.0);
    if (SUNSparseMatrix_IndexPointers(S)[type == 0 ? nv : m] != LGNJoints_JacobianNnz(J)) {
      printf("B nnz mismatch\n");
      failures++;
    }
    SUNMatDestroy(S);
    S = SUNSparseMatrix(nv, nv, 4, st, ctx);
    LGNJoints_Stiffness(J, q, lam, S);
    Check(type == 0 ? "sparse CSC K = dense K" : "sparse CSR K = dense K",
          SparseVsDense(S, K), 0.0);
    SUNMatDestroy(S);
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
