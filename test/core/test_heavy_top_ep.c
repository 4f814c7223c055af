/* The heavy top in Euler parameters on R^7 (doc/accuracy-study.md),
 * formulation HT_EULER_PARAMETERS of models/heavy_top.c, with its
 * analytic tangents EPStiffness, EPDamping, EPCurvature:
 *  (a) B, K_t, C_t and Z agree with central differences of the constraint,
 *      residual and force callbacks at random states (heavy_top_check_
 *      jacobians: unit p, x, qdot, qddot, lambda of unit size) to 1e-8
 *      relative; the R^3 x SO(3) and SE(3) callbacks are checked the same way;
 *  (b) the consistent start (which uses Z) equals the R^3 x SO(3) one to 1e-9;
 *  (c) Newmark and generalized-alpha, index 3 and index 2: analytic and
 *      difference-quotient tangents give the same solution at t = 0.1 s
 *      (1e-9 in x with Newton rtol = atol = 1e-11, as test_heavy_top_se3),
 *      and the analytic runs use no residual difference quotients. */
#include <lignum/lignum.h>

#include "models/heavy_top.h"
#include "test_util.h"

#define NSEEDS 5

/* measured (seeds 1-5, eps = cbrt(DBL_EPSILON)): B, C_t, Z <= 3e-10 and
 * K_t <= 4e-9 for all three formulations. The K_t differences are roundoff:
 * the Euler-parameter residual is quadratic in q, so its central differences
 * have no truncation error, but the residual carries the weight m g = 147 N,
 * and ulp(147) / (2 eps) = 2.4e-9. Changing one term of EPStiffness,
 * EPDamping or EPCurvature by a factor 1.001 fails this test (tried on five
 * terms). */
#define TANGENT_TOL 1e-8

static void TangentsVsDifferences(HeavyTopFormulation f, const char *name)
{
  HeavyTopJacobianErrors e;
  unsigned int seed;
  for (seed = 1; seed <= NSEEDS; seed++) {
    CHECK(heavy_top_check_jacobians(f, seed, &e) == 0, "%s check %u ran", name, seed);
    printf("%-6s seed %u: rel. diff  B %.1e  K_t %.1e  C_t %.1e  Z %.1e\n", name, seed,
           e.B, e.K, e.C, e.Z);
    CHECK(e.B <= TANGENT_TOL, "%s seed %u: B rel. diff %.3e <= %g", name, seed, e.B,
          TANGENT_TOL);
    CHECK(e.K <= TANGENT_TOL, "%s seed %u: K_t rel. diff %.3e <= %g", name, seed, e.K,
          TANGENT_TOL);
    CHECK(e.C <= TANGENT_TOL, "%s seed %u: C_t rel. diff %.3e <= %g", name, seed, e.C,
          TANGENT_TOL);
    CHECK(e.Z <= TANGENT_TOL, "%s seed %u: Z rel. diff %.3e <= %g", name, seed, e.Z,
          TANGENT_TOL);
  }
}

static void ConsistentStart(void)
{
  HeavyTopOptions opt;
  HeavyTopResult lie, ep;
  char what[64];
  int k;

  heavy_top_default_options(&opt);
  opt.t_end = 0.0;
  CHECK(heavy_top_run(&opt, &lie) == LGN_SUCCESS, "R^3xSO(3) start computed");
  opt.formulation = HT_EULER_PARAMETERS;
  CHECK(heavy_top_run(&opt, &ep) == LGN_SUCCESS, "EP start computed");
  CHECK(ep.ndq == 0, "EP start without difference quotients (%ld)", ep.ndq);
  for (k = 0; k < 6; k++) {
    snprintf(what, sizeof what, "EP vs LIE vdot0[%d]", k);
    CHECK_CLOSE(ep.vdot[k], lie.vdot[k], 1e-9, what);
  }
  for (k = 0; k < 3; k++) {
    snprintf(what, sizeof what, "EP vs LIE lambda0[%d]", k);
    CHECK_CLOSE(ep.lambda[k], lie.lambda[k], 1e-9, what);
  }
}

static void AnalyticVsDQ(HeavyTopMethod method, int constraints)
{
  HeavyTopOptions opt;
  HeavyTopResult an, dq;
  double dx = 0.0, dl = 0.0;
  char name[64];
  int k;

  heavy_top_default_options(&opt);
  opt.formulation = HT_EULER_PARAMETERS;
  opt.method = method;
  opt.constraints = constraints;
  opt.t_end = 0.1;
  opt.rtol = opt.atol = 1e-11;
  heavy_top_describe(&opt, name, sizeof name);
  CHECK(heavy_top_run(&opt, &an) == LGN_SUCCESS, "%s analytic run", name);
  opt.analytic_jacobians = 0;
  CHECK(heavy_top_run(&opt, &dq) == LGN_SUCCESS, "%s DQ run", name);
  for (k = 0; k < 3; k++) {
    dx = fmax(dx, fabs(an.x[k] - dq.x[k]));
    dl = fmax(dl, fabs(an.lambda[k] - dq.lambda[k]));
  }
  printf("%s analytic vs DQ, t = 0.1 s: |dx| = %.2e  |dlambda| = %.2e  "
         "newton/step %.2f vs %.2f  DQ evals %ld vs %ld\n",
         name, dx, dl, (double)an.nniters / (double)an.nsteps,
         (double)dq.nniters / (double)dq.nsteps, an.ndq, dq.ndq);
  CHECK(dx <= 1e-9, "%s analytic vs DQ: |dx| = %.3e <= 1e-9", name, dx);
  /* index 3 needs no difference quotients at all; index 2 keeps only
   * Lignum's D_q(B v) row (constraint Jacobians, not residuals) */
  if (constraints == LGN_CONSTR_INDEX3)
    CHECK(an.ndq == 0, "%s analytic: no DQ evaluations (%ld)", name, an.ndq);
  else
    CHECK(an.ndq < dq.ndq, "%s analytic: fewer DQ evaluations (%ld < %ld)", name, an.ndq,
          dq.ndq);
}

int main(void)
{
  /* (a) */
  TangentsVsDifferences(HT_EULER_PARAMETERS, "EP");
  TangentsVsDifferences(HT_LIE, "LIE");
  TangentsVsDifferences(HT_SE3, "SE3");

  /* (b) */
  ConsistentStart();

  /* (c) */
  AnalyticVsDQ(HT_GENALPHA, LGN_CONSTR_INDEX3);
  AnalyticVsDQ(HT_GENALPHA, LGN_CONSTR_INDEX2);
  AnalyticVsDQ(HT_NEWMARK, LGN_CONSTR_INDEX3);
  AnalyticVsDQ(HT_NEWMARK, LGN_CONSTR_INDEX2);

  return test_summary("test_heavy_top_ep");
}
