/* -----------------------------------------------------------------------------
 * Lignum test: error control at index 3 with an undamped method of the
 * Newmark family (Newmark beta = 1/4, gamma = 1/2; generalized-alpha with
 * rho_inf = 1) fails at once with a message naming the cause and the
 * remedies, instead of collapsing its step with every step accepted.
 *
 * Before, the heavy top (mod. LGNM, index 3, rtol = atol = 1e-3 ... 1e-5)
 * took 10^6 accepted steps with h falling to 4e-8 and stopped at mxstep at
 * t = 0.39 / 0.29 / 0.23 (6-7 s each); the pendulum at tol 1e-7 the same.
 * The constraint mode of these methods is undamped at index 3 (with beta =
 * 1/4 a Jordan block at -1: the multipliers' step-to-step oscillation grows
 * by 4 V / h^2 per unit time from a velocity error V across the
 * constraints), and the error estimate follows it (lgn_newmark_adapt.c).
 *
 *  (a) the heavy top: mod. LGNM and LGNM (exact and simplified kinematics)
 *      and generalized-alpha with rho_inf = 1, index 3, error control:
 *      LGN_ILL_INPUT before any step (t = 0, no step); capped at 20,000
 *      steps, so that the old behaviour fails here in a fraction of a second
 *      (LGN_TOO_MUCH_WORK at t = 0.92 for mod. LGNM at tol 1e-3);
 *  (b) a pendulum (the chain of one body) at tol 1e-7: the same flag, and
 *      the message names the cause (rho_inf = 1) and the remedies (rho_inf
 *      < 1, LGN_CONSTR_INDEX2, LGN_CONSTR_GGL);
 *  (c) the remedies it names reach t = 1 on the heavy top with an error that
 *      follows the tolerance (ARKODE reference): generalized-alpha rho_inf =
 *      0.9 at index 3, undamped Newmark at index 2 and under GGL: at tol
 *      1e-6 the error is below 1e-4 and 10 times below that at tol 1e-4;
 *  (d) fixed steps of undamped index-3 Newmark are not refused (mod. LGNM,
 *      h = 1e-3, t = 1: error 1.3e-3 in bench/work_precision).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_ls.h>

#include "lgn_reference.h"
#include "models/chain.h"
#include "models/heavy_top.h"
#include "models/rigid_bodies.h"
#include "test_util.h"

#define CAP 20000L         /* steps of a refused run: the old collapse fails fast */
#define CAP_REMEDY 100000L /* steps of a remedy (index 2 at tol 1e-6: 21,840) */

static LGNRefHeavyTop ref; /* the heavy top at t = 1 */

static double ComErr(const double x[3])
{
  const double d0 = x[0] - ref.x[0], d1 = x[1] - ref.x[1], d2 = x[2] - ref.x[2];
  return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

/* The heavy top on R^3 x SO(3) over [0, 1], error control at rtol = atol =
 * tol: Newmark (1/4, 1/2) when rho_inf < 0, else generalized-alpha. */
static int HeavyTop(double rho_inf, int kinematics, int constraints, double tol,
                    long int cap, HeavyTopResult *res)
{
  HeavyTopOptions opt;
  heavy_top_default_options(&opt);
  opt.formulation = HT_LIE;
  opt.method = rho_inf < 0.0 ? HT_NEWMARK : HT_GENALPHA;
  opt.rho_inf = rho_inf < 0.0 ? 0.9 : rho_inf;
  opt.beta = 0.25;
  opt.gamma = 0.5;
  opt.kinematics = kinematics;
  opt.constraints = constraints;
  opt.adaptive = 1;
  opt.rtol = opt.atol = tol;
  opt.h = 1.0;
  opt.t_end = 1.0;
  opt.analytic_jacobians = 1;
  opt.single_solve = 1;
  opt.max_steps = cap;
  opt.make_ls = LGNLinSol_Dense;
  return heavy_top_run(&opt, res);
}

static char last_msg[1024];

static void KeepMessage(int code, const char *module, const char *function, const char *msg,
                        void *data)
{
  (void)code;
  (void)module;
  (void)function;
  (void)data;
  snprintf(last_msg, sizeof last_msg, "%s", msg);
}

static void Refused(void)
{
  static const struct {
    const char *name;
    double rho_inf;
    int kinematics;
  } cases[] = {
      {"mod. LGNM (exact kinematics)", -1.0, LGN_KINEMATICS_EXACT},
      {"LGNM (simplified kinematics)", -1.0, LGN_KINEMATICS_SIMPLIFIED},
      {"generalized-alpha rho_inf = 1", 1.0, LGN_KINEMATICS_EXACT},
  };
  const double tols[2] = {1e-3, 1e-5};
  size_t k;
  int j;
  for (k = 0; k < sizeof cases / sizeof cases[0]; k++)
    for (j = 0; j < 2; j++) {
      HeavyTopResult res;
      const int flag = HeavyTop(cases[k].rho_inf, cases[k].kinematics, LGN_CONSTR_INDEX3,
                                tols[j], CAP, &res);
      printf("(a) heavy top, %s, index 3, tol %.0e: flag %d, t = %g, %ld steps\n",
             cases[k].name, tols[j], flag, res.t, res.nsteps);
      CHECK(flag == LGN_ILL_INPUT, "(a) %s tol %.0e: flag %d, expected LGN_ILL_INPUT (%d)",
            cases[k].name, tols[j], flag, LGN_ILL_INPUT);
      CHECK(res.t == 0.0 && res.nsteps == 0, "(a) %s tol %.0e: no step (t = %g, %ld steps)",
            cases[k].name, tols[j], res.t, res.nsteps);
    }
}

static void PendulumMessage(void)
{
  SUNContext ctx = NULL;
  RigidSystem *sys;
  RigidRunOptions opt;
  RigidRunResult res;
  memset(&res, 0, sizeof res);
  CHECK(SUNContext_Create(NULL, &ctx) == 0, "(b) SUNContext_Create");
  sys = chain_create(1, RB_R3XSO3, ctx);
  CHECK(sys != NULL, "(b) chain_create(1)");
  if (sys == NULL) {
    SUNContext_Free(&ctx);
    return;
  }
  rigid_default_run_options(&opt);
  opt.solver = RB_DENSE;
  opt.method = 0; /* Newmark 1/4, 1/2 */
  opt.beta = 0.25;
  opt.gamma = 0.5;
  opt.kinematics = LGN_KINEMATICS_EXACT;
  opt.constraints = LGN_CONSTR_INDEX3;
  opt.analytic = 1;
  opt.adaptive = 1;
  opt.rtol = opt.atol = 1e-7;
  opt.h = 1e-4;
  opt.t_end = 1.0;
  opt.outputs = 1;
  opt.max_steps = CAP;
  opt.ehfun = KeepMessage;
  last_msg[0] = '\0';
  rigid_run(sys, &opt, &res);
  printf("(b) pendulum, Newmark, index 3, tol 1e-7: flag %d, t = %g, %ld steps\n    %s\n",
         res.flag, res.t, res.nsteps, last_msg);
  CHECK(res.flag == LGN_ILL_INPUT, "(b) flag %d, expected LGN_ILL_INPUT", res.flag);
  CHECK(res.nsteps == 0, "(b) %ld steps, expected none", res.nsteps);
  CHECK(strstr(last_msg, "undamped") != NULL && strstr(last_msg, "rho_inf = 1") != NULL,
        "(b) the message names the cause: \"%s\"", last_msg);
  CHECK(strstr(last_msg, "rho_inf < 1") != NULL && strstr(last_msg, "LGN_CONSTR_INDEX2") != NULL &&
            strstr(last_msg, "LGN_CONSTR_GGL") != NULL,
        "(b) the message names the remedies: \"%s\"", last_msg);
  rigid_result_free(&res);
  rigid_free(&sys);
  SUNContext_Free(&ctx);
}

static void Remedies(void)
{
  static const struct {
    const char *name;
    double rho_inf;
    int constraints;
  } cases[] = {
      {"generalized-alpha rho_inf = 0.9, index 3", 0.9, LGN_CONSTR_INDEX3},
      {"Newmark, index 2", -1.0, LGN_CONSTR_INDEX2},
      {"Newmark, GGL", -1.0, LGN_CONSTR_GGL},
  };
  size_t k;
  for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    HeavyTopResult r4, r6;
    const int f4 = HeavyTop(cases[k].rho_inf, LGN_KINEMATICS_EXACT, cases[k].constraints,
                            1e-4, CAP_REMEDY, &r4);
    const int f6 = HeavyTop(cases[k].rho_inf, LGN_KINEMATICS_EXACT, cases[k].constraints,
                            1e-6, CAP_REMEDY, &r6);
    const double e4 = ComErr(r4.x), e6 = ComErr(r6.x);
    printf("(c) heavy top, %s: tol 1e-4: err %.3e (%ld steps), tol 1e-6: err %.3e (%ld steps)\n",
           cases[k].name, e4, r4.nsteps, e6, r6.nsteps);
    CHECK(f4 == LGN_SUCCESS && r4.t == 1.0, "(c) %s tol 1e-4: flag %d at t = %g", cases[k].name,
          f4, r4.t);
    CHECK(f6 == LGN_SUCCESS && r6.t == 1.0, "(c) %s tol 1e-6: flag %d at t = %g", cases[k].name,
          f6, r6.t);
    CHECK(e6 < 1e-4 && e6 < 0.1 * e4, "(c) %s: err %.3e at 1e-6 < 1e-4 and < err(1e-4) / 10 = %.3e",
          cases[k].name, e6, 0.1 * e4);
  }
}

static void FixedSteps(void)
{
  HeavyTopOptions opt;
  HeavyTopResult res;
  int flag;
  heavy_top_default_options(&opt);
  opt.formulation = HT_LIE;
  opt.method = HT_NEWMARK;
  opt.beta = 0.25;
  opt.gamma = 0.5;
  opt.kinematics = LGN_KINEMATICS_EXACT;
  opt.constraints = LGN_CONSTR_INDEX3;
  opt.h = 1e-3;
  opt.t_end = 1.0;
  opt.analytic_jacobians = 1;
  opt.single_solve = 1;
  opt.make_ls = LGNLinSol_Dense;
  flag = heavy_top_run(&opt, &res);
  printf("(d) heavy top, mod. LGNM, index 3, fixed h = 1e-3: flag %d, t = %g, err %.3e\n", flag,
         res.t, ComErr(res.x));
  CHECK(flag == LGN_SUCCESS && fabs(res.t - 1.0) < 1e-12, "(d) flag %d at t = %g", flag, res.t);
  CHECK(ComErr(res.x) < 1e-2, "(d) err %.3e < 1e-2", ComErr(res.x));
}

int main(void)
{
  const double t1 = 1.0;
  if (lgnref_heavy_top(&t1, 1, &ref, LGNREF_FEHLBERG_8) != 0) {
    printf("FAIL: the heavy top's reference solution\n");
    return 1;
  }
  Refused();
  PendulumMessage();
  Remedies();
  FixedSteps();
  return test_summary("test_undamped_index3");
}
