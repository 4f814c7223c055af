/* -----------------------------------------------------------------------------
 * Lignum study tool: the N-body spherical pendulum chain (models/chain.h).
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 *   chain --n N [--solver dense|klu|klu-csr] [method options] [--compare]
 *         [--adaptive [--rtol R] [--atol A] [--hmax H]]
 *
 * Integrates the chain on the product (R^3 x SO(3))^N (or SE(3)^N) and reports
 * the energy drift max |E(t) - E(0)|, the largest constraint violation, the
 * work counters and the position of the free end. With --compare it also
 * solves the same problem with the other linear solvers (dense only for
 * N <= 200), with difference-quotient tangents and with the plain residual
 * (--residual plain) and, with KLU, with the other of Lignum's and KLU's
 * solves (--klu-solve), and fails unless the dense and sparse solutions
 * agree to round-off (1e-10) with the same number of Newton iterations, the
 * DQ solution agrees to the Newton tolerance, the plain residual's to
 * round-off and the other solves' to round-off with the same iterations.
 * The exit status is 0 only if every run succeeded and its constraint
 * violation is at round-off level.
 * With --adaptive the steps are error-controlled (LGN_STEP_ADAPTIVE: --rtol,
 * --atol the error test's tolerances, default 1e-6; --h the first step
 * tried); the energy samples are interpolated (LGN_NORMAL), t_end is landed
 * on exactly, and the report adds the rejected steps.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/chain.h"

static void Usage(const char *prog)
{
  fprintf(stderr, "usage: %s [--n N] [--compare]\n", prog);
  rigid_print_usage(stderr);
}

static void Report(const RigidSystem *sys, const RigidRunOptions *opt,
                   const RigidRunResult *r)
{
  const double *q = r->q + 7 * (sys->n - 1);
  double R[9], tip[3];
  int i;
  LGNQuaternionToRotation(q + 3, R);
  for (i = 0; i < 3; i++) tip[i] = q[i] - 0.5 * R[3 * i + 2]; /* x - (L/2) R e3 */
  printf("%-8s %-9s t = %.3f  steps %ld  Newton/step %.2f  DQ evals %ld  "
         "analyses %ld  nnz %ld  cpu %.3f s (%.3g ms/step)%s%s\n",
         rigid_solver_name(opt->solver), opt->analytic ? "analytic" : "dq", r->t,
         r->nsteps, r->nsteps > 0 ? (double)r->nni / r->nsteps : 0.0, r->ndq,
         r->nanalyses, r->nnz, r->cpu_seconds,
         r->nsteps > 0 ? 1e3 * r->cpu_seconds / r->nsteps : 0.0,
         opt->plain_residual ? "  plain residual" : "",
         opt->solver != RB_DENSE && opt->klu_solve_sundials ? "  KLU's solves" : "");
  printf("         energy E0 = %.10g  E(t_end) = %.10g  max |E - E0| = %.3e "
         "(relative to the potential scale N^2 m g L/2: %.3e)\n",
         r->energy0, r->energy, r->max_drift,
         r->max_drift / (0.5 * 9.81 * sys->n * sys->n));
  printf("         max |Phi| = %.3e%s  |Phi(t_end)| = %.3e  work space %ld reals + "
         "%ld integers (%.0f bytes/body)\n",
         r->max_phi, opt->adaptive ? " (interpolated samples)" : "", r->phi_end,
         r->lenrw, r->leniw,
         (8.0 * r->lenrw + 8.0 * r->leniw) / sys->n);
  printf("         free end %.17g %.17g %.17g\n", tip[0], tip[1], tip[2]);
  printf("         matrix setups %ld  reused-matrix iterations %ld  Newton stalls %ld\n",
         r->nlsetups, r->nreuse, r->nstall);
  if (opt->adaptive)
    printf("         error control: steps %ld  error-test failures %ld  "
           "Newton failures %ld  mean h %.3e\n",
           r->nsteps, r->netf, r->nncf, r->nsteps > 0 ? r->t / r->nsteps : 0.0);
}

static double MaxDiff(const double *a, const double *b, long int n)
{
  double d = 0;
  long int i;
  for (i = 0; i < n; i++) d = fmax(d, fabs(a[i] - b[i]));
  return d;
}

/* Run the chain with opt and compare with the reference run ref (labelled
 * `label`): the run must succeed, its configuration agree to tol and, with
 * same_newton, its Newton iteration count be ref's. Returns 1 on failure. */
static int CompareRun(RigidSystem *sys, const RigidRunOptions *opt,
                      const RigidRunResult *ref, const char *label, double tol,
                      int same_newton)
{
  RigidRunResult other;
  const int flag = rigid_run(sys, opt, &other);
  double d;
  int fail;
  Report(sys, opt, &other);
  d    = MaxDiff(ref->q, other.q, 7L * sys->n);
  fail = flag != LGN_SUCCESS || !(d < tol) || (same_newton && other.nni != ref->nni);
  printf("         |q - q(%s)|_max = %.3e (must be < %.0e)", label, d, tol);
  if (same_newton)
    printf(", Newton iterations %ld (must be %ld)", other.nni, ref->nni);
  printf("\n");
  rigid_result_free(&other);
  return fail;
}

int main(int argc, char **argv)
{
  RigidRunOptions opt;
  RigidFormulation formulation = RB_R3XSO3;
  RigidRunResult res;
  RigidSystem *sys;
  SUNContext ctx;
  int n = 10, compare = 0, i, flag, status = 0, s;

  rigid_default_run_options(&opt);
  opt.t_end = 1.0;
  for (i = 1; i < argc; i++) {
    int r = rigid_parse_option(argc, argv, &i, &opt, &formulation);
    if (r == 1) continue;
    if (r == 0 && strcmp(argv[i], "--n") == 0 && i + 1 < argc && atoi(argv[i + 1]) >= 1) {
      n = atoi(argv[++i]);
      continue;
    }
    if (r == 0 && strcmp(argv[i], "--compare") == 0) {
      compare = 1;
      continue;
    }
    if (r == 0 && strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
      opt.csv = fopen(argv[++i], "w");
      if (opt.csv != NULL) continue;
    }
    fprintf(stderr, "chain: bad option or value: %s\n", argv[i]);
    Usage(argv[0]);
    return 2;
  }
  if (opt.solver == RB_DENSE && n > 2000) {
    fprintf(stderr, "chain: a dense %d-body chain needs too much memory; use --solver klu\n", n);
    return 2;
  }
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  sys = chain_create(n, formulation, ctx);
  if (sys == NULL) return 1;

  if (opt.bdf_maxord > 0)
    printf("chain of %d rods on %s, BDF of orders 1 ... %d, index %d, %s = %g, t in [0, %g]\n",
           n, formulation == RB_SE3 ? "SE(3)^N" : "(R^3 x SO(3))^N", opt.bdf_maxord,
           opt.constraints == LGN_CONSTR_INDEX3 ? 3 : 2,
           opt.adaptive ? "error control, h0" : "h", opt.h, opt.t_end);
  else
    printf("chain of %d rods on %s, %s, %s kinematics, index %d, %s = %g, t in [0, %g]\n",
           n, formulation == RB_SE3 ? "SE(3)^N" : "(R^3 x SO(3))^N",
           opt.method == 1 ? "generalized-alpha" : "Newmark",
           opt.kinematics == LGN_KINEMATICS_EXACT ? "exact" : "simplified",
           opt.constraints == LGN_CONSTR_INDEX3 ? 3 : 2,
           opt.adaptive ? "error control, h0" : "h", opt.h, opt.t_end);
  if (opt.adaptive)
    printf("error control: rtol = %g, atol = %g\n", opt.rtol > 0 ? opt.rtol : 1e-6,
           opt.atol > 0 ? opt.atol : 1e-6);
  flag = rigid_run(sys, &opt, &res);
  if (opt.csv != NULL) fclose(opt.csv);
  opt.csv = NULL;
  Report(sys, &opt, &res);
  /* index 2 lets Phi drift (only B v = 0 is enforced); with error control
   * the samples are interpolated (Phi = O(interpolation error) there), the
   * state at t_end (a stop time) is the integrator's own */
  if (flag != LGN_SUCCESS ||
      (opt.adaptive ? res.phi_end : res.max_phi) >
          (opt.constraints == LGN_CONSTR_INDEX3 ? 1e-9 * n : 1e-4)) {
    printf("FAILED: flag %s, max |Phi| = %.3e, |Phi(t_end)| = %.3e\n",
           LGNGetReturnFlagName(flag), res.max_phi, res.phi_end);
    status = 1;
  }

  if (compare && status == 0) {
    const RigidSolver solvers[3] = {RB_DENSE, RB_KLU_CSC, RB_KLU_CSR};
    const RigidSolver mine = opt.solver;
    char label[64];
    /* the same iteration matrix gives the same iterates to round-off, at
     * index 2 too: D_q(B v) is a difference quotient by columns (dense) or
     * by column colours (sparse), with the same increments, and a colour's
     * columns touch disjoint rows. The same matrices, so the same
     * iterations too: a term missing from one matrix costs iterations
     * before it shows in q. */
    const double same_tol = 1e-10;
    for (s = 0; s < 3; s++) {
      if (solvers[s] == mine || (solvers[s] == RB_DENSE && n > 200) ||
          !rigid_solver_available(solvers[s]))
        continue;
      opt.solver = solvers[s];
      status |= CompareRun(sys, &opt, &res, rigid_solver_name(mine), same_tol, 1);
    }
    opt.solver = mine;

    /* difference-quotient tangents: the same solution to the Newton tolerance */
    opt.analytic = !opt.analytic;
    snprintf(label, sizeof label, "%s; Newton tolerance",
             opt.analytic ? "dq" : "analytic");
    status |= CompareRun(sys, &opt, &res, label, 1e-5, 0);
    opt.analytic = !opt.analytic;

    /* the residual shortcuts (constant M, B^T lambda without B) change
     * only the rounding of the residual */
    opt.plain_residual = !opt.plain_residual;
    status |= CompareRun(sys, &opt, &res,
                         opt.plain_residual ? "shortcut residual" : "plain residual",
                         same_tol, 0);
    opt.plain_residual = !opt.plain_residual;

    /* Lignum's solves on a copy of KLU's factors: by columns (CSR) KLU's
     * operations in KLU's order, the same iterates (to the last bit
     * without FMA); by rows (CSC) Lignum refactors and keeps U's rows
     * divided by the diagonal, the same iterates to round-off */
    if (opt.solver != RB_DENSE) {
      opt.klu_solve_sundials = !opt.klu_solve_sundials;
      status |= CompareRun(sys, &opt, &res,
                           opt.klu_solve_sundials ? "Lignum's solves" : "KLU's solves",
                           same_tol, 1);
      opt.klu_solve_sundials = !opt.klu_solve_sundials;
    }
  }
  printf("%s\n", status == 0 ? "PASSED" : "FAILED");
  rigid_result_free(&res);
  rigid_free(&sys);
  SUNContext_Free(&ctx);
  return status;
}
