/* -----------------------------------------------------------------------------
 * Found by test/fuzz (lgn_fuzz, AddressSanitizer), minimised by hand. Not
 * part of the suite. Needs KLU.
 *
 * With Lignum's own KLU solves on (LGNSetOwnKLUSolves(mem, SUNTRUE)), a KLU
 * CSC solver and stiffness and damping callbacks (K_t, C_t with a diagonal
 * pattern): one step, then LGNInit again, then the stiffness and damping
 * callbacks removed (LGNSetStiffnessFn / LGNSetDampingFn(mem, NULL): the
 * iteration matrix gets another pattern), then LGNSolve. The consistent
 * initial values' SUNLinSolSetup_KLU frees KLU's Numeric object and hands
 * klu_l_free a pointer malloc never returned, inside a block freed by
 * lgnKluCopyFree at the LGNInit:
 *   ERROR: AddressSanitizer: attempting free on address which was not
 *   malloc()-ed ... klu_l_free_numeric <- SUNLinSolSetup_KLU
 *   <- lgnLsSetup src/linsys/lgn_ls.c:381 <- SaddlePointSolve src/core/lgn_consistent_ic.c:76
 *   <- lgnComputeIC <- lgnInitialConditions <- LGNSolve src/core/lgn.c:348
 *   the block: freed by lgnKluCopyFree src/linsol/klu_copy/lgn_klu_solve.c:69
 *   <- lgnFreeMatrices src/core/lgn_mem.c:357 (at the LGNInit)
 * So KLU's Numeric object of the solver is left pointing into (or was
 * replaced by) memory of Lignum's freed copy of the factors. Leaving out
 * the second LGNInit, or the removal of the callbacks, makes it go away;
 * fixed or adaptive steps, full or modified Newton, CSC or a switch to a
 * CSR solver do not matter. Without ASan: heap corruption (a crash in
 * free or silently wrong factors).
 *
 *   clang -g -fsanitize=address -I/usr/include/suitesparse \
 *     -I<lignum>/include -I<build>/include klu_own_solves_reinit.c \
 *     -L<build>/src -llignum -lsundials_nvecserial -lsundials_sunmatrixsparse \
 *     -lsundials_sunlinsolklu -lklu -lm && ./a.out
 * (with a library built with ASan, e.g. build-clang-asan/ or the static
 * lignum_internal of build-fuzz/) stops with the report above.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/
#include <stdio.h>

#include <lignum/lignum.h>
#include <lignum/lignum_group.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

static const double JB[3] = {0.3, 0.5, 0.7};

/* diagonal mass matrix of a body of mass 2 (sparse, CSC or CSR alike) */
static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  sunindextype i, *ptr = SUNSparseMatrix_IndexPointers(M), *ind = SUNSparseMatrix_IndexValues(M);
  double *val = SUNSparseMatrix_Data(M);
  (void)t; (void)q; (void)ud;
  for (i = 0; i < 6; i++) {
    ptr[i] = i;
    ind[i] = i;
    val[i] = i < 3 ? 2.0 : JB[i - 3];
  }
  ptr[6] = 6;
  return 0;
}

/* gravity and the gyroscopic moment */
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const double *W = N_VGetArrayPointer(v) + 3;
  double *f       = N_VGetArrayPointer(g);
  (void)t; (void)q; (void)ud;
  f[0] = f[1] = 0.0;
  f[2] = 2.0 * 9.81;
  f[3] = W[1] * JB[2] * W[2] - W[2] * JB[1] * W[1];
  f[4] = W[2] * JB[0] * W[0] - W[0] * JB[2] * W[2];
  f[5] = W[0] * JB[1] * W[1] - W[1] * JB[0] * W[0];
  return 0;
}

/* K_t = 0 and C_t = 0 with a diagonal pattern */
static int Zero(SUNMatrix K)
{
  sunindextype i, *ptr = SUNSparseMatrix_IndexPointers(K), *ind = SUNSparseMatrix_IndexValues(K);
  double *val = SUNSparseMatrix_Data(K);
  for (i = 0; i < 6; i++) {
    ptr[i] = i;
    ind[i] = i;
    val[i] = 0.0;
  }
  ptr[6] = 6;
  return 0;
}

static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  (void)t; (void)q; (void)v; (void)vdot; (void)lambda; (void)ud;
  return Zero(K);
}

static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  return Zero(C);
}

static void Start(N_Vector q, N_Vector v)
{
  const double psi0[3] = {0.3, -0.2, 0.5};
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  LGNQuaternionFromRotationVector(psi0, N_VGetArrayPointer(q) + 3);
  NV_Ith_S(v, 3) = 1.0;
  NV_Ith_S(v, 4) = -2.0;
  NV_Ith_S(v, 5) = 8.0;
}

int main(void)
{
  SUNContext ctx;
  LGNGroup G;
  N_Vector q, v, tmp;
  SUNMatrix A1;
  SUNLinearSolver LS1;
  void *mem;
  double t;
  int flag;
  SUNContext_Create(NULL, &ctx);
  G   = LGNGroup_R3xSO3();
  q   = N_VNew_Serial(7, ctx);
  v   = N_VNew_Serial(6, ctx);
  tmp = N_VNew_Serial(6, ctx);
  A1  = SUNSparseMatrix(6, 6, 36, CSC_MAT, ctx);
  LS1 = SUNLinSol_KLU(tmp, A1, ctx);
  Start(q, v);

  mem = LGNCreate(ctx);
  LGNSetGroup(mem, G);
  LGNSetMassFn(mem, Mass);
  LGNSetForceFn(mem, Force);
  LGNSetStiffnessFn(mem, Stiffness);
  LGNSetDampingFn(mem, Damping);
  LGNInit(mem, 0.0, q, v);
  LGNSetLinearSolver(mem, LS1, A1);
  LGNSetGenAlpha(mem, 0.8);
  LGNSetStepSize(mem, 1e-3);
  flag = LGNSetOwnKLUSolves(mem, SUNTRUE);
  printf("LGNSetOwnKLUSolves -> %s\n", LGNGetReturnFlagName(flag));
  flag = LGNSolve(mem, 1.0, &t, q, v, LGN_ONE_STEP);
  printf("step with KLU CSC -> %s\n", LGNGetReturnFlagName(flag));

  Start(q, v);
  flag = LGNInit(mem, 0.0, q, v); /* LGNInit again */
  LGNSetStiffnessFn(mem, NULL); /* another pattern of the iteration matrix */
  LGNSetDampingFn(mem, NULL);
  printf("LGNInit -> %s\n", LGNGetReturnFlagName(flag));
  fflush(stdout);
  flag = LGNSolve(mem, 1.0, &t, q, v, LGN_ONE_STEP); /* ASan stops here */
  printf("step after LGNInit -> %s\n", LGNGetReturnFlagName(flag));

  LGNFree(&mem);
  SUNLinSolFree(LS1);
  SUNMatDestroy(A1);
  N_VDestroy(q); N_VDestroy(v); N_VDestroy(tmp);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return 0;
}
