/* -----------------------------------------------------------------------------
 * Lignum benchmark: cost per step of the N-body chain against N.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 *   chain_scaling [--n N1,N2,...] [--steps S] [--repeat R] [--dense-max N]
 *                 [--klu-solve lignum|klu]
 *                 [--csv FILE] [--memory-csv FILE] [--floor-csv FILE] [--quick]
 *
 * The chain of models/chain.h (generalized-alpha rho_inf = 0.9,
 * index 3, h = 1e-3, analytic K_t, C_t, Z from the joint helpers), S steps
 * per run, with KLU (CSC) for every N, full Newton ("klu") and modified
 * Newton with the extrapolating predictor ("klu-mN", LGNSetNewtonMode,
 * LGNSetPredictor), and the dense solver up to --dense-max.
 * Time = process CPU time inside LGNSolve, in two parts: the first call,
 * to t = S h / 10 (set-up, the first assembly, KLU's symbolic analysis,
 * consistent initial values and its S/10 steps), and the steps after it,
 * whose time per step is the steady cost a long simulation pays ("ms/step",
 * fitted below; "first [ms]" is the first call). Each KLU run is repeated
 * R times (default 3; dense once) and the fastest kept, since the machine
 * may be shared. Prints a table, writes
 *   n,solver,steps,seconds,seconds_per_step,newton_per_step,nnz
 * (steps and seconds: those after the first call; newton_per_step: all)
 * and fits the exponent p of seconds_per_step ~ N^p for KLU (least squares
 * in log-log over all N, the target p <= 1.1; and between the two
 * largest N, per step and per Newton iteration: there the step also pays
 * for the iterations per step growing with N, and at N = 10000 the factors
 * no longer fit in the 4 MB L2 of this machine). Memory per body
 * (Lignum's work space from LGNGetWorkSpace plus KLU's peak) goes to a
 * second CSV, and the floor under a Newton iteration, the CPU time [ms] of
 * one solve and one factorisation by SUNDIALS' KLU with the last iteration
 * matrix ("KLU solve", "KLU factor"; Lignum's own solves on its copy of the
 * factors, LGNSetOwnKLUSolves, take about 0.6 of KLU's), to a third.
 * The KLU runs use Lignum's solves on a copy of KLU's factors (and, CSC,
 * its refactorisations; LGNSetOwnKLUSolves, off by default in the library,
 * opted in by rigid_run), or with --klu-solve klu SUNDIALS' own
 * SUNLinSolSetup and SUNLinSolSolve, to measure what the copy buys.
 * Never fails on timing.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/chain.h"

#define MAXN 16

static double FitExponent(const double *x, const double *y, int n)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int i;
  for (i = 0; i < n; i++) {
    const double lx = log(x[i]), ly = log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/* The steady cost of a run: the steps after the first LGNSolve call (all
 * of them when the first call took every step). Returns seconds per step. */
static double SteadyPerStep(const RigidRunResult *r, long int *steps, double *seconds)
{
  *steps   = r->nsteps - r->nsteps_first;
  *seconds = r->cpu_seconds - r->cpu_first_seconds;
  if (*steps < 1) {
    *steps   = r->nsteps;
    *seconds = r->cpu_seconds;
  }
  return *seconds / (double)*steps;
}

int main(int argc, char **argv)
{
  int ns[MAXN] = {10, 100, 1000, 10000}, nn = 4, steps = 100, dense_max = 100, i, k, s;
  int repeat = 3, rep, klu_solve_sundials = 0;
  const char *csv_name = "chain_scaling.csv", *mem_name = "chain_memory.csv";
  const char *floor_name = "chain_floor.csv";
  double klu_n[2][MAXN], klu_t[2][MAXN]; /* full, modified Newton */
  double klu_it[2][MAXN];                /* time per Newton iteration */
  int nklu[2] = {0, 0}, v;
  FILE *csv, *mem, *flr;
  SUNContext ctx;

  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--n") == 0 && i + 1 < argc) {
      char *tok = strtok(argv[++i], ",");
      nn = 0;
      while (tok != NULL && nn < MAXN) {
        ns[nn++] = atoi(tok);
        tok = strtok(NULL, ",");
      }
    } else if (strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
      steps = atoi(argv[++i]);
    } else if (strcmp(argv[i], "--repeat") == 0 && i + 1 < argc) {
      repeat = atoi(argv[++i]);
    } else if (strcmp(argv[i], "--dense-max") == 0 && i + 1 < argc) {
      dense_max = atoi(argv[++i]);
    } else if (strcmp(argv[i], "--klu-solve") == 0 && i + 1 < argc &&
               (strcmp(argv[i + 1], "lignum") == 0 || strcmp(argv[i + 1], "klu") == 0)) {
      klu_solve_sundials = strcmp(argv[++i], "klu") == 0;
    } else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
      csv_name = argv[++i];
    } else if (strcmp(argv[i], "--memory-csv") == 0 && i + 1 < argc) {
      mem_name = argv[++i];
    } else if (strcmp(argv[i], "--floor-csv") == 0 && i + 1 < argc) {
      floor_name = argv[++i];
    } else if (strcmp(argv[i], "--quick") == 0) {
      ns[0] = 10; ns[1] = 30; ns[2] = 100;
      nn = 3;
      steps = 10;
      dense_max = 30;
      repeat = 1;
    } else {
      fprintf(stderr, "usage: %s [--n N1,N2,...] [--steps S] [--repeat R] [--dense-max N] "
                      "[--klu-solve lignum|klu] "
                      "[--csv FILE] [--memory-csv FILE] [--floor-csv FILE] [--quick]\n",
              argv[0]);
      return 2;
    }
  }
  for (i = 0; i < nn; i++)
    if (ns[i] < 1) return 2;
  if (steps < 1 || repeat < 1) return 2;
  csv = fopen(csv_name, "w");
  mem = fopen(mem_name, "w");
  flr = fopen(floor_name, "w");
  if (csv == NULL || mem == NULL || flr == NULL || SUNContext_Create(NULL, &ctx) != 0)
    return 1;
  fprintf(csv, "n,solver,steps,seconds,seconds_per_step,newton_per_step,nnz\n");
  fprintf(mem, "n,solver,lignum_bytes,klu_peak_bytes,bytes_per_body\n");
  fprintf(flr, "n,solver,solve_seconds,setup_seconds,setups,stalls,"
               "first_call_seconds,first_call_steps\n");

  printf("chain scaling: generalized-alpha 0.9, index 3, h = 1e-3, %d steps, "
         "analytic tangents; KLU with %s\n\n", steps,
         klu_solve_sundials ? "SUNDIALS' setups and solves (--klu-solve klu)"
                            : "Lignum's solves on a copy of its factors");
  printf("%7s %-6s %6s %9s %10s %10s %9s %7s %9s %10s %10s %11s\n", "N", "solver",
         "steps", "cpu [s]", "first [ms]", "ms/step", "Newton/st", "setups", "nnz",
         "KLU solve", "KLU factor", "bytes/body");
  for (i = 0; i < nn; i++) {
    RigidSystem *sys = chain_create(ns[i], RB_R3XSO3, ctx);
    if (sys == NULL) return 1;
    for (s = 0; s < 3; s++) { /* dense, KLU, KLU with modified Newton */
      RigidRunOptions opt;
      RigidRunResult r;
      double bytes, per_step, steady_seconds;
      long int steady_steps;
      char label[16];
      int flag;
      if (s == 0 && ns[i] > dense_max) continue;
      rigid_default_run_options(&opt);
      opt.solver  = s == 0 ? RB_DENSE : RB_KLU_CSC;
      opt.newton  = s == 2 ? LGN_NEWTON_MODIFIED : LGN_NEWTON_FULL;
      opt.predictor = s == 2 ? LGN_PREDICTOR_EXTRAPOLATE : LGN_PREDICTOR_ZERO;
      opt.time_linear_algebra = 1;
      opt.klu_solve_sundials  = klu_solve_sundials;
      snprintf(label, sizeof label, "%s%s", rigid_solver_name(opt.solver),
               s == 2 ? "-mN" : "");
      opt.h       = 1e-3;
      opt.t_end   = steps * opt.h;
      opt.outputs = steps >= 10 ? 10 : 1;
      /* the fastest of `repeat` runs (one for dense): the machine is shared */
      flag = LGN_SUCCESS;
      per_step = -1.0;
      for (rep = 0; rep < (s == 0 ? 1 : repeat) && flag == LGN_SUCCESS; rep++) {
        RigidRunResult t;
        double t_per_step;
        flag = rigid_run(sys, &opt, &t);
        if (flag != LGN_SUCCESS || t.nsteps < 1) {
          if (per_step >= 0.0) rigid_result_free(&r);
          r = t;
          per_step = -1.0;
          break;
        }
        t_per_step = SteadyPerStep(&t, &steady_steps, &steady_seconds);
        if (per_step < 0.0 || t_per_step < per_step) {
          if (per_step >= 0.0) rigid_result_free(&r);
          r        = t;
          per_step = t_per_step;
        } else {
          rigid_result_free(&t);
        }
      }
      if (per_step < 0.0) {
        printf("%7d %-6s failed: %s\n", ns[i], label,
               flag != LGN_SUCCESS ? LGNGetReturnFlagName(flag) : "no step taken");
        rigid_result_free(&r);
        continue;
      }
      per_step = SteadyPerStep(&r, &steady_steps, &steady_seconds);
      bytes    = 8.0 * (double)(r.lenrw + r.leniw) + r.klu_peak_bytes;
      printf("%7d %-6s %6ld %9.3f %10.2f %10.4f %9.2f %7ld %9ld %10.4f %10.4f %11.0f\n",
             ns[i], label, r.nsteps, r.cpu_seconds, 1e3 * r.cpu_first_seconds,
             1e3 * per_step, (double)r.nni / r.nsteps, r.nlsetups, r.nnz,
             1e3 * r.solve_seconds, 1e3 * r.setup_seconds, bytes / ns[i]);
      fprintf(flr, "%d,%s,%.6g,%.6g,%ld,%ld,%.6g,%ld\n", ns[i], label, r.solve_seconds,
              r.setup_seconds, r.nlsetups, r.nstall, r.cpu_first_seconds, r.nsteps_first);
      fprintf(csv, "%d,%s,%ld,%.6g,%.6g,%.4g,%ld\n", ns[i], label,
              steady_steps, steady_seconds, per_step, (double)r.nni / r.nsteps, r.nnz);
      fprintf(mem, "%d,%s,%.0f,%.0f,%.1f\n", ns[i], label,
              8.0 * (double)(r.lenrw + r.leniw), r.klu_peak_bytes, bytes / ns[i]);
      if (s >= 1) {
        klu_n[s - 1][nklu[s - 1]]   = ns[i];
        /* the Newton iterations of the same steps as steady_seconds */
        {
          const long int it = steady_steps == r.nsteps ? r.nni : r.nni - r.nni_first;
          klu_it[s - 1][nklu[s - 1]] = steady_seconds / (double)(it > 0 ? it : 1);
        }
        klu_t[s - 1][nklu[s - 1]++] = per_step;
      }
      rigid_result_free(&r);
    }
    rigid_free(&sys);
  }
  fclose(csv);
  fclose(mem);
  fclose(flr);
  for (v = 0; v < 2; v++) {
    const int nk = nklu[v];
    const double *kn = klu_n[v], *kt = klu_t[v], *ki = klu_it[v];
    const char *name = v == 0 ? "KLU" : "KLU, modified Newton";
    if (nk < 2) continue;
    {
      const double p_all = FitExponent(kn, kt, nk);
      const double p_top = FitExponent(kn + nk - 2, kt + nk - 2, 2);
      const double p_it  = FitExponent(kn + nk - 2, ki + nk - 2, 2);
      printf("\n%s: time per step ~ N^p, p = %.3f (least squares over N = %g..%g), "
             "p = %.3f (between the two largest N; per Newton iteration %.3f)\n",
             name, p_all, kn[0], kn[nk - 1], p_top, p_it);
      printf("target p <= 1.1 (least-squares exponent): %s\n",
             p_all <= 1.1 ? "MET" : "MISSED");
    }
    for (k = 0; k < nk; k++)
      if (kn[k] == 10000)
        printf("target < 5 ms per step at N = 10000: %.2f ms, %s\n", 1e3 * kt[k],
               kt[k] < 5e-3 ? "MET" : "MISSED");
  }
  printf("wrote %s, %s and %s\n", csv_name, mem_name, floor_name);
  SUNContext_Free(&ctx);
  return 0;
}
