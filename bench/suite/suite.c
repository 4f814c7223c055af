/* -----------------------------------------------------------------------------
 * Lignum benchmarks: the standard multibody suite (issue 30 item 4, issue 33
 * item 5; bench/suite/README.md). Every problem with IDA in its best form and
 * with Lignum's BDF (maxord 5 and 4) and generalized-alpha, full and
 * modified Newton, under error control at rtol = atol = tol over
 * tol = 1e-3 ... 1e-12:
 *
 *   andrews   Andrews' squeezing mechanism (Test Set), t = 0.03   R^7
 *   caraxis   the car axis (Test Set), t = 3                      R^4
 *   pendulum  IFToMM A01, the simple pendulum over 2000 s         R^2
 *   top       the heavy top (models/heavy_top.c), t = 1     R^3 x SO(3)
 *   chain     the 3-rod chain (models/chain.c), t = 1       (R^3 x SO(3))^3
 *
 * IDA: index 2 with IDASetId / IDASetSuppressAlg (suite_ida.c) on the R^n
 * problems; on the top and the chain the GGL peers in Euler parameters
 * (bench/ida_heavy_top.c, bench/ida_chain.c); dense LU with IDA's
 * difference-quotient Jacobian, maxord 5.
 *
 * Error: the Test Set's mixed error over the positions at t_end,
 * max_i |q_i - q_ref,i| / (1 + |q_ref,i|) (the top: its centre of mass, the
 * chain: the free end of the last rod), mescd = -log10(error); the
 * pendulum: the IFToMM A01 error, the largest position error over the 4000
 * outputs, with the energy drift. CPU: process CPU time of the solver
 * calls, the best of --reps runs (one run when a run takes over 0.5 s).
 * A method's tighter tolerances are skipped once one of its runs on a
 * problem has taken more than --budget seconds (default 5), so that the
 * suite runs in a few minutes.
 *
 * Output: per problem a table on stdout, the CSV (--csv, every run; header
 * CSV_HEADER), and with gnuplot the PNG <prefix>_<problem>.png (--png
 * PREFIX): error against CPU time, and error against tol.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>
#include <lignum/lignum_ls.h>

#include "bench_gnuplot.h"
#include "ida_chain.h"
#include "ida_heavy_top.h"
#include "lgn_reference.h"
#include "models/chain.h"
#include "models/heavy_top.h"
#include "suite_run.h"
#include "suite_sundials.h"

#define CSV_HEADER                                                                   \
  "problem,code,method,tol,flag,error,mescd,error_v,energy_drift,steps,rejected,lu," \
  "newton_iters,cpu_s,sundials"

/* ---- the methods ---------------------------------------------------------- */

typedef struct {
  const char *name;
  int ida;        /* 1: IDA; 0: Lignum                           */
  int bdf;        /* Lignum: BDF maxord (0: generalized-alpha)   */
  int newton;     /* Lignum: LGN_NEWTON_*                        */
} Method;

static const Method METHODS[] = {
  {"IDA",          1, 0, 0},
  {"BDF5",         0, 5, LGN_NEWTON_FULL},
  {"BDF5 mN",      0, 5, LGN_NEWTON_MODIFIED},
  {"BDF4",         0, 4, LGN_NEWTON_FULL},
  {"BDF4 mN",      0, 4, LGN_NEWTON_MODIFIED},
  {"gen-alpha",    0, 0, LGN_NEWTON_FULL},
  {"gen-alpha mN", 0, 0, LGN_NEWTON_MODIFIED},
};
#define NMETHODS ((int)(sizeof METHODS / sizeof METHODS[0]))
#define RHO_INF 0.9 /* generalized-alpha (Lignum's default) */

/* --methods: the comma-separated list of the methods to run (NULL: all) */
static const char *method_list = NULL;

/* Is the method named in the comma-separated list (NULL: all)? */
static int MethodListed(const char *list, const char *name)
{
  const size_t n = strlen(name);
  const char *p = list;
  if (list == NULL) return 1;
  while (*p != '\0') {
    const char *end = strchr(p, ',');
    const size_t len = end != NULL ? (size_t)(end - p) : strlen(p);
    if (len == n && strncmp(p, name, n) == 0) return 1;
    if (end == NULL) break;
    p = end + 1;
  }
  return 0;
}

static const char *const PROBLEMS[] = {"andrews", "caraxis", "pendulum", "top", "chain"};
#define NPROBLEMS ((int)(sizeof PROBLEMS / sizeof PROBLEMS[0]))

#define MAXTOLS 16

/* The chain's reference tip at t = 1: IDA at rtol 1e-12
 * (work_precision --chain-reference, bench/README.md). */
static const double CHAIN_TIP_REF[3] = {-1.855169400564356, -6.545653961586941e-03,
                                        -2.068593335280935};
#define CHAIN_N 3

static double MixedError3(const double *x, const double *ref)
{
  double e = 0.0;
  int i;
  for (i = 0; i < 3; i++) e = fmax(e, fabs(x[i] - ref[i]) / (1.0 + fabs(ref[i])));
  return isfinite(x[0] + x[1] + x[2]) ? e : NAN;
}

/* ---- the heavy top and the chain (the existing models and IDA peers) ---- */

static void RunTop(const Method *me, double tol, const double xref[3], SuiteResult *r)
{
  memset(r, 0, sizeof *r);
  r->err_v = r->energy_drift = NAN;
  if (me->ida) {
    IdaHTOptions opt;
    IdaHTResult res;
    ida_heavy_top_default_options(&opt);
    opt.linsol = IDAHT_DENSE_DQ;
    opt.rtol = tol;
    opt.t_end = 1.0;
    opt.scale_x = opt.scale_p = opt.scale_xd = opt.scale_pd = 1.0; /* atol = tol */
    opt.scale_lambda = opt.scale_mu = 1e3; /* out of the error test; Newton's test only,
                                              as in work_precision (fewer steps) */
    opt.h0 = 1e-6;      /* as in work_precision: IDA's own first step fails here */
    ida_heavy_top_run(&opt, &res);
    r->flag = res.flag;
    r->t = res.t;
    r->err = MixedError3(res.x, xref);
    r->nsteps = res.nsteps;
    r->nrejected = res.netf + res.nncf;
    r->nniters = res.nniters;
    r->nlu = res.njevals; /* a DQ Jacobian at every setup */
    r->cpu = res.cpu_seconds;
  } else {
    HeavyTopOptions opt;
    HeavyTopResult res;
    heavy_top_default_options(&opt);
    opt.formulation = HT_LIE;
    opt.method = HT_GENALPHA;
    opt.rho_inf = RHO_INF;
    opt.kinematics = LGN_KINEMATICS_EXACT; /* mod. LGGalpha; BDF ignores it */
    opt.constraints = LGN_CONSTR_INDEX3;
    opt.adaptive = 1;
    opt.rtol = opt.atol = tol;
    opt.h = opt.t_end = 1.0;
    opt.single_solve = 1;
    opt.bdf_maxord = me->bdf;
    opt.newton = me->newton;
    opt.make_ls = LGNLinSol_Dense;
    heavy_top_run(&opt, &res);
    r->flag = res.flag == LGN_TSTOP_RETURN ? 0 : res.flag;
    r->t = res.t;
    r->err = MixedError3(res.x, xref);
    r->nsteps = res.nsteps;
    r->nrejected = res.netfails + res.nncfails;
    r->nniters = res.nniters;
    r->nlu = res.nlsetups;
    r->cpu = res.cpu_seconds;
  }
  if (r->flag == 0 && fabs(r->t - 1.0) > 1e-12) r->flag = -101;
  r->mescd = -log10(r->err);
}

static void RunChain(const Method *me, double tol, SuiteResult *r)
{
  double tip[3] = {NAN, NAN, NAN};
  memset(r, 0, sizeof *r);
  r->err_v = r->energy_drift = NAN;
  if (me->ida) {
    IdaChainOptions opt;
    IdaChainResult res;
    ida_chain_default_options(&opt);
    opt.n = CHAIN_N;
    opt.linsol = IDACH_DENSE_DQ;
    opt.rtol = tol; /* atol: its fixed scales (ida_chain.h) */
    opt.t_end = 1.0;
    ida_chain_run(&opt, &res);
    r->flag = res.flag;
    r->t = res.t;
    memcpy(tip, res.tip, sizeof tip);
    r->nsteps = res.nsteps;
    r->nrejected = -1; /* not reported by ida_chain_run */
    r->nniters = res.nniters;
    r->nlu = res.njevals;
    r->cpu = res.cpu_seconds;
  } else {
    SUNContext ctx = NULL;
    RigidSystem *sys = NULL;
    RigidRunOptions opt;
    RigidRunResult res;
    memset(&res, 0, sizeof res);
    res.flag = -100;
    if (SUNContext_Create(NULL, &ctx) == 0 && (sys = chain_create(CHAIN_N, RB_R3XSO3, ctx))) {
      rigid_default_run_options(&opt);
      opt.solver = RB_DENSE;
      opt.method = 1;
      opt.rho_inf = RHO_INF;
      opt.kinematics = LGN_KINEMATICS_EXACT;
      opt.constraints = LGN_CONSTR_INDEX3;
      opt.newton = me->newton;
      opt.analytic = 1;
      opt.t_end = 1.0;
      opt.outputs = 1;
      opt.bdf_maxord = me->bdf;
      opt.own_dense_lu = 1;
      opt.adaptive = 1;
      opt.rtol = opt.atol = tol;
      opt.h = 1e-4; /* the first step tried */
      rigid_run(sys, &opt, &res);
      if (res.q != NULL) ida_chain_tip(CHAIN_N, res.q, tip);
    }
    r->flag = res.flag;
    r->t = res.t;
    r->nsteps = res.nsteps;
    r->nrejected = res.netf + res.nncf;
    r->nniters = res.nni;
    r->nlu = res.nlsetups;
    r->cpu = res.cpu_seconds;
    rigid_result_free(&res);
    rigid_free(&sys);
    SUNContext_Free(&ctx);
  }
  if (r->flag == 0 && fabs(r->t - 1.0) > 1e-12) r->flag = -101;
  r->err = r->flag == 0 ? MixedError3(tip, CHAIN_TIP_REF) : NAN;
  r->mescd = -log10(r->err);
}

/* One run of problem k with method me at tol. */
static void RunOnce(int k, const Method *me, double tol, const double xref[3], SuiteResult *r)
{
  const char *name = PROBLEMS[k];
  if (strcmp(name, "top") == 0) RunTop(me, tol, xref, r);
  else if (strcmp(name, "chain") == 0) RunChain(me, tol, r);
  else {
    const SuiteProblem *p = suite_problem(name);
    if (me->ida) suite_ida_run(p, tol, 5, SUITE_IDA_INDEX2, r);
    else {
      const SuiteLignumMethod lm = {me->bdf, RHO_INF, LGN_CONSTR_INDEX3, me->newton};
      suite_lignum_run(p, &lm, tol, r);
    }
  }
  if (r->flag != 0) r->err = r->mescd = NAN;
}

/* The best CPU time of reps runs (a run over 0.5 s is not repeated). */
static void Measure(int k, const Method *me, double tol, const double xref[3], int reps,
                    SuiteResult *r)
{
  int i;
  RunOnce(k, me, tol, xref, r);
  for (i = 1; i < reps && r->flag == 0 && r->cpu < 0.5; i++) {
    SuiteResult again;
    RunOnce(k, me, tol, xref, &again);
    if (again.cpu < r->cpu) r->cpu = again.cpu;
  }
}

/* ---- output --------------------------------------------------------------- */

typedef struct {
  int done;       /* 0: skipped (budget)  */
  double tol;
  SuiteResult r;
} Cell;

static void PrintTable(int k, Cell cells[][MAXTOLS], int ntol)
{
  int j, i;
  printf("\n%s: error = %s; rtol = atol = tol\n", PROBLEMS[k],
         strcmp(PROBLEMS[k], "pendulum") == 0
           ? "max position error over 4000 outputs (IFToMM A01; high precision <= 1e-3)"
           : "mixed position error at t_end (-log10: mescd)");
  printf("%-13s %7s %10s %10s %6s %8s %6s %8s %10s%s\n", "method", "tol", "error", "err/tol",
         "mescd", "steps", "rej", "LU", "CPU ms",
         strcmp(PROBLEMS[k], "pendulum") == 0 ? "  energy drift" : "");
  for (j = 0; j < NMETHODS; j++) {
    if (!MethodListed(method_list, METHODS[j].name)) continue;
    for (i = 0; i < ntol; i++) {
      const Cell *c = &cells[j][i];
      if (!c->done) {
        printf("%-13s %7.0e %10s (skipped: over the time budget)\n", METHODS[j].name, c->tol, "-");
        continue;
      }
      if (c->r.flag != 0) {
        printf("%-13s %7.0e %10s (failed: flag %d after %ld steps)\n", METHODS[j].name, c->tol,
               "-", c->r.flag, c->r.nsteps);
        continue;
      }
      printf("%-13s %7.0e %10.2e %10.3g %6.2f %8ld %6ld %8ld %10.3f", METHODS[j].name, c->tol,
             c->r.err, c->r.err / c->tol, c->r.mescd, c->r.nsteps, c->r.nrejected, c->r.nlu,
             1e3 * c->r.cpu);
      if (strcmp(PROBLEMS[k], "pendulum") == 0) printf("  %10.2e", c->r.energy_drift);
      printf("\n");
    }
  }
}

static void WriteCsv(FILE *fp, int k, Cell cells[][MAXTOLS], int ntol, const char *sundials)
{
  int j, i;
  for (j = 0; j < NMETHODS; j++)
    for (i = 0; i < ntol; i++) {
      const Cell *c = &cells[j][i];
      if (!c->done) continue;
      fprintf(fp, "%s,%s,%s,%.1e,%d,%.6e,%.4f,%.6e,%.6e,%ld,%ld,%ld,%ld,%.6e,%s\n",
              PROBLEMS[k], METHODS[j].ida ? "IDA" : "Lignum", METHODS[j].name, c->tol, c->r.flag,
              c->r.err, c->r.mescd, c->r.err_v, c->r.energy_drift, c->r.nsteps, c->r.nrejected,
              c->r.nlu, c->r.nniters, c->r.cpu, sundials);
    }
}

/* Two panels: error against CPU time, error against tol (with error = tol). */
static void WritePlot(const char *prefix, int k, Cell cells[][MAXTOLS], int ntol,
                      const char *sundials)
{
  char png[4096], script[4200];
  FILE *fp;
  int j, i, panel, first;
  snprintf(png, sizeof png, "%s_%s.png", prefix, PROBLEMS[k]);
  fp = bench_gnuplot_open("suite", png, script, sizeof script);
  if (fp == NULL) return;
  fprintf(fp, "set terminal pngcairo size 1400,600 font ',10'\nset output '%s'\n", png);
  for (j = 0; j < NMETHODS; j++) {
    fprintf(fp, "$m%d << EOD\n", j);
    for (i = 0; i < ntol; i++)
      if (cells[j][i].done && cells[j][i].r.flag == 0 && cells[j][i].r.err > 0.0)
        fprintf(fp, "%.3e %.6e %.6e\n", cells[j][i].tol, 1e3 * cells[j][i].r.cpu,
                cells[j][i].r.err);
    fprintf(fp, "EOD\n");
  }
  fprintf(fp, "set multiplot layout 1,2 title '%s: Lignum and IDA (SUNDIALS %s), rtol = atol = "
              "tol'\nset logscale xy\nset format xy '10^{%%L}'\nset grid\n"
              "set key top right\n",
          PROBLEMS[k], sundials);
  for (panel = 0; panel < 2; panel++) {
    fprintf(fp, "set xlabel '%s'\nset ylabel 'error'\n", panel == 0 ? "CPU time (ms)" : "tol");
    if (panel == 1) fprintf(fp, "set xrange [*:*] reverse\n");
    fprintf(fp, "plot ");
    for (j = 0, first = 1; j < NMETHODS; j++) {
      if (!MethodListed(method_list, METHODS[j].name)) continue;
      fprintf(fp, "%s$m%d using %d:3 with linespoints lw 2 title '%s'", first ? "" : ", ", j,
              panel == 0 ? 2 : 1, METHODS[j].name);
      first = 0;
    }
    if (panel == 1) fprintf(fp, ", x with lines dt 2 lc 'black' title 'error = tol'");
    fprintf(fp, "\n");
  }
  fprintf(fp, "unset multiplot\n");
  bench_gnuplot_run("suite", fp, script, png);
}

/* ---- main ----------------------------------------------------------------- */

static void Usage(const char *prog)
{
  printf("usage: %s [--problems a,b,...] [--tol-max T] [--tol-min T] [--reps N]\n"
         "          [--budget SECONDS] [--csv FILE] [--png PREFIX | --no-png]\n"
         "          [--methods \"IDA,BDF5 mN,...\"] [--expect-sundials debian|O2] [--verbose]\n"
         "  The standard multibody suite (bench/suite/README.md): problems andrews,\n"
         "  caraxis, pendulum, top, chain (default all); tol = tol-max, tol-max / 10,\n"
         "  ... tol-min (default 1e-3 ... 1e-12); CPU = best of N runs (default 3).\n"
         "  --methods: only the methods named (IDA, BDF5, BDF5 mN, BDF4, BDF4 mN,\n"
         "  gen-alpha, gen-alpha mN; default all). --verbose: one line per run on stderr.\n",
         prog);
}

int main(int argc, char **argv)
{
  const char *csv = "suite.csv", *prefix = "suite", *expect = NULL, *list = NULL;
  const char *sundials;
  double tol_max = 1e-3, tol_min = 1e-12, budget = 5.0, t1 = 1.0, tols[MAXTOLS];
  int reps = 3, ntol = 0, verbose = 0, i, j, k;
  LGNRefHeavyTop ref;
  FILE *fp;
  static Cell cells[NMETHODS][MAXTOLS];

  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--problems") == 0 && i + 1 < argc) list = argv[++i];
    else if (strcmp(argv[i], "--tol-max") == 0 && i + 1 < argc) tol_max = atof(argv[++i]);
    else if (strcmp(argv[i], "--tol-min") == 0 && i + 1 < argc) tol_min = atof(argv[++i]);
    else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) reps = atoi(argv[++i]);
    else if (strcmp(argv[i], "--budget") == 0 && i + 1 < argc) budget = atof(argv[++i]);
    else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csv = argv[++i];
    else if (strcmp(argv[i], "--png") == 0 && i + 1 < argc) prefix = argv[++i];
    else if (strcmp(argv[i], "--no-png") == 0) prefix = NULL;
    else if (strcmp(argv[i], "--methods") == 0 && i + 1 < argc) method_list = argv[++i];
    else if (strcmp(argv[i], "--verbose") == 0) verbose = 1;
    else if (strcmp(argv[i], "--expect-sundials") == 0 && i + 1 < argc) expect = argv[++i];
    else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
      Usage(argv[0]);
      return 0;
    } else {
      Usage(argv[0]);
      return 2;
    }
  }
  if (!(tol_max > 0.0 && tol_min > 0.0 && tol_min <= tol_max) || reps < 1 || reps > 100 ||
      !(budget > 0.0)) {
    fprintf(stderr, "suite: need 0 < tol-min <= tol-max, 1 <= reps <= 100, budget > 0\n");
    return 2;
  }
  for (ntol = 0; ntol < MAXTOLS; ntol++) { /* decades from tol_max down to tol_min */
    tols[ntol] = tol_max * pow(10.0, -ntol);
    if (tols[ntol] < tol_min * (1 - 1e-9)) break;
  }
  sundials = suite_sundials_build(stdout);
  printf("SUNDIALS build: %s\n", sundials);
  if (expect != NULL && strcmp(expect, sundials) != 0) {
    fprintf(stderr, "suite: expected the %s SUNDIALS build but loaded '%s'\n", expect, sundials);
    return 3;
  }
  if (lgnref_heavy_top(&t1, 1, &ref, LGNREF_FEHLBERG_8) != 0) {
    fprintf(stderr, "suite: the heavy top's reference failed\n");
    return 1;
  }
  fp = fopen(csv, "w");
  if (fp == NULL) {
    perror(csv);
    return 1;
  }
  fprintf(fp, "%s\n", CSV_HEADER);
  for (k = 0; k < NPROBLEMS; k++) {
    if (list != NULL && strstr(list, PROBLEMS[k]) == NULL) continue;
    for (j = 0; j < NMETHODS; j++) {
      int over = !MethodListed(method_list, METHODS[j].name);
      for (i = 0; i < ntol; i++) {
        Cell *c = &cells[j][i];
        c->tol = tols[i];
        c->done = !over;
        if (over) continue;
        Measure(k, &METHODS[j], tols[i], ref.x, reps, &c->r);
        if (c->r.cpu > budget) over = 1;
        if (verbose)
          fprintf(stderr, "suite: %s %s tol %.0e: flag %d, error %.2e, %.3f s\n", PROBLEMS[k],
                  METHODS[j].name, tols[i], c->r.flag, c->r.err, c->r.cpu);
      }
    }
    PrintTable(k, cells, ntol);
    WriteCsv(fp, k, cells, ntol, sundials);
    fflush(stdout);
    if (prefix != NULL) WritePlot(prefix, k, cells, ntol, sundials);
  }
  fclose(fp);
  printf("\nCSV: %s\n", csv);
  return 0;
}
