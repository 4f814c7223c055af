/* -----------------------------------------------------------------------------
 * Found by test/fuzz (lgn_fuzz: "LGNSolve returned LGN_SUCCESS with a
 * non-finite tret, q or v"), minimised by hand. Not part of the suite.
 *
 * LGNInit (and LGNReInit) accept a q0 or v0 with NaN or Inf entries and
 * return LGN_SUCCESS; LGNSolve then integrates them and returns LGN_SUCCESS
 * with a non-finite q (here q = -Inf on R^1; in the fuzzer x = -Inf of a
 * free body on R^3 x SO(3)) whenever no callback output turns non-finite
 * (the LGN_NONFINITE checks look at the callbacks' outputs only: here the
 * force does not read q). Expected: LGNInit / LGNReInit refuse a
 * non-finite q0 or v0 with LGN_ILL_INPUT (as LGNSVtolerances refuses a
 * non-finite atol), or LGNSolve reports LGN_NONFINITE.
 *
 *   cc init_nonfinite_q0.c -I<lignum>/include -I<build>/include \
 *      -L<build>/src -llignum -lsundials_nvecserial -lsundials_sunmatrixdense \
 *      -lsundials_sunlinsoldense -lm && ./a.out
 * prints "LGNInit(q0 = -Inf) -> LGN_SUCCESS" and "LGNSolve -> LGN_SUCCESS,
 * t = 0.01, q = -inf, v = -0.01" and exits 1 while the behaviour is as
 * described.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/
#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>
#include <lignum/lignum_group.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = 1.0;
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)v; (void)ud;
  NV_Ith_S(g, 0) = 1.0; /* does not read q */
  return 0;
}

int main(void)
{
  SUNContext ctx;
  LGNGroup G;
  N_Vector q, v, tmp;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  double t = 0.0;
  int flag, bad;
  SUNContext_Create(NULL, &ctx);
  G   = LGNGroup_Rn(1);
  q   = N_VNew_Serial(1, ctx);
  v   = N_VNew_Serial(1, ctx);
  tmp = N_VNew_Serial(1, ctx);
  A   = SUNDenseMatrix(1, 1, ctx);
  LS  = SUNLinSol_Dense(tmp, A, ctx);
  NV_Ith_S(q, 0) = -INFINITY;
  NV_Ith_S(v, 0) = 0.0;
  mem = LGNCreate(ctx);
  LGNSetErrFile(mem, NULL);
  LGNSetGroup(mem, G);
  LGNSetMassFn(mem, Mass);
  LGNSetForceFn(mem, Force);
  flag = LGNInit(mem, 0.0, q, v);
  printf("LGNInit(q0 = -Inf) -> %s\n", LGNGetReturnFlagName(flag));
  LGNSetLinearSolver(mem, LS, A);
  LGNSetStepSize(mem, 1e-3);
  flag = LGNSolve(mem, 1e-2, &t, q, v, LGN_NORMAL);
  bad  = flag == LGN_SUCCESS && !isfinite(NV_Ith_S(q, 0));
  printf("LGNSolve -> %s, t = %g, q = %g, v = %g\n", LGNGetReturnFlagName(flag), t,
         NV_Ith_S(q, 0), NV_Ith_S(v, 0));
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q); N_VDestroy(v); N_VDestroy(tmp);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return bad;
}
