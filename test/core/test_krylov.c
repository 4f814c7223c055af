/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Matrix-free Krylov solvers (lgn_krylov.c) and the block preconditioner
 * (lgn_blockprec.c) on the spherical-pendulum chain:
 *
 *  1. SPGMR + the block preconditioner with 1, 2 and 4 blocks against KLU,
 *     N = 20 and 200, 50 steps of generalized-alpha (h = 1e-3, Newton's
 *     default tolerances 1e-8). Asserted: the final q agrees with KLU's
 *     to 1e-7 and v to 1e-6 (absolute; |q| up to N m, |v| ~ 1 m/s). The
 *     bound on v is looser because v1 = v_n + gamma' sigma-ish: Newton's
 *     own tolerance on sigma (atol h + rtol |sigma| ~ 2e-11 here) is
 *     gamma' = gamma/(beta h) = 2000 times larger in v (4e-8 per step),
 *     which is the uncertainty either solver leaves (measured: 2e-9 in q,
 *     2e-7 to 5e-7 in v with 2 and 4 blocks; 1e-13 and 4e-10 with one
 *     block, whose GMRES solves are exact to roundoff); no linear solve missed its
 *     tolerance; the Krylov iterations per Newton iteration are <= 2 with
 *     one block (the preconditioner is A) and <= 30 with 2 and 4. Why the
 *     trajectories differ at all: each Newton correction is solved to a
 *     weighted residual of 0.05 of Newton's tolerance instead of to
 *     roundoff, so each step's end point moves by about that much (~1e-12
 *     in sigma) and the differences add up over the steps. It could fail:
 *     when a Newton iteration stops one iteration earlier with one solver
 *     than with the other (the difference is then Newton's own tolerance,
 *     still far below 1e-7), when the chain's motion amplifies the
 *     differences strongly (not over 50 steps), or when GMRES stops short
 *     of its tolerance (counted, and asserted to be zero).
 *  2. Matrix-free without a preconditioner: the 3-body chain (27 unknowns)
 *     with SPGMR (Krylov dimension 40) converges and agrees with KLU.
 *  3. A user preconditioner (the identity, PREC_LEFT): its callbacks are
 *     called, with the scalings of the matrix ((1, 0, 0) for the initial
 *     values, beta h^2 beta', beta h^2 gamma', beta h^2 in the steps).
 *  4. Bad input: clear errors for NULL callbacks, a direct solver without
 *     its matrix, a Krylov solver with one, PCG, a preconditioner with a
 *     PREC_NONE solver, illegal partitions, NULL outputs.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_config.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "models/chain.h"
#include "test_util.h"

#if defined(LGN_HAVE_KLU) /* the comparisons with KLU */
static double MaxDiff(const double *a, const double *b, long int n)
{
  double d = 0.0;
  long int i;
  for (i = 0; i < n; i++) d = fmax(d, fabs(a[i] - b[i]));
  return d;
}

static void RunOptions(RigidRunOptions *opt, RigidSolver solver, int nblocks)
{
  rigid_default_run_options(opt);
  opt->solver        = solver;
  opt->krylov_blocks = nblocks;
  opt->h             = 1e-3;
  opt->t_end         = 0.05;
  opt->outputs       = 5;
}

/* 1. SPGMR + block preconditioner against KLU. */
static void CompareWithKLU(SUNContext ctx, int n)
{
  const int blocks[3] = {1, 2, 4};
  RigidSystem *sys = chain_create(n, RB_R3XSO3, ctx);
  RigidRunOptions opt;
  RigidRunResult ref, kry;
  int k;
  CHECK(sys != NULL, "chain_create(%d)", n);
  if (sys == NULL) return;
  RunOptions(&opt, RB_KLU_CSC, 0);
  CHECK(rigid_run(sys, &opt, &ref) == 0, "KLU run, N = %d", n);
  for (k = 0; k < 3; k++) {
    double dq, dv, per;
    RunOptions(&opt, RB_SPGMR, blocks[k]);
    CHECK(rigid_run(sys, &opt, &kry) == 0, "SPGMR + %d blocks, N = %d: flag %d",
          blocks[k], n, kry.flag);
    dq  = MaxDiff(kry.q, ref.q, sys->G->nq);
    dv  = MaxDiff(kry.v, ref.v, sys->G->nv);
    per = kry.nni > 0 ? (double)kry.nli / (double)kry.nni : 0.0;
    printf("N = %3d, %d block(s): max|dq| = %.2e  max|dv| = %.2e  Newton %ld "
           "(KLU %ld)  Krylov %ld (%.2f per Newton iteration)  prec setups %ld "
           "solves %ld  products %ld  short %ld\n",
           n, blocks[k], dq, dv, kry.nni, ref.nni, kry.nli, per, kry.npe,
           kry.nps, kry.njtimes, kry.nlcf);
    CHECK(dq <= 1e-7, "N = %d, %d blocks: max|q - q_KLU| = %.3e > 1e-7", n,
          blocks[k], dq);
    CHECK(dv <= 1e-6, "N = %d, %d blocks: max|v - v_KLU| = %.3e > 1e-6", n,
          blocks[k], dv);
    CHECK(kry.nsteps == ref.nsteps, "same number of steps");
    CHECK(kry.nlcf == 0, "no linear solve short of its tolerance (%ld)", kry.nlcf);
    CHECK(per <= (blocks[k] == 1 ? 2.0 : 30.0),
          "N = %d, %d blocks: %.2f Krylov iterations per Newton iteration", n,
          blocks[k], per);
    CHECK(kry.npe == kry.nlsetups, "a preconditioner setup per matrix setup");
    CHECK(kry.nps > 0 && kry.njtimes > 0, "preconditioner solves and products counted");
    rigid_result_free(&kry);
  }
  rigid_result_free(&ref);
  rigid_free(&sys);
}

/* 2. No preconditioner on a small chain. */
static void Unpreconditioned(SUNContext ctx)
{
  RigidSystem *sys = chain_create(3, RB_R3XSO3, ctx);
  RigidRunOptions opt;
  RigidRunResult ref, kry;
  CHECK(sys != NULL, "chain_create(3)");
  if (sys == NULL) return;
  RunOptions(&opt, RB_KLU_CSC, 0);
  CHECK(rigid_run(sys, &opt, &ref) == 0, "KLU run, N = 3");
  RunOptions(&opt, RB_SPGMR, 0);
  opt.krylov_maxl = 40;
  CHECK(rigid_run(sys, &opt, &kry) == 0, "SPGMR without preconditioner: flag %d",
        kry.flag);
  printf("N = 3, no preconditioner: max|dq| = %.2e  Krylov %ld per Newton "
         "iteration %.2f  prec solves %ld\n", MaxDiff(kry.q, ref.q, sys->G->nq),
         kry.nli, kry.nni > 0 ? (double)kry.nli / kry.nni : 0.0, kry.nps);
  CHECK(MaxDiff(kry.q, ref.q, sys->G->nq) <= 1e-7, "unpreconditioned agrees with KLU");
  CHECK(kry.nps == 0 && kry.npe == 0, "no preconditioner calls");
  CHECK(kry.nli > 0, "Krylov iterations counted");
  rigid_result_free(&kry);
  rigid_result_free(&ref);
  rigid_free(&sys);
}
#endif /* LGN_HAVE_KLU */

/* ---- a chain set up by hand (for the user preconditioner and errors) ---- */

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((RigidSystem *)ud)->joints, t, q, phi) == 0 ? 0 : -1;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((RigidSystem *)ud)->joints, t, q, B) == 0 ? 0 : -1;
}

static void *ChainMem(RigidSystem *sys, SUNContext ctx)
{
  RigidCallbacks cb;
  void *mem = LGNCreate(ctx);
  int flag;
  rigid_get_callbacks(&cb);
  flag = LGNSetGroup(mem, sys->G);
  if (flag == 0) flag = LGNInit(mem, 0.0, sys->q0, sys->v0);
  if (flag == 0) flag = LGNSetUserData(mem, sys);
  if (flag == 0) flag = LGNSetMassFn(mem, cb.mass);
  if (flag == 0) flag = LGNSetForceFn(mem, cb.force);
  if (flag == 0) flag = LGNSetStiffnessFn(mem, cb.stiffness);
  if (flag == 0) flag = LGNSetDampingFn(mem, cb.damping);
  if (flag == 0)
    flag = LGNSetConstraints(mem, LGNJoints_NumConstraints(sys->joints), Constr, ConstrJac);
  if (flag == 0) flag = LGNSetStepSize(mem, 1e-3);
  if (flag == 0) flag = LGNSetGenAlpha(mem, 0.9);
  CHECK(flag == 0, "chain set up by hand (%d)", flag);
  return mem;
}

typedef struct {
  long int nsetup, nsolve, nic, nstep;
  int bad_args;
} PrecLog;
static PrecLog prec_log;

static int IdentitySetup(sunrealtype t, N_Vector q, N_Vector v, sunrealtype cM,
                         sunrealtype cC, sunrealtype cK, void *user_data)
{
  (void)t;
  prec_log.nsetup++;
  if (q == NULL || v == NULL || user_data == NULL) prec_log.bad_args = 1;
  if (cM == 1.0 && cC == 0.0 && cK == 0.0) prec_log.nic++;
  else if (cM > 0.0 && cC > 0.0 && cK > 0.0 && cK < cC && cC < cM) prec_log.nstep++;
  else prec_log.bad_args = 1;
  return 0;
}

static int IdentitySolve(sunrealtype t, N_Vector q, N_Vector v, N_Vector r,
                         N_Vector z, sunrealtype cM, sunrealtype cC,
                         sunrealtype cK, sunrealtype delta, void *user_data)
{
  (void)t; (void)q; (void)v; (void)cM; (void)cC; (void)cK; (void)user_data;
  prec_log.nsolve++;
  if (!(delta >= 0.0)) prec_log.bad_args = 1;
  N_VScale(1.0, r, z);
  return 0;
}

/* 3. The user preconditioner's callbacks. */
static void UserPreconditioner(SUNContext ctx)
{
  RigidSystem *sys = chain_create(3, RB_R3XSO3, ctx);
  const sunindextype n = sys->G->nv + LGNJoints_NumConstraints(sys->joints);
  N_Vector y = N_VNew_Serial(n, ctx), q = N_VClone(sys->q0), v = N_VClone(sys->v0);
  SUNLinearSolver LS = SUNLinSol_SPGMR(y, SUN_PREC_LEFT, 40, ctx);
  void *mem = ChainMem(sys, ctx);
  long int npe = 0, nps = 0, nli = 0, njt = 0;
  sunrealtype t = 0.0;
  memset(&prec_log, 0, sizeof prec_log);
  SUNLinSol_SPGMRSetMaxRestarts(LS, 2);
  CHECK(LGNSetLinearSolver(mem, LS, NULL) == LGN_SUCCESS, "SPGMR attached");
  CHECK(LGNSetPreconditioner(mem, IdentitySetup, IdentitySolve) == LGN_SUCCESS,
        "user preconditioner attached");
  CHECK(LGNSolve(mem, 0.01, &t, q, v, LGN_NORMAL) == LGN_SUCCESS, "solve with it");
  LGNGetNumPrecEvals(mem, &npe);
  LGNGetNumPrecSolves(mem, &nps);
  LGNGetNumLinIters(mem, &nli);
  LGNGetNumJtimesEvals(mem, &njt);
  printf("user preconditioner: setups %ld (initial values %ld, steps %ld), "
         "solves %ld; Krylov %ld, products %ld\n", prec_log.nsetup, prec_log.nic,
         prec_log.nstep, prec_log.nsolve, nli, njt);
  CHECK(prec_log.nsetup == npe && prec_log.nsolve == nps, "counted as called");
  CHECK(prec_log.nic >= 1 && prec_log.nstep >= 10, "setups at the initial values and in the steps");
  CHECK(!prec_log.bad_args, "the callbacks' arguments");
  CHECK(LGNPrintAllStats(mem, stdout, SUN_OUTPUTFORMAT_TABLE) == LGN_SUCCESS, "stats");
  LGNFree(&mem);
  SUNLinSolFree(LS);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
  rigid_free(&sys);
}

/* 4. Bad input. */
static void BadInput(SUNContext ctx)
{
  RigidSystem *sys = chain_create(4, RB_R3XSO3, ctx);
  const sunindextype n = sys->G->nv + LGNJoints_NumConstraints(sys->joints);
  N_Vector y = N_VNew_Serial(n, ctx), q = N_VClone(sys->q0), v = N_VClone(sys->v0);
  SUNMatrix D = SUNDenseMatrix(n, n, ctx);
  SUNLinearSolver dense = SUNLinSol_Dense(y, D, ctx);
  SUNLinearSolver none = SUNLinSol_SPGMR(y, SUN_PREC_NONE, 20, ctx);
  SUNLinearSolver left = SUNLinSol_SPGMR(y, SUN_PREC_LEFT, 20, ctx);
  void *mem = ChainMem(sys, ctx);
  const long int bad_order[3] = {0, 3, 2}, bad_start[3] = {1, 2, 4};
  const long int short_end[3] = {0, 2, 3};
  long int out;
  sunrealtype t = 0.0;

  LGNSetErrFile(mem, stdout);
  CHECK(LGNSetLinearSolver(mem, dense, NULL) == LGN_ILL_INPUT,
        "a direct solver with A = NULL");
  CHECK(LGNSetLinearSolver(mem, left, D) == LGN_ILL_INPUT,
        "a matrix-free solver with a matrix");
  CHECK(LGNSetLinearSolver(mem, NULL, NULL) == LGN_ILL_INPUT, "LS = NULL");
  CHECK(LGNSetPreconditioner(mem, IdentitySetup, NULL) == LGN_ILL_INPUT,
        "psolve = NULL with psetup");
  CHECK(LGNSetPreconditioner(NULL, NULL, IdentitySolve) == LGN_MEM_NULL, "mem = NULL");
  CHECK(LGNSetPreconditioner(mem, NULL, NULL) == LGN_SUCCESS, "both NULL: off");
  CHECK(LGNSetEpsLin(mem, -1.0) == LGN_ILL_INPUT, "eplifac < 0");
  CHECK(LGNSetBlockPreconditioner(mem, -1, NULL) == LGN_ILL_INPUT, "nblocks < 0");
  CHECK(LGNSetBlockPreconditioner(mem, 2, bad_order) == LGN_ILL_INPUT,
        "a partition not increasing");
  CHECK(LGNSetBlockPreconditioner(mem, 2, bad_start) == LGN_ILL_INPUT,
        "a partition not starting at body 0");
  CHECK(LGNGetNumLinIters(mem, NULL) == LGN_ILL_INPUT, "nliters = NULL");
  CHECK(LGNGetNumPrecEvals(NULL, &out) == LGN_MEM_NULL, "getter, mem = NULL");
#if defined(LGN_HAVE_KLU)
  /* a preconditioner with a PREC_NONE solver: refused at the solve */
  CHECK(LGNSetLinearSolver(mem, none, NULL) == LGN_SUCCESS, "SPGMR PREC_NONE attached");
  CHECK(LGNSetBlockPreconditioner(mem, 2, NULL) == LGN_SUCCESS, "2 blocks");
  CHECK(LGNSolve(mem, 0.01, &t, q, v, LGN_NORMAL) == LGN_LS_MISMATCH,
        "a preconditioner with PREC_NONE");
  /* a partition that ends short of the bodies, or too many blocks */
  CHECK(LGNSetLinearSolver(mem, left, NULL) == LGN_SUCCESS, "SPGMR PREC_LEFT attached");
  CHECK(LGNSetBlockPreconditioner(mem, 2, short_end) == LGN_SUCCESS, "recorded");
  CHECK(LGNSolve(mem, 0.01, &t, q, v, LGN_NORMAL) == LGN_ILL_INPUT,
        "a partition ending at body 3 of 4");
  CHECK(LGNSetBlockPreconditioner(mem, 5, NULL) == LGN_SUCCESS, "recorded");
  CHECK(LGNSolve(mem, 0.01, &t, q, v, LGN_NORMAL) == LGN_ILL_INPUT, "5 blocks of 4 bodies");
  /* and then a correct one works, switching back to a direct solver too */
  CHECK(LGNSetBlockPreconditioner(mem, 2, NULL) == LGN_SUCCESS, "2 blocks");
  CHECK(LGNSolve(mem, 0.005, &t, q, v, LGN_NORMAL) == LGN_SUCCESS, "then it runs");
  CHECK(LGNSetLinearSolver(mem, dense, D) == LGN_SUCCESS, "back to dense");
  CHECK(LGNSolve(mem, 0.01, &t, q, v, LGN_NORMAL) == LGN_SUCCESS, "dense runs on");
#else
  (void)none; (void)short_end; (void)t;
  CHECK(LGNSetBlockPreconditioner(mem, 2, NULL) == LGN_ILL_INPUT, "no KLU: refused");
#endif
  LGNFree(&mem);
  SUNLinSolFree(dense);
  SUNLinSolFree(none);
  SUNLinSolFree(left);
  SUNMatDestroy(D);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
  rigid_free(&sys);
}

int main(void)
{
  SUNContext ctx;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
#if defined(LGN_HAVE_KLU)
  CompareWithKLU(ctx, 20);
  CompareWithKLU(ctx, 200);
  Unpreconditioned(ctx);
#endif
  UserPreconditioner(ctx);
  BadInput(ctx);
  SUNContext_Free(&ctx);
  return test_summary("test_krylov");
}
