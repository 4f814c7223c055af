/* -----------------------------------------------------------------------------
 * Lignum study tool: a whipping chain, where error control pays.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 *   whipping_chain [--n N] [--taper F] [--t-end T] [--rtol R] [--atol A]
 *                  [--solver ...] [--csv FILE] [--png FILE] [--no-png]
 *                  [--check]
 *
 * N rods (total length 1 m, total mass 1 kg, spherical joints; the
 * rigid_bodies model), each F (default 0.8) times as heavy as the one before
 * it, as a whip tapers, hang from a fixed point at one end and start at
 * rest, straight and horizontal. The chain falls and swings down; as it straightens below the
 * support the free end whips through at a speed many times that of the rest
 * of the chain, and the time scale of the motion drops by an order of
 * magnitude for a short while. A fixed step must be small enough for that
 * moment everywhere; error control takes large steps before and after it.
 *
 * The tool
 *   1. integrates with error control (LGN_STEP_ADAPTIVE, rtol = atol = R,
 *      default 1e-5) step by step (LGN_ONE_STEP to the stop time t_end) and
 *      prints the step size history (t, h) (every step into --csv, a sample
 *      on stdout) and a PNG of h(t) with gnuplot;
 *   2. computes a reference with error control at R / 1000 (tolerance
 *      proportionality: the global error follows about R^(2/3));
 *   3. reports the error at t_end (max over the bodies of the distance of
 *      the centres of mass to the reference's), the steps, the rejected
 *      steps and the CPU time;
 *   4. searches the fixed step that reaches the same error (doubling the
 *      number of steps, then bisecting it) and reports its steps and CPU
 *      time.
 * With --check the exit status is 1 unless every run succeeds and the
 * adaptive run needs fewer steps than the fixed-step run of the same error.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_gnuplot.h"
#include "models/rigid_bodies.h"

/* The chain of n rods of length 1/n along +x from the origin, at rest. */
static RigidSystem *WhippingChainCreate(int n, double taper, RigidFormulation formulation,
                                        SUNContext ctx)
{
  const double L = 1.0 / n, radius = 0.01;
  double mass, total = 0.0;
  const double top[3] = {0.0, 0.0, 0.5 * L}, bottom[3] = {0.0, 0.0, -0.5 * L};
  const double origin[3] = {0.0, 0.0, 0.0};
  /* body frame: e3 = -x (from the bottom end to the top end), e1 = y,
   * e2 = e3 x e1 = -z; columns of R are e1, e2, e3 (row-major storage) */
  const double R[9] = {0.0, 0.0, -1.0, 1.0, 0.0, 0.0, 0.0, -1.0, 0.0};
  RigidSystem *sys = rigid_create(n, formulation, ctx);
  int k;
  if (sys == NULL) return NULL;
  for (k = 0; k < n; k++) total += pow(taper, k);
  for (k = 0; k < n; k++) {
    const double x[3] = {(k + 0.5) * L, 0.0, 0.0};
    mass = pow(taper, k) / total;
    rigid_set_cylinder(sys, k, L, mass, radius * sqrt(mass * n));
    rigid_place(sys, k, x, R);
    if (k == 0) LGNJoints_AddSpherical(sys->joints, LGN_GROUND, origin, 0, top);
    else LGNJoints_AddSpherical(sys->joints, k - 1, bottom, k, top);
  }
  return sys;
}

/* max_k |x_k - x_ref_k| over the centres of mass (the first 3 of every 7). */
static double PositionError(const RigidSystem *sys, const double *q, const double *qref)
{
  double e = 0.0;
  int k, i;
  for (k = 0; k < sys->n; k++)
    for (i = 0; i < 3; i++) e = fmax(e, fabs(q[7 * k + i] - qref[7 * k + i]));
  return e;
}

/* One fixed-step run with nsteps steps: its error (inf on failure). */
static double FixedRun(RigidSystem *sys, const RigidRunOptions *base, long int nsteps,
                       const double *qref, double *cpu)
{
  RigidRunOptions opt = *base;
  RigidRunResult r;
  double err;
  int flag;
  opt.adaptive = 0;
  opt.step_log = NULL;
  opt.csv      = NULL;
  opt.outputs  = 1;
  opt.h        = opt.t_end / (double)nsteps;
  opt.rtol = opt.atol = 0.0; /* Newton's defaults (1e-8) */
  flag = rigid_run(sys, &opt, &r);
  err  = (flag == LGN_SUCCESS && r.q != NULL) ? PositionError(sys, r.q, qref) : HUGE_VAL;
  *cpu = r.cpu_seconds;
  printf("  fixed   N = %7ld  h = %.3e  error %.3e  cpu %.4f s%s\n", nsteps, opt.h, err,
         r.cpu_seconds, flag == LGN_SUCCESS ? "" : "  (failed)");
  rigid_result_free(&r);
  return err;
}

static void Usage(const char *prog)
{
  fprintf(stderr,
          "usage: %s [--n N] [--taper F] [--t-end T] [--rtol R] [--atol A] [--csv FILE]\n"
          "          [--png FILE] [--no-png] [--check]\n"
          "          [--solver dense|klu|klu-csr] [method options]\n", prog);
  rigid_print_usage(stderr);
}

int main(int argc, char **argv)
{
  RigidRunOptions opt, ref;
  RigidFormulation formulation = RB_R3XSO3;
  RigidRunResult res, rres;
  RigidSystem *sys;
  SUNContext ctx;
  const char *csv_path = "whipping_chain.csv", *png_path = "whipping_chain.png";
  FILE *log;
  double taper = 0.8;
  int n = 10, check = 0, png = 1, i, flag, rflag, status = 0;
  double tol, err, err_fixed, cpu_fixed = 0.0, cpu;
  long int lo, hi, mid;

  rigid_default_run_options(&opt);
  opt.adaptive = 1;
  opt.t_end    = 1.0;
  opt.rtol     = 1e-5;
  opt.h        = 1e-3; /* the first step tried */
  opt.outputs  = 1;
  for (i = 1; i < argc; i++) {
    int r = rigid_parse_option(argc, argv, &i, &opt, &formulation);
    if (r == 1) continue;
    if (r == 0 && !strcmp(argv[i], "--n") && i + 1 < argc && atoi(argv[i + 1]) >= 2) {
      n = atoi(argv[++i]);
      continue;
    }
    if (r == 0 && !strcmp(argv[i], "--taper") && i + 1 < argc && atof(argv[i + 1]) > 0) {
      taper = atof(argv[++i]);
      continue;
    }
    if (r == 0 && !strcmp(argv[i], "--csv") && i + 1 < argc) {
      csv_path = argv[++i];
      continue;
    }
    if (r == 0 && !strcmp(argv[i], "--png") && i + 1 < argc) {
      png_path = argv[++i];
      continue;
    }
    if (r == 0 && !strcmp(argv[i], "--no-png")) {
      png = 0;
      continue;
    }
    if (r == 0 && !strcmp(argv[i], "--check")) {
      check = 1;
      continue;
    }
    fprintf(stderr, "whipping_chain: bad option or value: %s\n", argv[i]);
    Usage(argv[0]);
    return 2;
  }
  opt.adaptive = 1; /* whatever the options said */
  if (!(opt.atol > 0.0)) opt.atol = opt.rtol;
  tol = opt.rtol;

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  sys = WhippingChainCreate(n, taper, formulation, ctx);
  if (sys == NULL) return 1;
  printf("whipping chain: %d rods (mass ratio %g), total length 1 m, released "
         "horizontal at rest, t in [0, %g], %s\n", n, taper, opt.t_end,
         rigid_solver_name(opt.solver));

  /* 1. error control, every step logged */
  log = fopen(csv_path, "w");
  if (log == NULL) {
    perror(csv_path);
    return 1;
  }
  opt.step_log = log;
  flag         = rigid_run(sys, &opt, &res);
  fclose(log);
  opt.step_log = NULL;

  /* 2. the reference: error control at tol / 1000 */
  ref      = opt;
  ref.rtol = tol * 1e-3;
  ref.atol = opt.atol * 1e-3;
  ref.h    = 1e-5;
  rflag    = rigid_run(sys, &ref, &rres);
  if (flag != LGN_SUCCESS || rflag != LGN_SUCCESS || res.q == NULL || rres.q == NULL) {
    printf("FAILED: adaptive run %s, reference %s\n", LGNGetReturnFlagName(flag),
           LGNGetReturnFlagName(rflag));
    return 1;
  }
  err = PositionError(sys, res.q, rres.q);

  /* the step size history: a sample on stdout */
  {
    FILE *in = fopen(csv_path, "r");
    char line[128];
    long int k = 0, every = res.nsteps / 25 + 1;
    double t, h, hmin = HUGE_VAL, hmax = 0.0, tmin = 0.0;
    printf("\nstep size history (every %ld-th step; all in %s):\n       t          h\n",
           every, csv_path);
    while (in != NULL && fgets(line, sizeof line, in) != NULL) {
      if (sscanf(line, "%lf,%lf", &t, &h) != 2) continue;
      if (h < hmin) {
        hmin = h;
        tmin = t;
      }
      hmax = fmax(hmax, h);
      if (k++ % every == 0) printf("  %8.5f  %.3e\n", t, h);
    }
    if (in != NULL) fclose(in);
    printf("  smallest h %.3e at t = %.4f, largest %.3e (ratio %.0f)\n", hmin, tmin, hmax,
           hmax / hmin);
  }

  printf("\nadaptive  rtol = atol = %.0e: steps %ld, rejected %ld (error test) + %ld "
         "(Newton), Newton iterations %ld, cpu %.4f s\n",
         tol, res.nsteps, res.netf, res.nncf, res.nni, res.cpu_seconds);
  printf("reference rtol = atol = %.0e: steps %ld, rejected %ld, cpu %.4f s\n", ref.rtol,
         rres.nsteps, rres.netf, rres.cpu_seconds);
  printf("error at t_end (max |x_k - x_k,ref|) %.3e m; |Phi(t_end)| %.1e\n", err,
         res.phi_end);

  /* 3. the fixed step of the same error: double, then bisect the steps */
  printf("\nfixed-step runs (h = t_end / N) to reach the error %.3e:\n", err);
  lo = 0;
  hi = res.nsteps / 4 > 8 ? res.nsteps / 4 : 8;
  for (;;) {
    err_fixed = FixedRun(sys, &opt, hi, rres.q, &cpu);
    if (err_fixed <= err) {
      cpu_fixed = cpu;
      break;
    }
    lo = hi;
    if (hi > 4000000L) break;
    hi *= 2;
  }
  if (err_fixed <= err) {
    while (hi - lo > hi / 50 + 1) { /* within 2% */
      double c;
      mid = (lo + hi) / 2;
      if (FixedRun(sys, &opt, mid, rres.q, &c) <= err) {
        hi        = mid;
        cpu_fixed = c;
      } else {
        lo = mid;
      }
    }
    printf("\nsummary: to the error %.2e at t_end, error control takes %ld steps "
           "(%ld rejected) in %.4f s CPU; a fixed step needs N = %ld steps "
           "(h = %.3e) in %.4f s: %.1fx the steps, %.1fx the CPU time\n",
           err, res.nsteps, res.netf + res.nncf, res.cpu_seconds, hi, opt.t_end / hi,
           cpu_fixed, (double)hi / res.nsteps,
           res.cpu_seconds > 0 ? cpu_fixed / res.cpu_seconds : 0.0);
    printf("adaptive_steps %ld fixed_steps %ld\n", res.nsteps, hi);
  } else {
    printf("no fixed step reached the error %.3e\n", err);
    hi = -1;
  }

  if (png) {
    char script[4200];
    FILE *gp = bench_gnuplot_open("whipping_chain", png_path, script, sizeof script);
    if (gp != NULL) {
      fprintf(gp,
              "set terminal pngcairo size 900,540 noenhanced\n"
              "set output '%s'\n"
              "set datafile separator ','\n"
              "set key autotitle columnhead top left\n"
              "set title 'Whipping chain, %d rods: step size of error control "
              "(rtol = atol = %.0e, %ld steps)'\n"
              "set xlabel 't [s]'\nset ylabel 'h [s]'\nset logscale y\nset grid\n"
              "set y2label 'order'\nset y2range [0:6]\nset y2tics 1\n"
              "plot '%s' using 1:2 with linespoints pt 7 ps 0.4 lw 1.5 title 'h(t), adaptive'",
              png_path, n, tol, res.nsteps, csv_path);
      if (opt.bdf_maxord > 0) /* the order of every step on the right axis */
        fprintf(gp, ", '%s' using 1:3 axes x1y2 with steps lw 1.5 title 'BDF order'", csv_path);
      if (hi > 0)
        fprintf(gp, ", %.10g with lines dt 2 lw 2 title 'fixed h of the same error (%ld steps)'",
                opt.t_end / hi, hi);
      fprintf(gp, "\n");
      bench_gnuplot_run("whipping_chain", gp, script, png_path);
    }
  }

  if (check) {
    if (hi < 0 || !(res.nsteps < hi)) {
      printf("FAILED: error control should need fewer steps than a fixed step of the "
             "same error\n");
      status = 1;
    } else {
      printf("PASSED: %ld adaptive steps < %ld fixed steps of the same error\n", res.nsteps,
             hi);
    }
  }
  rigid_result_free(&res);
  rigid_result_free(&rres);
  rigid_free(&sys);
  SUNContext_Free(&ctx);
  return status;
}
