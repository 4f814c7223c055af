/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Matrix-free Krylov solvers (SUNLINEARSOLVER_ITERATIVE: SPGMR, SPFGMR,
 * SPBCGS, SPTFQMR) for the Newton iteration, after IDA's idals.c:
 *
 *   - ATimes: the product with the scaled iteration matrix. Lignum
 *     assembles that matrix from its table of terms (lgn_matrix.c) into a
 *     CSC matrix of its own (allocated by lgn_mem.c) where a direct solver
 *     would factor it, and multiplies with it: the Krylov solver solves the
 *     very system KLU would, one pass over its entries per product, and the
 *     block preconditioner takes its blocks from it;
 *   - the preconditioner: the user's (LGNSetPreconditioner) or Lignum's
 *     block-Jacobi one (LGNSetBlockPreconditioner, lgn_blockprec.c), set up
 *     by SUNLinSolSetup and applied through SUNLinSolSetPreconditioner;
 *   - the tolerance: in a Newton iteration the weights of its correction
 *     norm (lgn_newton.c, CorrectionNorm) as the solver's scaling vectors,
 *     and delta = eplifac sqrt(nv + m), i.e. a weighted RMS residual of
 *     eplifac (0.05) of Newton's tolerance 1; other solves (consistent
 *     initial values, the error estimate's projection) stop at a relative
 *     residual of 1e-10;
 *   - the counters (Krylov iterations, preconditioner setups and solves,
 *     products, solves short of their tolerance) and their getters.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_spbcgs.h>
#include <sunlinsol/sunlinsol_spfgmr.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunlinsol/sunlinsol_sptfqmr.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_blockprec.h"
#include "lgn_impl.h"
#include "lgn_sparse.h"

/* Solves outside Newton: a relative residual of 1e-10. */
#define KRYLOV_RTOL_OTHER SUN_RCONST(1.0e-10)

/* =============================================================================
 * Attaching and checking
 * ===========================================================================*/

/* LS's preconditioning side, read from the contents SUNDIALS publishes for
 * its own solvers (-1: a solver of another kind). */
static int PrecType(SUNLinearSolver LS)
{
  switch (SUNLinSolGetID(LS)) {
  case SUNLINEARSOLVER_SPGMR:
    return ((SUNLinearSolverContent_SPGMR)LS->content)->pretype;
  case SUNLINEARSOLVER_SPFGMR:
    return ((SUNLinearSolverContent_SPFGMR)LS->content)->pretype;
  case SUNLINEARSOLVER_SPBCGS:
    return ((SUNLinearSolverContent_SPBCGS)LS->content)->pretype;
  case SUNLINEARSOLVER_SPTFQMR:
    return ((SUNLinearSolverContent_SPTFQMR)LS->content)->pretype;
  default: return -1;
  }
}

/* The local length of the vectors LS was made for (a clone of its template
 * y, in the contents SUNDIALS publishes for its own solvers; -1: unknown). */
static sunindextype TemplateLength(SUNLinearSolver LS)
{
  N_Vector x = NULL;
  switch (SUNLinSolGetID(LS)) {
  case SUNLINEARSOLVER_SPGMR: x = ((SUNLinearSolverContent_SPGMR)LS->content)->vtemp; break;
  case SUNLINEARSOLVER_SPFGMR: x = ((SUNLinearSolverContent_SPFGMR)LS->content)->vtemp; break;
  case SUNLINEARSOLVER_SPBCGS: x = ((SUNLinearSolverContent_SPBCGS)LS->content)->vtemp; break;
  case SUNLINEARSOLVER_SPTFQMR: x = ((SUNLinearSolverContent_SPTFQMR)LS->content)->vtemp1; break;
  default: break;
  }
  return x != NULL ? lgnLocalLength(x) : -1;
}

/* LGNSetLinearSolver with a matrix-free solver (A = NULL, checked there). */
int lgnKrylovAttach(LGNMem mem, SUNLinearSolver LS)
{
  if (SUNLinSolGetID(LS) == SUNLINEARSOLVER_PCG) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "SUNLinSol_PCG needs a symmetric positive definite matrix; the "
              "saddle-point iteration matrix is indefinite: use SPGMR, "
              "SPFGMR, SPBCGS or SPTFQMR.");
    return LGN_LS_MISMATCH;
  }
  if (LS->ops->setatimes == NULL) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "The iterative linear solver takes no ATimes function "
              "(SUNLinSolSetATimes): Lignum cannot apply its matrix.");
    return LGN_LS_MISMATCH;
  }
  lgnFreeRedundancySolver(mem); /* a stand-in for the old direct solver */
  if (!mem->krylov) {
    mem->A = NULL; /* the user's matrix of a direct solver: not ours */
    mem->own_A = SUNFALSE;
  }
  mem->krylov = SUNTRUE;
  mem->LS     = LS;
  mem->kry_pretype = PrecType(LS);
  lgnInvalidate(mem, LGN_CHANGE_LINSOL);
  return LGN_SUCCESS;
}

static int ATimes(void *A_data, N_Vector v, N_Vector z);
static int PSetup(void *P_data);
static int PSolve(void *P_data, N_Vector r, N_Vector z, sunrealtype tol, int lr);

static sunbooleantype HasPreconditioner(const LGNMem mem)
{
  return mem->psolve != NULL || mem->bp_nblocks > 0;
}

/* The block preconditioner for the current sizes and group: the bodies
 * (leaves) of the partition as velocity offsets; with ghost bodies, the
 * owned ones (the ghosts' unknowns are other ranks'). */
static int MakeBlockPreconditioner(LGNMem mem)
{
#if defined(LGN_HAVE_KLU)
  const int nb = mem->bp_nblocks, nbody = lgnGhostsOwnedBodies(mem);
  const sunindextype n = mem->nv + mem->m;
  sunindextype *voff;
  int b;
  if (lgnBlockPrecFits(mem->bp, n, mem->nv, nb)) return LGN_SUCCESS;
  lgnBlockPrecFree(&mem->bp);
  if (nb > nbody) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "%d blocks for the block preconditioner but only %d %sbodies "
              "(leaves of the Lie group).", nb, nbody, mem->halo != NULL ? "owned " : "");
    return LGN_ILL_INPUT;
  }
  if (mem->bp_bodies != NULL && mem->bp_bodies[nb] != (long int)nbody) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The block preconditioner's partition ends at body %ld, but "
              "there are %d %sbodies (leaves of the Lie group).",
              mem->bp_bodies[nb], nbody, mem->halo != NULL ? "owned " : "");
    return LGN_ILL_INPUT;
  }
  voff = (sunindextype *)malloc((size_t)(nb + 1) * sizeof *voff);
  if (voff == NULL) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  for (b = 0; b <= nb; b++) {
    const long int body = mem->bp_bodies != NULL
                              ? mem->bp_bodies[b]
                              : (long int)(((long long)b * nbody) / nb);
    voff[b] = mem->blk_voff[body];
  }
  mem->bp = lgnBlockPrecCreate(n, mem->nv, nb, voff);
  free(voff);
  if (mem->bp == NULL) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  return LGN_SUCCESS;
#else
  LGN_ERROR(mem, LGN_ILL_INPUT,
            "The block preconditioner needs Lignum built with KLU.");
  return LGN_ILL_INPUT;
#endif
}

/* The preconditioner against the side the solver was made for: no model
 * size enters, so LGNSolve checks it before the model is evaluated. */
int lgnKrylovCheckPreconditioner(LGNMem mem)
{
  const sunbooleantype prec = HasPreconditioner(mem);
  if (!prec && (mem->kry_pretype == SUN_PREC_LEFT || mem->kry_pretype == SUN_PREC_RIGHT ||
                mem->kry_pretype == SUN_PREC_BOTH)) {
    /* SUNLinSolInitialize would fail with SUNLS_PSOLVE_NULL (-807) */
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "The Krylov solver was created with %s but no preconditioner is "
              "attached: call LGNSetPreconditioner or LGNSetBlockPreconditioner, "
              "or create it with SUN_PREC_NONE.",
              mem->kry_pretype == SUN_PREC_LEFT    ? "SUN_PREC_LEFT (PREC_LEFT)"
              : mem->kry_pretype == SUN_PREC_RIGHT ? "SUN_PREC_RIGHT (PREC_RIGHT)"
                                                   : "SUN_PREC_BOTH (PREC_BOTH)");
    return LGN_LS_MISMATCH;
  }
  if (prec && (mem->kry_pretype == SUN_PREC_NONE ||
               (mem->kry_pretype == SUN_PREC_RIGHT &&
                SUNLinSolGetID(mem->LS) != SUNLINEARSOLVER_SPFGMR))) {
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "A preconditioner is attached but the Krylov solver was created "
              "with %s: create it with PREC_LEFT (SPFGMR: PREC_RIGHT), the "
              "side whose residual Lignum's tolerance measures.",
              mem->kry_pretype == SUN_PREC_NONE ? "PREC_NONE" : "PREC_RIGHT");
    return LGN_LS_MISMATCH;
  }
  return LGN_SUCCESS;
}

/* Before the first solve (lgnLsCheck): Lignum's matrix and vectors for the
 * sizes, the block preconditioner, and the hooks handed to the solver. */
int lgnKrylovCheck(LGNMem mem)
{
  const sunbooleantype prec = HasPreconditioner(mem);
  const sunindextype len = TemplateLength(mem->LS), n = mem->nv_own + mem->m;
  int flag = LGN_SUCCESS, ret;
  if (len >= 0 && len != n) {
    /* its vectors would be read and written past their ends */
    LGN_ERROR(mem, LGN_LS_MISMATCH,
              "The Krylov solver was made for vectors of local length %lld, but this "
              "rank's unknowns are %lld (%s%lld velocities + m = %lld constraints%s): "
              "make it with a template of that length.",
              (long long)len, (long long)n, mem->halo != NULL ? "the owned bodies' " : "",
              (long long)mem->nv_own, (long long)mem->m,
              mem->red_nout > 0 ? ", the rows kept of a redundant set: "
                                  "LGNGetRedundantConstraints lists those left out" : "");
    flag = LGN_LS_MISMATCH;
  }
  /* agreed before lgnAllocKrylov, which is collective */
  flag = lgnAgree(mem, flag);
  if (flag != LGN_SUCCESS) return flag;
  flag = lgnAllocKrylov(mem);
  if (flag != LGN_SUCCESS) return flag;
  flag = lgnKrylovCheckPreconditioner(mem);
  if (flag != LGN_SUCCESS) return flag;
  if (mem->bp_nblocks > 0) {
    flag = MakeBlockPreconditioner(mem);
    if (flag != LGN_SUCCESS) return flag;
  } else {
    lgnBlockPrecFree(&mem->bp);
  }
  ret = SUNLinSolSetATimes(mem->LS, mem, ATimes);
  if (ret == 0)
    ret = SUNLinSolSetPreconditioner(mem->LS, mem, prec ? PSetup : NULL,
                                     prec ? PSolve : NULL);
  if (ret == 0 && mem->LS->ops->setscalingvectors != NULL)
    ret = SUNLinSolSetScalingVectors(mem->LS, mem->kry_w, mem->kry_w);
  if (ret != 0) {
    LGN_ERROR(mem, LGN_LINIT_FAIL,
              "The Krylov solver refused Lignum's ATimes, preconditioner or "
              "scaling vectors (%d).", ret);
    return LGN_LINIT_FAIL;
  }
  return LGN_SUCCESS;
}

/* =============================================================================
 * ATimes and the preconditioner, as the Krylov solver calls them
 * ===========================================================================*/

/* z = A v with the assembled iteration matrix. With ghost bodies v and z
 * hold the owned unknowns: A is this rank's part of the sum over the ranks
 * (lgn_ghosts.c), so v's ghost entries come from their owners, and the
 * product's ghost rows go to them. */
static int ATimes(void *A_data, N_Vector v, N_Vector z)
{
  LGNMem mem = (LGNMem)A_data;
  mem->njtimes++;
  if (mem->halo != NULL) {
    lgnGhostsExpand(mem, lgnData(v), mem->hx_ext);
    lgnMatvec(mem->A, mem->hx_ext, mem->hx_ext2, SUNFALSE);
    lgnGhostsFold(mem, mem->hx_ext2, lgnData(z));
    return 0;
  }
  lgnMatvec(mem->A, lgnData(v), lgnData(z), SUNFALSE);
  return 0;
}

#if defined(LGN_HAVE_KLU)
/* The block solve with ghost bodies: r and z hold the owned unknowns, the
 * blocks index the rank's whole matrix (ghost entries: in no block). */
static int BlockSolveOwned(LGNMem mem, const sunrealtype *r, sunrealtype *z)
{
  const sunindextype nvo = mem->nv_own, nv = mem->nv, m = mem->m;
  int ret;
  memcpy(mem->hx_ext, r, (size_t)nvo * sizeof(sunrealtype));
  memset(mem->hx_ext + nvo, 0, (size_t)(nv - nvo) * sizeof(sunrealtype));
  memcpy(mem->hx_ext + nv, r + nvo, (size_t)m * sizeof(sunrealtype));
  ret = lgnBlockPrecSolve(mem->bp, mem->hx_ext, mem->hx_ext);
  lgnGhostsRestrict(mem, mem->hx_ext, z);
  return ret;
}
#endif

/* The user's setup at the matrix's iterate and scalings, or the blocks'
 * factorisations. Returns the callback's sign convention. */
static int PSetup(void *P_data)
{
  LGNMem mem = (LGNMem)P_data;
  mem->npe++;
  if (mem->bp_nblocks > 0 && mem->bp != NULL) {
#if defined(LGN_HAVE_KLU)
    return lgnBlockPrecSetup(mem->bp, SUNSparseMatrix_IndexPointers(mem->A),
                             SUNSparseMatrix_IndexValues(mem->A),
                             SUNSparseMatrix_Data(mem->A),
                             mem->sp != NULL ? mem->sp->npattern : 0L);
#else
    return -1;
#endif
  }
  if (mem->psetup == NULL) return 0;
  return mem->psetup(mem->asm_t, mem->q1, mem->v1, mem->asm_cM, mem->asm_cC,
                     mem->asm_cK, mem->user_data);
}

static int PreconditionerSolve(LGNMem mem, N_Vector r, N_Vector z, sunrealtype tol)
{
  if (mem->bp_nblocks > 0 && mem->bp != NULL) {
#if defined(LGN_HAVE_KLU)
    if (mem->halo != NULL) return BlockSolveOwned(mem, lgnData(r), lgnData(z));
    return lgnBlockPrecSolve(mem->bp, lgnData(r), lgnData(z));
#else
    return -1;
#endif
  }
  if (mem->psolve == NULL) {
    N_VScale(SUN_RCONST(1.0), r, z);
    return 0;
  }
  return mem->psolve(mem->asm_t, mem->q1, mem->v1, r, z, mem->asm_cM,
                     mem->asm_cC, mem->asm_cK, tol, mem->user_data);
}

/* Across ranks a failure must not end the Krylov iteration on one rank
 * while the others go on with its (collective) inner products: it is
 * recorded (kry_pfail), z = r, and the solve is failed on every rank after
 * it (lgnKrylovSolve). */
static int PSolve(void *P_data, N_Vector r, N_Vector z, sunrealtype tol, int lr)
{
  LGNMem mem = (LGNMem)P_data;
  int ret;
  (void)lr;
  mem->nps++;
  ret = PreconditionerSolve(mem, r, z, tol);
  if (ret == 0 || mem->par == NULL) return ret;
  if (mem->kry_pfail == 0 || ret < 0) mem->kry_pfail = ret;
  N_VScale(SUN_RCONST(1.0), r, z);
  return 0;
}

/* =============================================================================
 * Setup and solve (lgnLsSetup, lgnLsSolve)
 * ===========================================================================*/

/* A recoverable failure of the preconditioner or of the Krylov solve:
 * error control retries the step smaller (LGN_RECOVERABLE, internal); a
 * fixed step size cannot be reduced, so it is the named failure `fatal`
 * (as lgnCallbackFlag does for the callbacks), never LGN_RECOVERABLE. */
static int RecoverableFailure(LGNMem mem, int fatal, const char *what, int ret,
                              const char *detail)
{
  if (mem->step_control == LGN_STEP_ADAPTIVE) return LGN_RECOVERABLE;
  LGN_ERROR(mem, fatal,
            MSG_TIME "%s failed recoverably (%d) and the fixed step size cannot be "
            "reduced.%s", (double)mem->tn, what, ret, detail);
  return fatal;
}

/* The preconditioner's setup with the matrix just assembled. */
int lgnKrylovSetup(LGNMem mem)
{
  int ret = SUNLinSolSetup(mem->LS, NULL);
  mem->last_lin_flag = ret;
  mem->diag_text[0]  = '\0';
  if (ret == 0) return LGN_SUCCESS;
  if (ret > 0 && mem->bp_nblocks > 0 && mem->bp != NULL) {
    /* the whole matrix may be regular: a block keeps only its own columns */
    snprintf(mem->diag_text, sizeof mem->diag_text,
             " A block of the block preconditioner%s is singular: a block keeps the "
             "columns of its own bodies only, so its constraints must be independent "
             "on them; %s, or use a direct solver (KLU%s).",
             mem->halo != NULL ? " on this rank" : "",
             mem->halo != NULL ? "declare a joint at a cut on the rank where this holds "
                                 "(not beside another joint that holds the same owned body)"
                               : "cut the partition elsewhere",
             mem->halo != NULL ? " on one rank, MUMPS across ranks" : ", MUMPS");
  }
  if (ret > 0) /* a smaller step may help */
    return RecoverableFailure(mem, LGN_LSETUP_FAIL, "the preconditioner setup", ret,
                              mem->diag_text);
  LGN_ERROR(mem, LGN_LSETUP_FAIL,
            MSG_TIME "the preconditioner setup failed (%d)%s.", (double)mem->tn,
            ret,
            mem->bp_nblocks > 0 ? ": a block of the block preconditioner "
                                  "could not be factored (singular, or memory "
                                  "refused)"
                                : "");
  return LGN_LSETUP_FAIL;
}

/* The weights of Newton's correction norm (lgn_newton.c, CorrectionNorm:
 * the same formulas, which must stay in step with it) into kry_w: on
 * sigma 1/(atol h + rtol |sigma_i| + roundoff) (per component: atol_i h),
 * on the scaled multiplier correction dmu = beta h^2 dlambda
 * 1/((scale/h)(atol + roundoff/(beta h)) + (scale/h) rtol |h lambda_i|).
 * The next solve is Newton's. */
void lgnKrylovNewtonWeights(LGNMem mem, const LGNStepCoeffs *c)
{
  const sunindextype nv = mem->nv_own, m = mem->m; /* the solver's unknowns */
  const sunrealtype h = c->h, rtol = mem->nls_rtol, atol = mem->nls_atol;
  const sunrealtype *lambda1 = m > 0 ? lgnData(mem->lambda1) : NULL;
  const sunrealtype roundoff = SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * c->qscale;
  const sunrealtype sigma_atol  = atol * h + roundoff;
  const sunrealtype lambda_unit = c->scale / h;
  const sunrealtype lambda_atol = atol + roundoff / (mem->beta * h);
  sunrealtype *w = lgnData(mem->kry_w);
  sunindextype i;
  for (i = 0; i < nv; i++)
    w[i] = SUN_RCONST(1.0) /
           (mem->nls_atolv != NULL
                ? h * mem->nls_vfac * mem->nls_atolv[i] + roundoff + rtol * fabs(mem->sigma[i])
                : sigma_atol + rtol * fabs(mem->sigma[i]));
  for (i = 0; i < m; i++)
    w[nv + i] = SUN_RCONST(1.0) / (lambda_unit * lambda_atol +
                                   lambda_unit * mem->nls_lrtol * fabs(h * lambda1[i]));
  mem->kry_newton = SUNTRUE;
}

/* sqrt(sum (w_i x_i)^2), over all ranks */
static sunrealtype WeightedNorm(LGNMem mem, N_Vector x, N_Vector w)
{
  const sunindextype n = lgnLocalLength(x);
  const sunrealtype *px = lgnData(x), *pw = lgnData(w);
  sunrealtype s = SUN_RCONST(0.0);
  sunindextype i;
  for (i = 0; i < n; i++) s += (px[i] * pw[i]) * (px[i] * pw[i]);
  lgnSumAll(mem, &s, 1);
  return sqrt(s);
}

/* x = A^{-1} b to the tolerance of the caller (Newton: set by
 * lgnKrylovNewtonWeights; else relative), from x = 0. */
int lgnKrylovSolve(LGNMem mem, N_Vector x, N_Vector b)
{
  const sunrealtype n = mem->nv_all + mem->m_all; /* of all ranks */
  const sunbooleantype newton = mem->kry_newton;
  const sunbooleantype left = HasPreconditioner(mem) &&
                              mem->kry_pretype != SUN_PREC_RIGHT;
  sunrealtype delta;
  long int nli = 0;
  int ret, flag;
  mem->kry_newton = SUNFALSE;
  mem->kry_pfail  = 0;
  if (x == b) { /* the solver needs them apart */
    N_VScale(SUN_RCONST(1.0), b, mem->kry_tmp);
    b = mem->kry_tmp;
  }
  if (newton) {
    delta = mem->eplifac * sqrt(n);
  } else {
    /* unit weights, a relative residual: of P^{-1} b when the solver
     * measures the left-preconditioned residual */
    N_VConst(SUN_RCONST(1.0), mem->kry_w);
    if (left && b != mem->kry_tmp) {
      ret = PSolve(mem, b, mem->kry_tmp, SUN_RCONST(0.0), 1);
      if (ret != 0) {
        if (ret > 0)
          return RecoverableFailure(mem, LGN_LSOLVE_FAIL, "the preconditioner solve", ret, "");
        LGN_ERROR(mem, LGN_LSOLVE_FAIL,
                  MSG_TIME "the preconditioner solve failed (%d).",
                  (double)mem->tn, ret);
        return LGN_LSOLVE_FAIL;
      }
      delta = KRYLOV_RTOL_OTHER * WeightedNorm(mem, mem->kry_tmp, mem->kry_w);
    } else {
      delta = KRYLOV_RTOL_OTHER * WeightedNorm(mem, b, mem->kry_w);
    }
  }
  N_VConst(SUN_RCONST(0.0), x);
  if (!newton && delta == SUN_RCONST(0.0)) return LGN_SUCCESS; /* b = 0 */
  ret = SUNLinSolSolve(mem->LS, NULL, x, b, delta);
  nli = (long int)SUNLinSolNumIters(mem->LS);
  mem->nli += nli;
  mem->last_lin_flag = ret;
  if (mem->par != NULL) { /* a preconditioner that failed on some rank */
    if (mem->kry_pfail < 0)
      LGN_ERROR(mem, LGN_LSOLVE_FAIL, MSG_TIME "the preconditioner solve failed (%d).",
                (double)mem->tn, mem->kry_pfail);
    flag = lgnAgree(mem, mem->kry_pfail > 0
                             ? RecoverableFailure(mem, LGN_LSOLVE_FAIL,
                                                  "the preconditioner solve", mem->kry_pfail, "")
                         : mem->kry_pfail < 0 ? LGN_LSOLVE_FAIL
                                              : LGN_SUCCESS);
    if (flag != LGN_SUCCESS) return flag;
  }
  if (ret == SUNLS_SUCCESS) return LGN_SUCCESS;
  if (ret > 0) mem->nlcf++;
  /* an inexact Newton correction: Newton's own test judges it */
  if (ret == SUNLS_RES_REDUCED && newton) return LGN_SUCCESS;
  if (ret == SUNLS_PSOLVE_FAIL_REC || ret == SUNLS_ATIMES_FAIL_REC)
    return RecoverableFailure(mem, LGN_LSOLVE_FAIL, "the Krylov solve", ret, "");
  if (ret > 0 && newton) return LGN_CONV_FAILURE; /* no reduction at all */
  LGN_ERROR(mem, LGN_LSOLVE_FAIL,
            MSG_TIME "the Krylov solve failed (%d) after %ld iterations%s.",
            (double)mem->tn, ret, nli,
            ret > 0 ? ": the residual did not reach the tolerance (raise the "
                      "Krylov dimension or the restarts, or precondition)"
                    : "");
  return LGN_LSOLVE_FAIL;
}

/* =============================================================================
 * Settings and counters
 * ===========================================================================*/

int LGNSetPreconditioner(void *lgn_mem, LGNPrecSetupFn psetup,
                         LGNPrecSolveFn psolve)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (psolve == NULL && psetup != NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "psolve = NULL illegal with psetup given (both NULL switch the "
              "preconditioner off).");
    return LGN_ILL_INPUT;
  }
  mem->psetup     = psetup;
  mem->psolve     = psolve;
  mem->bp_nblocks = 0; /* the user's takes the block preconditioner's place */
  free(mem->bp_bodies);
  mem->bp_bodies = NULL;
  lgnBlockPrecFree(&mem->bp);
  mem->lu_valid = SUNFALSE; /* the next Newton iteration sets it up */
  return LGN_SUCCESS;
}

int LGNSetBlockPreconditioner(void *lgn_mem, int nblocks,
                              const long int *body_start)
{
  LGNMem mem;
  long int *copy = NULL;
  int b, flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
#if !defined(LGN_HAVE_KLU)
  if (nblocks != 0) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "The block preconditioner factors its blocks with KLU: build "
              "Lignum with LGN_ENABLE_KLU=ON.");
    return LGN_ILL_INPUT;
  }
#endif
  if (nblocks < 0) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "nblocks = %d < 0 illegal.", nblocks);
    return LGN_ILL_INPUT;
  }
  if (nblocks > 0 && body_start != NULL) {
    if (body_start[0] != 0) {
      LGN_ERROR(mem, LGN_ILL_INPUT,
                "body_start[0] = %ld illegal: the first block starts at body 0.",
                body_start[0]);
      return LGN_ILL_INPUT;
    }
    for (b = 0; b < nblocks; b++)
      if (body_start[b + 1] <= body_start[b]) {
        LGN_ERROR(mem, LGN_ILL_INPUT,
                  "body_start[%d] = %ld <= body_start[%d] = %ld illegal: "
                  "every block holds at least one body.",
                  b + 1, body_start[b + 1], b, body_start[b]);
        return LGN_ILL_INPUT;
      }
    copy = (long int *)malloc((size_t)(nblocks + 1) * sizeof *copy);
    if (copy == NULL) {
      LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
      return LGN_MEM_FAIL;
    }
    memcpy(copy, body_start, (size_t)(nblocks + 1) * sizeof *copy);
  }
  free(mem->bp_bodies);
  mem->bp_bodies  = copy;
  mem->bp_nblocks = nblocks;
  mem->psetup     = NULL;
  mem->psolve     = NULL;
  lgnBlockPrecFree(&mem->bp);
  mem->lu_valid = SUNFALSE;
  return LGN_SUCCESS;
}

int LGNSetEpsLin(void *lgn_mem, sunrealtype eplifac)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (eplifac < SUN_RCONST(0.0) || !isfinite(eplifac)) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "eplifac = %g illegal (>= 0; 0: the default %g).",
              (double)eplifac, (double)LGN_EPLIFAC_DEFAULT);
    return LGN_ILL_INPUT;
  }
  mem->eplifac = eplifac == SUN_RCONST(0.0) ? LGN_EPLIFAC_DEFAULT : eplifac;
  return LGN_SUCCESS;
}

/* The getters: memory, then the output pointer. */
static int Counter(void *lgn_mem, const char *func, long int *out,
                   const char *name, LGNMem *mem)
{
  int flag = lgnAccessMem(lgn_mem, func, mem);
  if (flag != LGN_SUCCESS) return flag;
  if (out == NULL) {
    LGN_ERROR(*mem, LGN_ILL_INPUT, "%s = NULL illegal.", name);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int LGNGetNumLinIters(void *lgn_mem, long int *nliters)
{
  LGNMem mem;
  int flag = Counter(lgn_mem, __func__, nliters, "nliters", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nliters = mem->nli;
  return LGN_SUCCESS;
}

int LGNGetNumPrecEvals(void *lgn_mem, long int *npevals)
{
  LGNMem mem;
  int flag = Counter(lgn_mem, __func__, npevals, "npevals", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *npevals = mem->npe;
  return LGN_SUCCESS;
}

int LGNGetNumPrecSolves(void *lgn_mem, long int *npsolves)
{
  LGNMem mem;
  int flag = Counter(lgn_mem, __func__, npsolves, "npsolves", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *npsolves = mem->nps;
  return LGN_SUCCESS;
}

int LGNGetNumJtimesEvals(void *lgn_mem, long int *njvevals)
{
  LGNMem mem;
  int flag = Counter(lgn_mem, __func__, njvevals, "njvevals", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *njvevals = mem->njtimes;
  return LGN_SUCCESS;
}

int LGNGetNumLinConvFails(void *lgn_mem, long int *nlcfails)
{
  LGNMem mem;
  int flag = Counter(lgn_mem, __func__, nlcfails, "nlcfails", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nlcfails = mem->nlcf;
  return LGN_SUCCESS;
}
