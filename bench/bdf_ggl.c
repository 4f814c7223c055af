/* -----------------------------------------------------------------------------
 * BDF on the heavy top (R^3 x SO(3), models/heavy_top.c) with the
 * three constraint formulations: index 3 (LGN_CONSTR_INDEX3), the
 * stabilised index 2 (LGN_CONSTR_GGL) and index 2 (LGN_CONSTR_INDEX2),
 * under error control, maxord 4 and 5, tol = rtol = atol = 1e-4 ... 1e-10,
 * to t = 1: the error of the centre of mass at t = 1 against the ARKODE
 * reference, steps, Newton iterations, matrix evaluations, error-test and
 * Newton failures, max |Phi| at t = 1 and CPU time (--half: tolerances
 * every half decade, 1e-4, 3.16e-5, ..., 1e-10); with --callgrind also
 * the instructions of each run (valgrind --tool=callgrind on this program
 * with --only, which runs one configuration without the reference).
 *
 *   bdf_ggl [--quick | --half] [--modified] [--csv FILE] [--callgrind]
 *   bdf_ggl [--modified] --only idx3|ggl|idx2 MAXORD TOL  (one run, for callgrind)
 *
 * (--modified: modified Newton, LGN_NEWTON_MODIFIED; default full Newton)
 *
 * Prints a table and writes CSV (default bdf_ggl.csv). Wall-clock and CPU
 * times vary by 20-50 % on a shared machine: compare steps, iterations and
 * instructions.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>

#include "lgn_reference.h"
#include "models/heavy_top.h"

static const struct {
  const char *name;
  int index;
} FORMS[3] = {{"idx3", LGN_CONSTR_INDEX3}, {"ggl", LGN_CONSTR_GGL}, {"idx2", LGN_CONSTR_INDEX2}};

static int newton_mode = LGN_NEWTON_FULL; /* --modified: LGN_NEWTON_MODIFIED */

static int RunOne(int index, int maxord, double tol, HeavyTopResult *res)
{
  HeavyTopOptions opt;
  heavy_top_default_options(&opt);
  opt.newton       = newton_mode;
  opt.formulation  = HT_LIE;
  opt.constraints  = index;
  opt.bdf_maxord   = maxord;
  opt.adaptive     = 1;
  opt.single_solve = 1;
  opt.rtol = opt.atol = tol;
  opt.h     = 1.0;
  opt.t_end = 1.0;
  opt.analytic_jacobians = 1;
  return heavy_top_run(&opt, res);
}

/* Instructions of one run under callgrind (-1: not available). */
static double Instructions(const char *self, const char *form, int maxord, double tol)
{
  char cmd[1024], line[512];
  const char *out = "bdf_ggl.callgrind.tmp";
  double ir = -1;
  FILE *f;
  snprintf(cmd, sizeof cmd,
           "valgrind --tool=callgrind --callgrind-out-file=%s %s %s--only %s %d %g "
           ">/dev/null 2>&1",
           out, self, newton_mode == LGN_NEWTON_MODIFIED ? "--modified " : "", form, maxord,
           tol);
  if (system(cmd) != 0) return -1;
  f = fopen(out, "r");
  if (f == NULL) return -1;
  while (fgets(line, sizeof line, f) != NULL)
    if (strncmp(line, "summary:", 8) == 0) ir = atof(line + 8);
  fclose(f);
  remove(out);
  return ir;
}

int main(int argc, char **argv)
{
  const double tols_full[7] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  const double tols_quick[2] = {1e-6, 1e-8};
  double tols_half[13];
  const char *csvname = "bdf_ggl.csv";
  int quick = 0, callgrind = 0, half = 0, i, j, f, mo, ntol;
  const double *tols;
  LGNRefHeavyTop ref;
  const double t1 = 1.0;
  FILE *csv;

  for (i = 1; i < argc; i++)
    if (strcmp(argv[i], "--modified") == 0) newton_mode = LGN_NEWTON_MODIFIED;
  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--only") == 0 && i + 3 < argc) {
      HeavyTopResult res;
      for (f = 0; f < 3; f++)
        if (strcmp(argv[i + 1], FORMS[f].name) == 0)
          return RunOne(FORMS[f].index, atoi(argv[i + 2]), atof(argv[i + 3]), &res) ? 1 : 0;
      fprintf(stderr, "--only: unknown formulation %s\n", argv[i + 1]);
      return 2;
    } else if (strcmp(argv[i], "--quick") == 0) {
      quick = 1;
    } else if (strcmp(argv[i], "--half") == 0) {
      half = 1;
    } else if (strcmp(argv[i], "--modified") == 0) {
      newton_mode = LGN_NEWTON_MODIFIED;
    } else if (strcmp(argv[i], "--callgrind") == 0) {
      callgrind = 1;
    } else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
      csvname = argv[++i];
    } else {
      fprintf(stderr, "usage: %s [--quick | --half] [--modified] [--csv FILE] [--callgrind] | "
                      "[--modified] --only idx3|ggl|idx2 MAXORD TOL\n", argv[0]);
      return 2;
    }
  }
  for (j = 0; j < 13; j++) tols_half[j] = pow(10.0, -4.0 - 0.5 * j);
  tols = quick ? tols_quick : half ? tols_half : tols_full;
  ntol = quick ? 2 : half ? 13 : 7;
  if (lgnref_heavy_top(&t1, 1, &ref, LGNREF_FEHLBERG_8) != 0) return 1;
  csv = fopen(csvname, "w");
  if (csv == NULL) return 1;
  fprintf(csv, "maxord,formulation,tol,error,steps,newton_iters,jac_evals,err_test_fails,"
               "newton_fails,phi_end,cpu_s,instructions\n");
  printf("heavy top, BDF under error control to t = 1, %s Newton: error of the centre of "
         "mass\n", newton_mode == LGN_NEWTON_MODIFIED ? "modified" : "full");
  printf("%6s %5s %7s %10s %6s %7s %6s %4s %4s %9s %8s %12s\n", "maxord", "form", "tol",
         "error", "steps", "newton", "jacs", "etf", "ncf", "|Phi|", "cpu s", "instr.");
  for (mo = 4; mo <= 5; mo++)
    for (j = 0; j < ntol; j++)
      for (f = 0; f < 3; f++) {
        HeavyTopResult res;
        double e = 0, phi = 0, ir = -1;
        int flag = RunOne(FORMS[f].index, mo, tols[j], &res), k;
        for (k = 0; k < 3; k++) e = fmax(e, fabs(res.x[k] - ref.x[k]));
        /* |X - R^T x| at t = 1, X = e_y */
        for (k = 0; k < 3; k++) {
          const double rx = res.R[k] * res.x[0] + res.R[3 + k] * res.x[1] +
                            res.R[6 + k] * res.x[2];
          phi = fmax(phi, fabs((k == 1 ? 1.0 : 0.0) - rx));
        }
        if (flag != 0) e = NAN;
        if (callgrind) ir = Instructions(argv[0], FORMS[f].name, mo, tols[j]);
        printf("%6d %5s %7.0e %10.3e %6ld %7ld %6ld %4ld %4ld %9.2e %8.4f %12.4g\n", mo,
               FORMS[f].name, tols[j], e, res.nsteps, res.nniters, res.njevals, res.netfails,
               res.nncfails, phi, res.cpu_seconds, ir);
        fprintf(csv, "%d,%s,%g,%.6e,%ld,%ld,%ld,%ld,%ld,%.3e,%.6f,%.0f\n", mo, FORMS[f].name,
                tols[j], e, res.nsteps, res.nniters, res.njevals, res.netfails, res.nncfails,
                phi, res.cpu_seconds, ir);
      }
  fclose(csv);
  printf("CSV: %s\n", csvname);
  return 0;
}
