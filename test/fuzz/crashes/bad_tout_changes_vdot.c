/* -----------------------------------------------------------------------------
 * Found by test/fuzz (lgn_fuzz), minimised by hand. Not part of the suite.
 *
 * A failed LGNSolve changes what LGNGetAcceleration (and
 * LGNGetAuxAcceleration) report: before the first LGNSolve after LGNInit
 * they return LGN_SUCCESS with vdot = 0 (nothing computed yet); an LGNSolve
 * that then fails with LGN_BAD_TOUT (tout behind t0) has computed and kept
 * the consistent initial values (CheckReadyToSolve in src/core/lgn.c runs
 * lgnInitialConditions before tout is checked), so afterwards the same
 * getter returns vdot_0 = -M^{-1} g. Time, q and v are unchanged; only the
 * reported acceleration differs, so "a failed call leaves the state as it
 * was, bit for bit" does not hold for LGNGetAcceleration at the start.
 * Either the getters should refuse (or compute) vdot before the initial
 * values exist, or LGN_BAD_TOUT should be checked before them.
 *
 *   cc bad_tout_changes_vdot.c -I<lignum>/include -I<build>/include \
 *      -L<build>/src -llignum -lsundials_nvecserial -lsundials_sunmatrixdense \
 *      -lsundials_sunlinsoldense -lm && ./a.out
 * exits 1 (and prints both values) while the behaviour is as described.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/
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
  NV_Ith_S(g, 0) = 4.0 * NV_Ith_S(q, 0); /* M vdot + g = 0: vdot_0 = -4 */
  return 0;
}

int main(void)
{
  SUNContext ctx;
  LGNGroup G;
  N_Vector q, v, a, tmp;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  double t, before, after;
  int flag;
  SUNContext_Create(NULL, &ctx);
  G   = LGNGroup_Rn(1);
  q   = N_VNew_Serial(1, ctx);
  v   = N_VNew_Serial(1, ctx);
  a   = N_VNew_Serial(1, ctx);
  tmp = N_VNew_Serial(1, ctx);
  A   = SUNDenseMatrix(1, 1, ctx);
  LS  = SUNLinSol_Dense(tmp, A, ctx);
  NV_Ith_S(q, 0) = 1.0;
  NV_Ith_S(v, 0) = 0.0;
  mem = LGNCreate(ctx);
  LGNSetErrFile(mem, NULL);
  LGNSetGroup(mem, G);
  LGNSetMassFn(mem, Mass);
  LGNSetForceFn(mem, Force);
  LGNInit(mem, 0.0, q, v);
  LGNSetLinearSolver(mem, LS, A);
  LGNSetStepSize(mem, 1e-3);

  NV_Ith_S(a, 0) = 99.0;
  flag   = LGNGetAcceleration(mem, a);
  before = NV_Ith_S(a, 0);
  printf("before: LGNGetAcceleration -> %s, vdot = %g\n", LGNGetReturnFlagName(flag), before);
  flag = LGNSolve(mem, -1.0, &t, q, v, LGN_NORMAL);
  printf("LGNSolve(tout = -1) -> %s\n", LGNGetReturnFlagName(flag));
  flag  = LGNGetAcceleration(mem, a);
  after = NV_Ith_S(a, 0);
  printf("after:  LGNGetAcceleration -> %s, vdot = %g\n", LGNGetReturnFlagName(flag), after);

  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q); N_VDestroy(v); N_VDestroy(a); N_VDestroy(tmp);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return before != after;
}
