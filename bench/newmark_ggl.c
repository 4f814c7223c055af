/* -----------------------------------------------------------------------------
 * mod. LGGalpha (generalized-alpha, rho_inf = 0.9, exact kinematics) on the
 * heavy top (R^3 x SO(3), models/heavy_top.c) with the three
 * constraint formulations: index 3 (LGN_CONSTR_INDEX3), the stabilised
 * index 2 (LGN_CONSTR_GGL, doc/theory.md section 7.1) and index 2
 * (LGN_CONSTR_INDEX2), to t = 1, with fixed steps h = 2e-3 ... 2.5e-4 and
 * under error control, tol = rtol = atol = 1e-4 ... 1e-8: the error of the
 * centre of mass at t = 1 against the ARKODE reference, steps, Newton
 * iterations, matrix evaluations, |Phi| and |B v| at t = 1; with
 * --callgrind also the instructions of each run (valgrind
 * --tool=callgrind on this program with --only, which runs one
 * configuration without the reference).
 *
 *   newmark_ggl [--quick] [--simplified] [--modified] [--csv FILE] [--callgrind]
 *   newmark_ggl [--simplified] [--modified] --only idx3|ggl|idx2 fixed|adaptive VALUE
 *
 * (--simplified: LGGalpha, simplified kinematics; --modified: modified
 * Newton, LGN_NEWTON_MODIFIED; default full Newton). Prints a table and
 * writes CSV (default newmark_ggl.csv). Compare steps, iterations and
 * instructions, not times (a shared machine).
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

static int newton_mode = LGN_NEWTON_FULL;       /* --modified */
static int kinematics  = LGN_KINEMATICS_EXACT;  /* --simplified */

/* One run to t = 1: fixed steps of size value, or error control at
 * tolerance value (adaptive). */
static int RunOne(int index, int adaptive, double value, HeavyTopResult *res)
{
  HeavyTopOptions opt;
  heavy_top_default_options(&opt);
  opt.newton       = newton_mode;
  opt.formulation  = HT_LIE;
  opt.method       = HT_GENALPHA;
  opt.rho_inf      = 0.9;
  opt.kinematics   = kinematics;
  opt.constraints  = index;
  opt.single_solve = 1;
  opt.t_end        = 1.0;
  opt.analytic_jacobians = 1;
  opt.adaptive     = adaptive;
  if (adaptive) {
    opt.rtol = opt.atol = value;
    opt.h = 1.0;
  } else {
    opt.h = value;
  }
  return heavy_top_run(&opt, res);
}

/* Instructions of one run under callgrind (-1: not available). */
static double Instructions(const char *self, const char *form, int adaptive, double value)
{
  char cmd[1024], line[512];
  const char *out = "newmark_ggl.callgrind.tmp";
  double ir = -1;
  FILE *f;
  snprintf(cmd, sizeof cmd,
           "valgrind --tool=callgrind --callgrind-out-file=%s %s %s%s--only %s %s %g "
           ">/dev/null 2>&1",
           out, self, newton_mode == LGN_NEWTON_MODIFIED ? "--modified " : "",
           kinematics == LGN_KINEMATICS_SIMPLIFIED ? "--simplified " : "", form,
           adaptive ? "adaptive" : "fixed", value);
  if (system(cmd) != 0) return -1;
  f = fopen(out, "r");
  if (f == NULL) return -1;
  while (fgets(line, sizeof line, f) != NULL)
    if (strncmp(line, "summary:", 8) == 0) ir = atof(line + 8);
  fclose(f);
  remove(out);
  return ir;
}

/* |Phi| = |X - R^T x| and |B v| = |R^T u - Omega x X| at the end, X = e_y. */
static void Violations(const HeavyTopResult *res, double *phi, double *bv)
{
  const double X[3] = {0, 1, 0};
  double rx[3], ru[3], ox[3];
  int k;
  for (k = 0; k < 3; k++) {
    rx[k] = res->R[k] * res->x[0] + res->R[3 + k] * res->x[1] + res->R[6 + k] * res->x[2];
    ru[k] = res->R[k] * res->u[0] + res->R[3 + k] * res->u[1] + res->R[6 + k] * res->u[2];
  }
  ox[0] = res->Omega[1] * X[2] - res->Omega[2] * X[1];
  ox[1] = res->Omega[2] * X[0] - res->Omega[0] * X[2];
  ox[2] = res->Omega[0] * X[1] - res->Omega[1] * X[0];
  *phi = *bv = 0;
  for (k = 0; k < 3; k++) {
    *phi = fmax(*phi, fabs(X[k] - rx[k]));
    *bv  = fmax(*bv, fabs(ru[k] - ox[k]));
  }
}

int main(int argc, char **argv)
{
  const double hs_full[4] = {2e-3, 1e-3, 5e-4, 2.5e-4}, hs_quick[1] = {1e-3};
  const double tols_full[5] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8}, tols_quick[1] = {1e-6};
  const char *csvname = "newmark_ggl.csv";
  int quick = 0, callgrind = 0, i, j, f, mode;
  LGNRefHeavyTop ref;
  const double t1 = 1.0;
  FILE *csv;

  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--modified") == 0) newton_mode = LGN_NEWTON_MODIFIED;
    if (strcmp(argv[i], "--simplified") == 0) kinematics = LGN_KINEMATICS_SIMPLIFIED;
  }
  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--only") == 0 && i + 3 < argc) {
      HeavyTopResult res;
      for (f = 0; f < 3; f++)
        if (strcmp(argv[i + 1], FORMS[f].name) == 0)
          return RunOne(FORMS[f].index, strcmp(argv[i + 2], "adaptive") == 0,
                        atof(argv[i + 3]), &res) ? 1 : 0;
      fprintf(stderr, "--only: unknown formulation %s\n", argv[i + 1]);
      return 2;
    } else if (strcmp(argv[i], "--quick") == 0) {
      quick = 1;
    } else if (strcmp(argv[i], "--callgrind") == 0) {
      callgrind = 1;
    } else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) {
      csvname = argv[++i];
    } else if (strcmp(argv[i], "--modified") != 0 && strcmp(argv[i], "--simplified") != 0) {
      fprintf(stderr, "usage: %s [--quick] [--simplified] [--modified] [--csv FILE] "
                      "[--callgrind] | [--simplified] [--modified] --only idx3|ggl|idx2 "
                      "fixed|adaptive VALUE\n", argv[0]);
      return 2;
    }
  }
  if (lgnref_heavy_top(&t1, 1, &ref, LGNREF_FEHLBERG_8) != 0) return 1;
  csv = fopen(csvname, "w");
  if (csv == NULL) return 1;
  fprintf(csv, "mode,formulation,value,error,steps,newton_iters,jac_evals,err_test_fails,"
               "newton_fails,phi_end,bv_end,instructions\n");
  printf("heavy top, %s, rho_inf 0.9, %s Newton, to t = 1: error of the centre of mass\n",
         kinematics == LGN_KINEMATICS_EXACT ? "mod. LGGalpha" : "LGGalpha",
         newton_mode == LGN_NEWTON_MODIFIED ? "modified" : "full");
  printf("%8s %5s %8s %10s %6s %7s %6s %4s %4s %9s %9s %12s\n", "mode", "form", "h / tol",
         "error", "steps", "newton", "jacs", "etf", "ncf", "|Phi|", "|B v|", "instr.");
  for (mode = 0; mode < 2; mode++) {
    const double *vals = mode == 0 ? (quick ? hs_quick : hs_full) : (quick ? tols_quick : tols_full);
    const int nval = quick ? 1 : mode == 0 ? 4 : 5;
    for (j = 0; j < nval; j++)
      for (f = 0; f < 3; f++) {
        HeavyTopResult res;
        double e = 0, phi, bv, ir = -1;
        int flag = RunOne(FORMS[f].index, mode, vals[j], &res), k;
        for (k = 0; k < 3; k++) e = fmax(e, fabs(res.x[k] - ref.x[k]));
        Violations(&res, &phi, &bv);
        if (flag != 0) e = NAN;
        if (callgrind) ir = Instructions(argv[0], FORMS[f].name, mode, vals[j]);
        printf("%8s %5s %8.1e %10.3e %6ld %7ld %6ld %4ld %4ld %9.2e %9.2e %12.4g\n",
               mode ? "adaptive" : "fixed", FORMS[f].name, vals[j], e, res.nsteps,
               res.nniters, res.njevals, res.netfails, res.nncfails, phi, bv, ir);
        fprintf(csv, "%s,%s,%g,%.6e,%ld,%ld,%ld,%ld,%ld,%.3e,%.3e,%.0f\n",
                mode ? "adaptive" : "fixed", FORMS[f].name, vals[j], e, res.nsteps,
                res.nniters, res.njevals, res.netfails, res.nncfails, phi, bv, ir);
      }
  }
  fclose(csv);
  printf("CSV: %s\n", csvname);
  return 0;
}
