/* -----------------------------------------------------------------------------
 * Full and modified Newton (LGNSetNewtonMode) give the same solution to the
 * Newton tolerance, the modified iteration reuses the factorised matrix and
 * rebuilds it when it must: after a change of step size, and by a restart of
 * the step when the iteration fails with an old matrix, and stops, like full
 * Newton, when the multipliers of a long chain stall at roundoff level.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <lignum/lignum_config.h> /* LGN_HAVE_KLU */

#include "models/chain.h"
#include "models/heavy_top.h"
#include "test_util.h"

/* ---------------------------------------------------------------------------
 * 1. Heavy top: full vs modified Newton.
 * The Newton stop test bounds each correction of sigma/h by rtol |sigma/h|
 * (+ atol) per component, so the per-step error of sigma is at most about
 * h rtol |v|; over t_end/h steps the two solutions may drift apart by
 * t_end rtol |v|_max (|v| <= 160 here) — the bound asserted below. Full
 * Newton itself is far inside it (quadratic convergence).
 * ------------------------------------------------------------------------- */
static void HeavyTopPair(HeavyTopFormulation formulation, HeavyTopMethod method,
                         int kinematics, int constraints)
{
  const double rtol = 1e-10, vmax = 160.0;
  HeavyTopOptions opt;
  HeavyTopResult full, mod;
  char name[128];
  double dx;
  int i;

  heavy_top_default_options(&opt);
  opt.formulation  = formulation;
  opt.method       = method;
  opt.kinematics   = kinematics;
  opt.constraints  = constraints;
  opt.h            = 5e-4;
  opt.rtol         = rtol;
  opt.atol         = rtol;
  opt.single_solve = 1;
  heavy_top_describe(&opt, name, sizeof name);

  opt.newton = LGN_NEWTON_FULL;
  heavy_top_run(&opt, &full);
  opt.newton = LGN_NEWTON_MODIFIED;
  heavy_top_run(&opt, &mod);
  CHECK(full.flag == LGN_SUCCESS && mod.flag == LGN_SUCCESS,
        "%s: both runs succeed (flags %d, %d)", name, full.flag, mod.flag);
  if (full.flag != LGN_SUCCESS || mod.flag != LGN_SUCCESS) return;

  dx = 0.0;
  for (i = 0; i < 3; i++) dx = fmax(dx, fabs(full.x[i] - mod.x[i]));
  printf("%-24s full: %.2f Newton/step, %ld setups; modified: %.2f Newton/step, "
         "%ld setups; |x_full - x_mod| = %.2e\n",
         name, (double)full.nniters / full.nsteps, full.nlsetups,
         (double)mod.nniters / mod.nsteps, mod.nlsetups, dx);
  CHECK(dx <= opt.t_end * rtol * vmax,
        "%s: modified Newton within the Newton tolerance of full Newton "
        "(%.3g > %.3g)", name, dx, opt.t_end * rtol * vmax);
  CHECK(full.nlsetups >= full.nniters,
        "%s: full Newton factorises at every iteration", name);
  CHECK(mod.nlsetups * 4 < full.nlsetups,
        "%s: modified Newton factorises less than a quarter as often "
        "(%ld setups, full Newton %ld)", name, mod.nlsetups, full.nlsetups);
}

/* ---------------------------------------------------------------------------
 * 2. A linear oscillator q'' + k(t) q = 0 on R^1 whose stiffness jumps from
 * 1 to 1e6 at t = 0.5: the matrix factorised before the jump is useless
 * after it.
 * ------------------------------------------------------------------------- */
#define T_JUMP 0.5
static double Stiffness(double t) { return t < T_JUMP ? 1.0 : 1e6; }

static int OscMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = 1.0;
  return 0;
}

static int OscForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)v; (void)ud;
  NV_Ith_S(g, 0) = Stiffness(t) * NV_Ith_S(q, 0);
  return 0;
}

static int OscStiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                        N_Vector lambda, SUNMatrix K, void *ud)
{
  (void)q; (void)v; (void)vdot; (void)lambda; (void)ud;
  SM_ELEMENT_D(K, 0, 0) = Stiffness(t);
  return 0;
}

static int OscDamping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  (void)t; (void)q; (void)v; (void)C; (void)ud;
  return 0;
}

typedef struct {
  SUNContext ctx;
  LGNGroup G;
  N_Vector q, v, tmpl;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
} Oscillator;

static int OscCreate(Oscillator *o, int mode, int maxcor)
{
  int flag = SUNContext_Create(NULL, &o->ctx);
  if (flag != 0) return flag;
  o->G    = LGNGroup_Rn(1);
  o->q    = N_VNew_Serial(1, o->ctx);
  o->v    = N_VNew_Serial(1, o->ctx);
  o->tmpl = N_VNew_Serial(1, o->ctx);
  o->A    = SUNDenseMatrix(1, 1, o->ctx);
  o->LS   = SUNLinSol_Dense(o->tmpl, o->A, o->ctx);
  o->mem  = LGNCreate(o->ctx);
  /* the step's own values (q_n, v_n, vdot_n, lambda_n): not the consistent,
   * projected outputs (LGNSetConsistentOutputs, LGNSetProjectOutputs) */
  LGNSetConsistentOutputs(o->mem, SUNFALSE);
  LGNSetProjectOutputs(o->mem, LGN_PROJECT_NONE);
  NV_Ith_S(o->q, 0) = 1.0;
  NV_Ith_S(o->v, 0) = 0.0;
  flag = LGNSetGroup(o->mem, o->G);
  if (flag == 0) flag = LGNSetMassFn(o->mem, OscMass);
  if (flag == 0) flag = LGNSetForceFn(o->mem, OscForce);
  if (flag == 0) flag = LGNSetStiffnessFn(o->mem, OscStiffness);
  if (flag == 0) flag = LGNSetDampingFn(o->mem, OscDamping);
  if (flag == 0) flag = LGNInit(o->mem, 0.0, o->q, o->v);
  if (flag == 0) flag = LGNSetLinearSolver(o->mem, o->LS, o->A);
  if (flag == 0) flag = LGNSetGenAlpha(o->mem, 0.8);
  if (flag == 0) flag = LGNSetStepSize(o->mem, 1e-2);
  if (flag == 0) flag = LGNSetNewtonMode(o->mem, mode);
  if (flag == 0) flag = LGNSetLSetupFrequency(o->mem, -1); /* no forced setups */
  if (flag == 0) flag = LGNSetMaxNewtonIters(o->mem, maxcor);
  return flag;
}

static void OscFree(Oscillator *o)
{
  LGNFree(&o->mem);
  SUNLinSolFree(o->LS);
  SUNMatDestroy(o->A);
  N_VDestroy(o->tmpl);
  N_VDestroy(o->v);
  N_VDestroy(o->q);
  LGNGroup_Destroy(o->G);
  SUNContext_Free(&o->ctx);
}

static void StiffnessJump(void)
{
  Oscillator full, mod;
  sunrealtype t;
  long int nrestart = -1, nreuse = -1, nsetup0 = 0, nsetup1 = 0, nsetup2 = 0;
  int flag_full, flag_mod;

  /* two iterations per step at most: a linear problem needs one Newton step
   * and one confirming correction, so only a fresh matrix can converge after
   * the jump — the step must be restarted with one */
  CHECK(OscCreate(&full, LGN_NEWTON_FULL, 2) == 0, "oscillator set-up (full)");
  CHECK(OscCreate(&mod, LGN_NEWTON_MODIFIED, 2) == 0, "oscillator set-up (modified)");
  flag_full = LGNSolve(full.mem, 1.0, &t, full.q, full.v, LGN_NORMAL);
  flag_mod  = LGNSolve(mod.mem, 1.0, &t, mod.q, mod.v, LGN_NORMAL);
  CHECK(flag_full == LGN_SUCCESS && flag_mod == LGN_SUCCESS,
        "stiffness jump: both runs succeed (flags %d, %d)", flag_full, flag_mod);
  LGNGetNumNewtonRestarts(mod.mem, &nrestart);
  LGNGetNumMatrixReuses(mod.mem, &nreuse);
  LGNGetNumLinSolvSetups(mod.mem, &nsetup0);
  printf("stiffness jump: %ld restarts, %ld reused-matrix iterations, %ld setups; "
         "q(1) full %.17g, modified %.17g\n", nrestart, nreuse, nsetup0,
         NV_Ith_S(full.q, 0), NV_Ith_S(mod.q, 0));
  CHECK(nrestart >= 1, "the step after the jump is restarted with a fresh matrix");
  CHECK(nreuse > 0, "iterations with a reused matrix are counted");
  CHECK_CLOSE(NV_Ith_S(mod.q, 0), NV_Ith_S(full.q, 0),
              1e-12 * fmax(1.0, fabs(NV_Ith_S(full.q, 0))),
              "q(1): modified = full Newton (linear problem)");

  /* a new step size makes the factorised matrix stale: one setup at the
   * next step, none at the step after */
  CHECK(LGNSetStepSize(mod.mem, 5e-3) == LGN_SUCCESS, "LGNSetStepSize");
  LGNSolve(mod.mem, 1.0, &t, mod.q, mod.v, LGN_ONE_STEP);
  LGNGetNumLinSolvSetups(mod.mem, &nsetup1);
  LGNSolve(mod.mem, 1.0, &t, mod.q, mod.v, LGN_ONE_STEP);
  LGNGetNumLinSolvSetups(mod.mem, &nsetup2);
  CHECK(nsetup1 == nsetup0 + 1 && nsetup2 == nsetup1,
        "after a new step size: one setup, then reuse (setups %ld -> %ld -> %ld)",
        nsetup0, nsetup1, nsetup2);

  CHECK(LGNSetNewtonMode(mod.mem, 2) == LGN_ILL_INPUT, "LGNSetNewtonMode(2) is illegal");
  CHECK(LGNSetNewtonMode(NULL, LGN_NEWTON_FULL) == LGN_MEM_NULL,
        "LGNSetNewtonMode(NULL) is LGN_MEM_NULL");
  OscFree(&full);
  OscFree(&mod);
}

/* ---------------------------------------------------------------------------
 * 3. A 1000-body chain at index 3 (KLU): its multipliers are determined only
 * to roundoff amplified by cond(A) ~ N^2, and their corrections stall above
 * the tolerance while the configuration has converged. Modified Newton must
 * accept that state with the old matrix, as full Newton does with a fresh
 * one, instead of rebuilding the matrix at nearly every step, and once the
 * noise level is known stop at it after two iterations. The two runs
 * agree to the bound of the stop test: per step h (atol + rtol |v|) plus the
 * roundoff floor 100 eps |q| of CorrectionNorm.
 * ------------------------------------------------------------------------- */
static void LongChainStalls(void)
{
#if defined(LGN_HAVE_KLU)
  const int n = 1000, steps = 20;
  RigidRunOptions opt;
  RigidRunResult full, mod;
  SUNContext ctx;
  RigidSystem *sys;
  double dq = 0.0, qmax = 0.0, vmax = 0.0, bound;
  long int i;

  CHECK(SUNContext_Create(NULL, &ctx) == 0, "SUNContext_Create");
  sys = chain_create(n, RB_R3XSO3, ctx);
  CHECK(sys != NULL, "chain_create");
  if (sys == NULL) return;
  rigid_default_run_options(&opt);
  opt.solver    = RB_KLU_CSC;
  opt.t_end     = steps * opt.h;
  opt.outputs   = 1;
  opt.predictor = LGN_PREDICTOR_EXTRAPOLATE;
  opt.newton    = LGN_NEWTON_FULL;
  rigid_run(sys, &opt, &full);
  opt.newton = LGN_NEWTON_MODIFIED;
  rigid_run(sys, &opt, &mod);
  CHECK(full.flag == LGN_SUCCESS && mod.flag == LGN_SUCCESS && full.q != NULL &&
        mod.q != NULL, "chain: both runs succeed (flags %d, %d)", full.flag, mod.flag);
  if (full.q != NULL && mod.q != NULL) {
    for (i = 0; i < 7L * n; i++) {
      dq   = fmax(dq, fabs(full.q[i] - mod.q[i]));
      qmax = fmax(qmax, fabs(full.q[i]));
    }
    for (i = 0; i < 6L * n; i++) vmax = fmax(vmax, fabs(full.v[i]));
    bound = steps * (opt.h * (1e-8 + 1e-8 * vmax) + 100.0 * SUN_UNIT_ROUNDOFF * qmax);
    printf("chain N = %d: full %.2f Newton/step, %ld setups, %ld stalls; "
           "modified %.2f Newton/step, %ld setups, %ld stalls; |q_full - q_mod| = "
           "%.2e (bound %.2e)\n", n, (double)full.nni / full.nsteps, full.nlsetups,
           full.nstall, (double)mod.nni / mod.nsteps, mod.nlsetups, mod.nstall, dq, bound);
    CHECK(full.nstall > 0, "chain: full Newton sees stalled multipliers");
    CHECK(mod.nstall > 0, "chain: modified Newton accepts stalled multipliers");
    CHECK(mod.nlsetups * 4 <= steps,
          "chain: modified Newton keeps its matrix (%ld setups in %d steps)",
          mod.nlsetups, steps);
    /* a stall needs three iterations; at the noise level of the last one,
     * two suffice */
    CHECK(mod.nni < 3 * mod.nsteps,
          "chain: modified Newton stops at the known noise level (%.2f "
          "iterations per step)", (double)mod.nni / mod.nsteps);
    CHECK(dq <= bound, "chain: modified within the Newton tolerance of full "
          "Newton (%.3g > %.3g)", dq, bound);
  }
  rigid_result_free(&full);
  rigid_result_free(&mod);
  rigid_free(&sys);
  SUNContext_Free(&ctx);
#else
  printf("chain stalls: skipped (built without KLU)\n");
#endif
}

/* ---------------------------------------------------------------------------
 * 4. The stall policy (LGNSetAcceptStalls): the 1000-body chain's stalls
 * make most steps, so the default run warns once (LGN_WARNING naming the
 * counts); with stalls refused the same run fails (LGN_CONV_FAILURE)
 * instead of accepting multipliers above the tolerance; and a diverging
 * iteration (a heavy top with a step 50 times too large) is never taken
 * for a stall, with either setting.
 * ------------------------------------------------------------------------- */
#if defined(LGN_HAVE_KLU)
static int nwarn = 0;
static char warn_msg[512];
static void CaptureWarnings(int code, const char *module, const char *fn, const char *msg,
                            void *d)
{
  (void)module; (void)fn; (void)d;
  if (code == LGN_WARNING) {
    nwarn++;
    snprintf(warn_msg, sizeof warn_msg, "%s", msg);
  }
}
#endif

static void StallPolicy(void)
{
#if defined(LGN_HAVE_KLU)
  const int n = 1000, steps = 20;
  RigidRunOptions opt;
  RigidRunResult res;
  SUNContext ctx;
  RigidSystem *sys;
  HeavyTopOptions ho;
  HeavyTopResult hr;
  long int nni_default;
  int k;

  CHECK(SUNContext_Create(NULL, &ctx) == 0, "SUNContext_Create");
  sys = chain_create(n, RB_R3XSO3, ctx);
  rigid_default_run_options(&opt);
  opt.solver    = RB_KLU_CSC;
  opt.t_end     = steps * opt.h;
  opt.outputs   = 1;
  opt.predictor = LGN_PREDICTOR_EXTRAPOLATE;
  opt.ehfun     = CaptureWarnings;
  opt.rtol      = 1e-13; /* below what cond(A) ~ N^2 leaves of the multipliers */
  opt.atol      = 1e-13;
  rigid_run(sys, &opt, &res);
  printf("stall policy: default run %s, %ld stalls in %ld steps, %d warning(s): %s\n",
         LGNGetReturnFlagName(res.flag), res.nstall, res.nsteps, nwarn, warn_msg);
  CHECK(res.flag == LGN_SUCCESS && res.nstall * 2 >= res.nsteps,
        "the chain's steps stall (%ld of %ld)", res.nstall, res.nsteps);
  CHECK(nwarn == 1 && strstr(warn_msg, "LGNSetAcceptStalls") != NULL,
        "one warning naming the setting (%d)", nwarn);
  nni_default = res.nni;
  rigid_result_free(&res);
  /* refused: no step ends on the stall rule; each iterates until its
   * correction is within the tolerance (here the roundoff floors of the
   * norm let it, with more iterations) or fails */
  opt.reject_stalls = 1;
  rigid_run(sys, &opt, &res);
  printf("stall policy: stalls refused: %s after %ld steps, %ld Newton iterations (default %ld)\n",
         LGNGetReturnFlagName(res.flag), res.nsteps, res.nni, nni_default);
  CHECK(res.nstall == 0 && (res.flag == LGN_CONV_FAILURE ||
                            (res.flag == LGN_SUCCESS && res.nni > nni_default)),
        "with stalls refused none is accepted (%s, %ld stalls, %ld iterations)",
        LGNGetReturnFlagName(res.flag), res.nstall, res.nni);
  rigid_result_free(&res);
  rigid_free(&sys);
  SUNContext_Free(&ctx);

  /* divergence is not a stall */
  for (k = 0; k < 2; k++) {
    heavy_top_default_options(&ho);
    ho.h = 0.05; /* h |Omega| = 7.5 */
    ho.t_end = 0.5;
    ho.single_solve = 1;
    ho.newton = k == 0 ? LGN_NEWTON_FULL : LGN_NEWTON_MODIFIED;
    heavy_top_run(&ho, &hr);
    printf("stall policy: heavy top, h = 0.05, %s Newton: %s, %ld stalls\n",
           k == 0 ? "full" : "modified", LGNGetReturnFlagName(hr.flag), hr.nstall);
    CHECK(hr.flag == LGN_CONV_FAILURE && hr.nstall == 0,
          "a diverging iteration fails, never accepted as a stall (%s, %ld stalls)",
          LGNGetReturnFlagName(hr.flag), hr.nstall);
  }
#else
  printf("stall policy: skipped (built without KLU)\n");
#endif
}

int main(void)
{
  HeavyTopPair(HT_LIE, HT_NEWMARK, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3);
  HeavyTopPair(HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3);
  HeavyTopPair(HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2);
  HeavyTopPair(HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED,
               LGN_CONSTR_INDEX3);
  StiffnessJump();
  LongChainStalls();
  StallPolicy();
  return test_summary("test_newton_modes");
}
