/* -----------------------------------------------------------------------------
 * Lignum benchmark: cost per step of the N-body chain against N.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 *   chain_scaling [--n N1,N2,...] [--steps S] [--dense-max N] [--csv FILE]
 *                 [--memory-csv FILE] [--quick]
 *
 * The chain of examples/models/chain.h (generalized-alpha rho_inf = 0.9,
 * index 3, h = 1e-3, analytic K_t, C_t, Z from the joint helpers), S steps
 * per run, with KLU (CSC) for every N and the dense solver up to --dense-max.
 * Time = process CPU time inside LGNSolve (set-up, consistent initial
 * values, the first assembly and KLU's symbolic analysis included, so
 * S should be large enough to amortise them). Prints a table, writes
 *   n,solver,steps,seconds,seconds_per_step,newton_per_step,nnz
 * and fits the exponent p of seconds_per_step ~ N^p for KLU (least squares
 * in log-log over all N, and between the two largest N). Memory per body
 * (Lignum's work space from LGNGetWorkSpace plus KLU's peak) goes to a
 * second CSV. Never fails on timing.
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

int main(int argc, char **argv)
{
  int ns[MAXN] = {10, 100, 1000, 10000}, nn = 4, steps = 50, dense_max = 100, i, k, s;
  const char *csv_name = "chain_scaling.csv", *mem_name = "chain_memory.csv";
  double klu_n[MAXN], klu_t[MAXN];
  int nklu = 0;
  FILE *csv, *mem;
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
    } else if (strcmp(argv[i], "--dense-max") == 0 && i + 1 < argc) {
      dense_max = atoi(argv[++i]);
    } else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
      csv_name = argv[++i];
    } else if (strcmp(argv[i], "--memory-csv") == 0 && i + 1 < argc) {
      mem_name = argv[++i];
    } else if (strcmp(argv[i], "--quick") == 0) {
      ns[0] = 10; ns[1] = 30; ns[2] = 100;
      nn = 3;
      steps = 10;
      dense_max = 30;
    } else {
      fprintf(stderr, "usage: %s [--n N1,N2,...] [--steps S] [--dense-max N] "
                      "[--csv FILE] [--memory-csv FILE] [--quick]\n", argv[0]);
      return 2;
    }
  }
  for (i = 0; i < nn; i++)
    if (ns[i] < 1) return 2;
  if (steps < 1) return 2;
  csv = fopen(csv_name, "w");
  mem = fopen(mem_name, "w");
  if (csv == NULL || mem == NULL || SUNContext_Create(NULL, &ctx) != 0) return 1;
  fprintf(csv, "n,solver,steps,seconds,seconds_per_step,newton_per_step,nnz\n");
  fprintf(mem, "n,solver,lignum_bytes,klu_peak_bytes,bytes_per_body\n");

  printf("chain scaling: generalized-alpha 0.9, index 3, h = 1e-3, %d steps, "
         "analytic tangents\n\n", steps);
  printf("%7s %-6s %8s %10s %12s %9s %10s %8s %14s\n", "N", "solver", "steps",
         "cpu [s]", "ms/step", "Newton/st", "nnz", "analyses", "bytes/body");
  for (i = 0; i < nn; i++) {
    RigidSystem *sys = chain_create(ns[i], RB_R3XSO3, ctx);
    if (sys == NULL) return 1;
    for (s = 0; s < 2; s++) {
      RigidRunOptions opt;
      RigidRunResult r;
      double bytes, per_step;
      int flag;
      if (s == 0 && ns[i] > dense_max) continue;
      rigid_default_run_options(&opt);
      opt.solver  = s == 0 ? RB_DENSE : RB_KLU_CSC;
      opt.h       = 1e-3;
      opt.t_end   = steps * opt.h;
      opt.outputs = 1;
      flag = rigid_run(sys, &opt, &r);
      if (flag != LGN_SUCCESS || r.nsteps < 1) {
        printf("%7d %-6s failed: %s\n", ns[i], rigid_solver_name(opt.solver),
               LGNGetReturnFlagName(flag));
        rigid_result_free(&r);
        continue;
      }
      per_step = r.cpu_seconds / r.nsteps;
      bytes    = 8.0 * (double)(r.lenrw + r.leniw) + r.klu_peak_bytes;
      printf("%7d %-6s %8ld %10.4f %12.4f %9.2f %10ld %8ld %14.0f\n", ns[i],
             rigid_solver_name(opt.solver), r.nsteps, r.cpu_seconds, 1e3 * per_step,
             (double)r.nni / r.nsteps, r.nnz, r.nanalyses, bytes / ns[i]);
      fprintf(csv, "%d,%s,%ld,%.6g,%.6g,%.4g,%ld\n", ns[i], rigid_solver_name(opt.solver),
              r.nsteps, r.cpu_seconds, per_step, (double)r.nni / r.nsteps, r.nnz);
      fprintf(mem, "%d,%s,%.0f,%.0f,%.1f\n", ns[i], rigid_solver_name(opt.solver),
              8.0 * (double)(r.lenrw + r.leniw), r.klu_peak_bytes, bytes / ns[i]);
      if (s == 1) {
        klu_n[nklu]   = ns[i];
        klu_t[nklu++] = per_step;
      }
      rigid_result_free(&r);
    }
    rigid_free(&sys);
  }
  fclose(csv);
  fclose(mem);
  if (nklu >= 2) {
    const double p_all = FitExponent(klu_n, klu_t, nklu);
    const double p_top = FitExponent(klu_n + nklu - 2, klu_t + nklu - 2, 2);
    printf("\nKLU: time per step ~ N^p, p = %.3f (least squares over N = %g..%g), "
           "p = %.3f (between the two largest N)\n", p_all, klu_n[0], klu_n[nklu - 1], p_top);
    printf("target p <= 1.1: %s\n", fmax(p_all, p_top) <= 1.1 ? "MET" : "MISSED");
    for (k = 0; k < nklu; k++)
      if (klu_n[k] == 10000)
        printf("target < 5 ms per step at N = 10000: %.2f ms, %s\n", 1e3 * klu_t[k],
               klu_t[k] < 5e-3 ? "MET" : "MISSED");
  }
  printf("wrote %s and %s\n", csv_name, mem_name);
  SUNContext_Free(&ctx);
  return 0;
}
