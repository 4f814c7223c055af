/* -----------------------------------------------------------------------------
 * Lignum benchmark: KLU against SPGMR + the block preconditioner on the
 * N-body spherical-pendulum chain (issue 23, item 2). Not a test: a table
 * to read (doc/user-guide.md, section 7).
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 *   krylov_scaling [--n N[,N...]] [--bpb B[,B...]] [--steps S] [--maxl L]
 *
 * For each N (default 1000,10000,100000): KLU (CSC, AMD, Lignum's solves on
 * a copy of its factors where the versions allow), then SPGMR (Krylov
 * dimension L = 50, 5 restarts, PREC_LEFT) with the block preconditioner
 * in blocks of B bodies (default 100,1000; B <= N). Generalized-alpha
 * (rho_inf 0.9), full Newton, h = 1e-3, S steps (default 10). Each run is
 * a child process (fork), so that its peak resident memory (ru_maxrss) is
 * its own. Columns: CPU ms per step over the second half of the steps
 * (without the set-up, analysis and initial values of the first), peak
 * RSS in MB, Lignum's work space (LGNGetWorkSpace, 8-byte words, in MB:
 * with SPGMR it includes the blocks' KLU factors) plus KLU's peak for the
 * KLU run, Newton iterations per step, Krylov iterations per Newton
 * iteration, solves short of their tolerance.
 * ---------------------------------------------------------------------------*/

#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "models/chain.h"

static int Run(int n, int bpb, int steps, int maxl)
{
  SUNContext ctx;
  RigidSystem *sys;
  RigidRunOptions opt;
  RigidRunResult res;
  struct rusage ru;
  double per_step, ws_mb;
  char name[64];
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  sys = chain_create(n, RB_R3XSO3, ctx);
  if (sys == NULL) return 1;
  rigid_default_run_options(&opt);
  opt.h       = 1e-3;
  opt.t_end   = steps * opt.h;
  opt.outputs = 2;
  if (bpb > 0) {
    opt.solver          = RB_SPGMR;
    opt.krylov_blocks   = (n + bpb - 1) / bpb;
    opt.krylov_maxl     = maxl;
    opt.krylov_restarts = 5;
    snprintf(name, sizeof name, "spgmr+block %d x %d", opt.krylov_blocks, bpb);
  } else {
    opt.solver = RB_KLU_CSC;
    snprintf(name, sizeof name, "klu");
  }
  rigid_run(sys, &opt, &res);
  getrusage(RUSAGE_SELF, &ru);
  per_step = res.nsteps > res.nsteps_first
                 ? 1e3 * (res.cpu_seconds - res.cpu_first_seconds) /
                       (double)(res.nsteps - res.nsteps_first)
                 : 0.0;
  ws_mb = (8.0 * (double)res.lenrw + 8.0 * (double)res.leniw + res.klu_peak_bytes) / 1e6;
  printf("| %6d | %-22s | %4d | %9.2f | %8.0f | %8.1f | %6.2f | %6.2f | %5ld |\n", n,
         name, res.flag, per_step, (double)ru.ru_maxrss / 1024.0, ws_mb,
         res.nsteps > 0 ? (double)res.nni / (double)res.nsteps : 0.0,
         res.nni > 0 ? (double)res.nli / (double)res.nni : 0.0, res.nlcf);
  fflush(stdout);
  rigid_result_free(&res);
  rigid_free(&sys);
  SUNContext_Free(&ctx);
  return 0;
}

static int Child(int n, int bpb, int steps, int maxl)
{
  pid_t pid = fork();
  int status = 0;
  if (pid < 0) return 1;
  if (pid == 0) _exit(Run(n, bpb, steps, maxl));
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

/* "a,b,c" -> up to 8 integers */
static int ParseList(const char *s, int *out)
{
  int k = 0;
  while (*s != '\0' && k < 8) {
    out[k++] = atoi(s);
    s = strchr(s, ',');
    if (s == NULL) break;
    s++;
  }
  return k;
}

int main(int argc, char **argv)
{
  int ns[8] = {1000, 10000, 100000}, bpbs[8] = {100, 1000};
  int nn = 3, nb = 2, steps = 10, maxl = 50, i, j, fail = 0;
  for (i = 1; i + 1 < argc; i += 2) {
    if (strcmp(argv[i], "--n") == 0) nn = ParseList(argv[i + 1], ns);
    else if (strcmp(argv[i], "--bpb") == 0) nb = ParseList(argv[i + 1], bpbs);
    else if (strcmp(argv[i], "--steps") == 0) steps = atoi(argv[i + 1]);
    else if (strcmp(argv[i], "--maxl") == 0) maxl = atoi(argv[i + 1]);
    else {
      fprintf(stderr, "usage: %s [--n N,...] [--bpb B,...] [--steps S] [--maxl L]\n", argv[0]);
      return 2;
    }
  }
  printf("chain, generalized-alpha, full Newton, h = 1e-3, %d steps; SPGMR "
         "maxl %d, 5 restarts, PREC_LEFT\n\n", steps, maxl);
  printf("| N      | solver                 | flag | ms/step   | RSS MB   | work MB  | Newton | Kry/N  | short |\n");
  printf("|--------|------------------------|------|-----------|----------|----------|--------|--------|-------|\n");
  fflush(stdout);
  for (i = 0; i < nn; i++) {
    fail |= Child(ns[i], 0, steps, maxl);
    for (j = 0; j < nb; j++)
      if (bpbs[j] <= ns[i]) fail |= Child(ns[i], bpbs[j], steps, maxl);
  }
  return fail;
}
