/* -----------------------------------------------------------------------------
 * Lignum benchmarks: work-precision diagram of the heavy top (spec numerics.md
 * §5) on t in [0, 1] s, Lignum against SUNDIALS IDA, in one process.
 *
 *   Lignum: every row of LIGNUM[] (heavy_top_run(), analytic Jacobians,
 *           default Newton tolerances) at h = 4e-3 * 2^-k, k = 0..7;
 *           the rows marked adaptive with error control (LGN_STEP_ADAPTIVE)
 *           at rtol = atol = 1e-3 .. 1e-8 instead.
 *   IDA:    the stabilised index-2 (GGL) Euler-parameter DAE of
 *           ida_heavy_top.c with every row of IDA[] (dense LU with IDA's
 *           difference-quotient Jacobian, dense LU with the analytic
 *           Jacobian, KLU with the analytic Jacobian) at rtol = 1e-3..1e-10.
 *
 * Error: |x(1) - x_ref(1)|_2, centre of mass at t = 1 s, against the
 * independent ARKODE reference (test/reference, Fehlberg 7(8)).  CPU time:
 * process CPU time (clock()) of the integration only, median of --reps runs
 * (failed runs are run once and recorded, not repeated).
 *
 * Output: CSV (--csv FILE, default work_precision.csv) with exactly the
 * header below; a table on stdout (per error level 1e-2 .. 1e-5 the CPU time
 * of the best Lignum method and of the best IDA set-up reaching it,
 * interpolated linearly in log(cpu) over log(err) on each method's curve,
 * and the ratio IDA / Lignum); the PASS/MISS lines of the targets of issue 6;
 * a PNG (--png FILE, default work_precision.png) drawn with gnuplot when it
 * is on PATH.  Error control: a table of error, steps and rejected steps
 * against the tolerance, with the steps and CPU time of the same method's
 * fixed step reaching the same error (interpolated on its curve), in
 * <csv>_adaptive.csv and, with gnuplot, <png>_adaptive.png (error and steps
 * against the tolerance).  Benchmarks report: the exit status never depends
 * on timing.
 *
 * --quick: a few settings (one repetition) and correctness checks of the IDA
 * model (consistent start, analytic Jacobian, convergence to the reference
 * as rtol decreases) and of Lignum; exit status 1 if a check fails (CTest).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>

#include "bench_gnuplot.h"
#include "ida_heavy_top.h"
#include "lgn_reference.h"
#include "models/heavy_top.h"

#define CSV_HEADER "solver,method,setting,err_com,cpu_s,steps,newton_iters,res_evals,jac_evals"
#define T_END 1.0

/* ---------------------------------------------------------------------------
 * Lignum configurations.  ** Add rows here to benchmark another option **
 * (e.g. a Newton variant: add a field, set it in LignumOptions() below).
 * Generalized-alpha rows use rho_inf = 0.9; Newmark rows beta = 1/4,
 * gamma = 1/2.  Exact kinematics only on the Lie group (on R^7 it is the
 * same method as the simplified one).
 * ------------------------------------------------------------------------- */
typedef struct {
  const char *name;
  int formulation; /* HeavyTopFormulation      */
  int method;      /* HeavyTopMethod           */
  int kinematics;  /* LGN_KINEMATICS_*         */
  int constraints; /* LGN_CONSTR_INDEX3 / 2    */
  int predictor;   /* LGN_PREDICTOR_*          */
  int newton;      /* LGN_NEWTON_*             */
  double tol_h2;   /* > 0: Newton rtol = atol = tol_h2 h^2 (else defaults 1e-8) */
  int adaptive;    /* 1: error control, the setting is rtol = atol */
} LignumSpec;

static const LignumSpec LIGNUM[] = {
  {"LGNM idx3 lie",          HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"LGNM idx2 lie",          HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"mod. LGNM idx3 lie",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"mod. LGNM idx2 lie",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"LGGalpha idx3 lie",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"LGGalpha idx2 lie",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"mod. LGGalpha idx3 lie", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"mod. LGGalpha idx2 lie", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"Newmark idx3 ep",        HT_EULER_PARAMETERS, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"Newmark idx2 ep",        HT_EULER_PARAMETERS, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"gen-alpha idx3 ep",      HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  {"gen-alpha idx2 ep",      HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0},
  /* modified Newton (LGNSetNewtonMode): reuse of the factorised matrix */
  {"mod. LGNM idx3 lie mN",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0},
  {"mod. LGNM idx2 lie mN",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0},
  {"LGGalpha idx3 lie mN",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0},
  {"mod. LGGalpha idx3 lie mN", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0},
  {"mod. LGGalpha idx2 lie mN", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0},
  {"gen-alpha idx3 ep mN",      HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0},
  /* ... with the Newton tolerance tied to the step: h^2, about 1/100 of the
   * global error of these second-order methods (the measured error decides) */
  {"mod. LGNM idx3 lie mN h2",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 1, 0},
  {"mod. LGGalpha idx3 lie mN h2", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 1, 0},
  {"mod. LGGalpha idx3 lie h2",    HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 1, 0},
  /* error control (LGNSetStepControl(LGN_STEP_ADAPTIVE)): tolerance sweep */
  {"LGGalpha idx3 lie EC",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1},
  {"mod. LGGalpha idx3 lie EC", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1},
  {"mod. LGNM idx3 lie EC",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1},
  {"LGGalpha idx2 lie EC",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1},
  {"gen-alpha idx3 ep EC",      HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1},
};
#define NLIGNUM ((int)(sizeof LIGNUM / sizeof LIGNUM[0]))

/* IDA set-ups (the tolerances and options are in IdaOptions()). */
typedef struct {
  const char *name;
  IdaHTLinSol linsol;
} IdaSpec;

static const IdaSpec IDA[] = {
  {"IDA GGL dense-DQ",  IDAHT_DENSE_DQ},
  {"IDA GGL dense-Jac", IDAHT_DENSE_JAC},
  {"IDA GGL KLU",       IDAHT_KLU},
};
#define NIDA ((int)(sizeof IDA / sizeof IDA[0]))

#define H0      4e-3 /* h_k = H0 * 2^-k, k = 0..NH-1 */
#define NH      8
#define RTOL0   1e-3 /* rtol_k = RTOL0 * 10^-k       */
#define NRTOL   8
#define TOL0    1e-3 /* error control: rtol = atol = TOL0 * 10^-(k/2) */
#define NTOL    11   /* 1e-3 .. 1e-8 */

static const double LEVELS[] = {1e-2, 1e-3, 1e-4, 1e-5};
#define NLEVELS 4

/* One run (one method at one setting). */
typedef struct {
  int ida;          /* 0: Lignum, 1: IDA          */
  int spec;         /* row of LIGNUM[] or IDA[]   */
  double setting;   /* h or rtol                  */
  int ok;
  int flag;
  double t;         /* time reached               */
  double err, cpu;  /* cpu: median over the reps  */
  long int steps, nni, nres, njac;
  long int netf, nncf; /* error control: rejected steps */
} Run;

static const char *MethodName(const Run *r)
{
  return r->ida ? IDA[r->spec].name : LIGNUM[r->spec].name;
}

static double WallSeconds(void)
{
  struct timespec ts;
  timespec_get(&ts, TIME_UTC);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int CmpDouble(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double Median(double *v, int n)
{
  qsort(v, (size_t)n, sizeof *v, CmpDouble);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static double ComErr(const double x[3], const LGNRefHeavyTop *ref)
{
  double d0 = x[0] - ref->x[0], d1 = x[1] - ref->x[1], d2 = x[2] - ref->x[2];
  return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

/* ---------------------------------------------------------------------------
 * Running
 * ------------------------------------------------------------------------- */

static void LignumOptions(const LignumSpec *s, double h, HeavyTopOptions *opt)
{
  heavy_top_default_options(opt);
  opt->formulation = (HeavyTopFormulation)s->formulation;
  opt->method = (HeavyTopMethod)s->method;
  opt->rho_inf = 0.9;
  opt->beta = 0.25;
  opt->gamma = 0.5;
  opt->kinematics = s->kinematics;
  opt->constraints = s->constraints;
  opt->predictor = s->predictor;
  opt->newton = s->newton;
  if (s->tol_h2 > 0.0) opt->rtol = opt->atol = s->tol_h2 * h * h;
  opt->h = h;
  if (s->adaptive) { /* h is the tolerance */
    opt->adaptive = 1;
    opt->rtol = opt->atol = h;
    opt->h = T_END;
  }
  opt->t_end = T_END;
  opt->analytic_jacobians = 1;
  opt->single_solve = 1; /* time the integration, not per-step output */
}

/* IDA set-up of the benchmark (see bench/README.md for the reasons):
 * atol = rtol * (1 for x and p, 5 for xdot, 75 for pdot, 1e3 for lambda and
 * mu), initial step 1e-6, everything else IDA's defaults (max order 5). */
static void IdaOptions(const IdaSpec *s, double rtol, IdaHTOptions *opt)
{
  ida_heavy_top_default_options(opt);
  opt->linsol = s->linsol;
  opt->rtol = rtol;
  opt->t_end = T_END;
  opt->scale_x = 1.0;
  opt->scale_p = 1.0;
  opt->scale_xd = 5.0;
  opt->scale_pd = 75.0;
  opt->scale_lambda = 1e3;
  opt->scale_mu = 1e3;
  opt->h0 = 1e-6;
}

/* One measurement; returns 1 if the run reached T_END. */
static int RunOnce(Run *r, const LGNRefHeavyTop *ref, double *cpu)
{
  if (!r->ida) {
    HeavyTopOptions opt;
    HeavyTopResult res;
    LignumOptions(&LIGNUM[r->spec], r->setting, &opt);
    heavy_top_run(&opt, &res);
    r->flag = res.flag;
    r->t = res.t;
    r->err = ComErr(res.x, ref);
    r->steps = res.nsteps;
    r->nni = res.nniters;
    r->nres = res.nres + res.ndq;
    r->njac = res.njevals;
    r->netf = res.netfails;
    r->nncf = res.nncfails;
    *cpu = res.cpu_seconds;
  } else {
    IdaHTOptions opt;
    IdaHTResult res;
    IdaOptions(&IDA[r->spec], r->setting, &opt);
    ida_heavy_top_run(&opt, &res);
    r->flag = res.flag;
    r->t = res.t;
    r->err = ComErr(res.x, ref);
    r->steps = res.nsteps;
    r->nni = res.nniters;
    r->nres = res.nres;
    r->njac = res.njevals;
    *cpu = res.cpu_seconds;
  }
  return r->flag == 0 && fabs(r->t - T_END) < 1e-12 && isfinite(r->err);
}

static void Measure(Run *r, const LGNRefHeavyTop *ref, int reps)
{
  double cpu[64], c;
  int i;
  if (reps > 64) reps = 64;
  r->ok = RunOnce(r, ref, &cpu[0]);
  if (!r->ok) {
    r->cpu = cpu[0];
    return;
  }
  for (i = 1; i < reps; i++) {
    Run again = *r;
    if (!RunOnce(&again, ref, &c)) break; /* cannot happen: deterministic */
    cpu[i] = c;
  }
  r->cpu = Median(cpu, i);
}

/* ---------------------------------------------------------------------------
 * Evaluation
 * ------------------------------------------------------------------------- */

typedef struct {
  double err, cpu;
} Point;

static int CmpPoint(const void *a, const void *b)
{
  const Point *x = a, *y = b;
  return (x->err > y->err) - (x->err < y->err);
}

/* CPU time of one method (runs r[0..n-1]) at error `level`: sort its ok runs
 * by error and interpolate log(cpu) linearly in log(err) between the two
 * neighbours that bracket the level.  Returns 0 if the curve does not reach
 * the level (no extrapolation). */
static int ValueAtLevel(const Run *r, int n, double level, int steps, double *cpu)
{
  Point p[64];
  int i, np = 0;
  for (i = 0; i < n && np < 64; i++)
    if (r[i].ok && r[i].err > 0.0 && r[i].cpu > 0.0) {
      p[np].err = r[i].err;
      p[np].cpu = steps ? (double)r[i].steps : r[i].cpu;
      np++;
    }
  qsort(p, (size_t)np, sizeof *p, CmpPoint);
  for (i = 0; i + 1 < np; i++)
    if (p[i].err <= level && level <= p[i + 1].err) {
      const double a = log(p[i].err), b = log(p[i + 1].err);
      const double w = b > a ? (log(level) - a) / (b - a) : 0.0;
      *cpu = exp((1.0 - w) * log(p[i].cpu) + w * log(p[i + 1].cpu));
      return 1;
    }
  if (np == 1 && p[0].err == level) {
    *cpu = p[0].cpu;
    return 1;
  }
  return 0;
}

static int CpuAtLevel(const Run *r, int n, double level, double *cpu)
{
  return ValueAtLevel(r, n, level, 0, cpu);
}

/* Best (smallest CPU) method of one solver at a level; returns the index of
 * the method's first run in runs[] via *first, or 0 if none reaches it. */
typedef struct {
  int first, n; /* runs[first .. first + n - 1] */
  int ida, spec;
} Curve;

static int Best(const Curve *cv, int ncv, const Run *runs, int ida, double level,
                double *cpu, int *which)
{
  int c, found = 0;
  for (c = 0; c < ncv; c++) {
    double t;
    if (cv[c].ida != ida) continue;
    if (CpuAtLevel(&runs[cv[c].first], cv[c].n, level, &t) && (!found || t < *cpu)) {
      *cpu = t;
      *which = c;
      found = 1;
    }
  }
  return found;
}

static int WriteCsv(const char *path, const Run *runs, int nruns)
{
  FILE *fp = fopen(path, "w");
  int i;
  if (fp == NULL) {
    perror(path);
    return -1;
  }
  fprintf(fp, "%s\n", CSV_HEADER);
  for (i = 0; i < nruns; i++) {
    const Run *r = &runs[i];
    fprintf(fp, "%s,%s,%g,",
            r->ida ? "ida" : LIGNUM[r->spec].adaptive ? "lignum-adaptive" : "lignum",
            MethodName(r), r->setting);
    if (r->ok) fprintf(fp, "%.6e", r->err);
    fprintf(fp, ",%.6e,%ld,%ld,%ld,%ld\n", r->cpu, r->steps, r->nni, r->nres, r->njac);
  }
  if (fclose(fp) != 0) {
    perror(path);
    return -1;
  }
  return 0;
}

static void PrintRuns(const Curve *cv, int ncv, const Run *runs)
{
  int c, k;
  printf("\n%-24s %9s  %10s  %10s  %7s  %6s  %7s  %6s\n", "method", "setting", "err_com",
         "cpu [ms]", "steps", "nni/st", "res", "jac");
  for (c = 0; c < ncv; c++)
    for (k = 0; k < cv[c].n; k++) {
      const Run *r = &runs[cv[c].first + k];
      char e[32];
      if (r->ok) snprintf(e, sizeof e, "%.3e", r->err);
      else snprintf(e, sizeof e, "F@%.3g", r->t);
      printf("%-24s %9.3g  %10s  %10.3f  %7ld  %6.2f  %7ld  %6ld%s\n", MethodName(r),
             r->setting, e, 1e3 * r->cpu, r->steps,
             r->steps > 0 ? (double)r->nni / (double)r->steps : 0.0, r->nres, r->njac,
             r->ok ? "" : (r->ida ? "  (IDA failed)" : "  (failed)"));
    }
}

/* The table of issue 6 and the PASS/MISS lines. */
static void PrintSummary(const Curve *cv, int ncv, const Run *runs)
{
  double ratio[NLEVELS];
  int have[NLEVELS], l, all = 1;
  printf("\nWork-precision summary: CPU time to reach |x(1) - x_ref(1)| = level\n"
         "(interpolated on each method's log-log curve; best = fastest method)\n");
  printf("%8s  %-24s %10s  %-20s %10s  %8s\n", "level", "best Lignum", "cpu [ms]",
         "best IDA", "cpu [ms]", "IDA/Lig");
  for (l = 0; l < NLEVELS; l++) {
    double cl = 0.0, ci = 0.0;
    int wl = -1, wi = -1;
    const int hl = Best(cv, ncv, runs, 0, LEVELS[l], &cl, &wl);
    const int hi = Best(cv, ncv, runs, 1, LEVELS[l], &ci, &wi);
    char sl[32] = "not reached", si[32] = "not reached", sr[32] = "-";
    if (hl) snprintf(sl, sizeof sl, "%.3f", 1e3 * cl);
    if (hi) snprintf(si, sizeof si, "%.3f", 1e3 * ci);
    have[l] = hl && hi;
    if (have[l]) {
      ratio[l] = ci / cl;
      snprintf(sr, sizeof sr, "%.2f", ratio[l]);
    }
    printf("%8.0e  %-24s %10s  %-20s %10s  %8s\n", LEVELS[l],
           hl ? LIGNUM[cv[wl].spec].name : "-", sl, hi ? IDA[cv[wi].spec].name : "-", si, sr);
  }
  printf("\nTargets of issue 6 (reported, never enforced):\n");
  if (have[1])
    printf("  %s  Lignum's best at least 5x faster than IDA's best at error 1e-3: factor %.2f\n",
           ratio[1] >= 5.0 ? "PASS" : "MISS", ratio[1]);
  else
    printf("  MISS  Lignum's best at least 5x faster than IDA's best at error 1e-3: "
           "level not reached by both\n");
  for (l = 0; l < NLEVELS; l++)
    if (!have[l] || !(ratio[l] > 1.0)) all = 0;
  printf("  %s  Lignum faster at every level 1e-2 .. 1e-5: factors", all ? "PASS" : "MISS");
  for (l = 0; l < NLEVELS; l++) {
    if (have[l]) printf(" %.0e: %.2f", LEVELS[l], ratio[l]);
    else printf(" %.0e: -", LEVELS[l]);
    printf(l + 1 < NLEVELS ? ";" : "\n");
  }
}

static const char *const COLOURS[] = {"#9400d3", "#009e73", "#56b4e9", "#e69f00",
                                      "#d62728", "#0072b2", "#8c564b", "#cc79a7"};
#define NCOLOURS ((int)(sizeof COLOURS / sizeof COLOURS[0]))

/* path with its extension ext replaced by suffix + ext ("a.csv" ->
 * "a_adaptive.csv"; without ext: appended) */
static void SiblingPath(const char *path, const char *suffix, const char *ext, char *out,
                        size_t len)
{
  const size_t n = strlen(path), ne = strlen(ext);
  if (n >= ne && strcmp(path + n - ne, ext) == 0)
    snprintf(out, len, "%.*s%s%s", (int)(n - ne), path, suffix, ext);
  else
    snprintf(out, len, "%s%s%s", path, suffix, ext);
}

/* The fixed-step curve of the same method as the adaptive curve c (-1: none). */
static int FixedTwin(const Curve *cv, int ncv, int c)
{
  const LignumSpec *a = &LIGNUM[cv[c].spec];
  int d;
  for (d = 0; d < ncv; d++) {
    const LignumSpec *b;
    if (cv[d].ida) continue;
    b = &LIGNUM[cv[d].spec];
    if (!b->adaptive && b->tol_h2 == 0.0 && b->formulation == a->formulation &&
        b->method == a->method && b->kinematics == a->kinematics &&
        b->constraints == a->constraints && b->newton == a->newton &&
        b->predictor == a->predictor)
      return d;
  }
  return -1;
}

/* Error control: error, steps and rejections against the tolerance, and
 * the steps and CPU time of the same method's fixed step at the same
 * error (interpolated on its curve; "-" outside it). Writes path. */
static int PrintAdaptive(const Curve *cv, int ncv, const Run *runs, const char *path)
{
  FILE *fp = fopen(path, "w");
  int c, k;
  if (fp == NULL) {
    perror(path);
    return -1;
  }
  fprintf(fp, "method,tol,err_com,steps,err_test_fails,newton_fails,cpu_s,"
              "fixed_steps_same_err,fixed_cpu_s_same_err\n");
  printf("\nError control: error at t = 1 and steps against rtol = atol; the same\n"
         "method with a fixed step of the same error (interpolated on its curve)\n");
  printf("%-26s %8s  %10s  %6s  %5s  %4s  %8s  %9s  %9s\n", "method", "tol", "err_com",
         "steps", "rej.", "ncf", "cpu [ms]", "fix steps", "fix [ms]");
  for (c = 0; c < ncv; c++) {
    const int twin = cv[c].ida || !LIGNUM[cv[c].spec].adaptive ? -2 : FixedTwin(cv, ncv, c);
    if (twin == -2) continue;
    for (k = 0; k < cv[c].n; k++) {
      const Run *r = &runs[cv[c].first + k];
      double fs = 0.0, fc = 0.0;
      int have = 0;
      char e[32], s1[32] = "-", s2[32] = "-";
      if (r->ok && twin >= 0)
        have = ValueAtLevel(&runs[cv[twin].first], cv[twin].n, r->err, 1, &fs) &&
               ValueAtLevel(&runs[cv[twin].first], cv[twin].n, r->err, 0, &fc);
      if (r->ok) snprintf(e, sizeof e, "%.3e", r->err);
      else snprintf(e, sizeof e, "F@%.3g", r->t);
      if (have) {
        snprintf(s1, sizeof s1, "%.0f", fs);
        snprintf(s2, sizeof s2, "%.3f", 1e3 * fc);
      }
      printf("%-26s %8.2e  %10s  %6ld  %5ld  %4ld  %8.3f  %9s  %9s\n", MethodName(r),
             r->setting, e, r->steps, r->netf, r->nncf, 1e3 * r->cpu, s1, s2);
      fprintf(fp, "%s,%g,", MethodName(r), r->setting);
      if (r->ok) fprintf(fp, "%.6e", r->err);
      fprintf(fp, ",%ld,%ld,%ld,%.6e,", r->steps, r->netf, r->nncf, r->cpu);
      if (have) fprintf(fp, "%.0f,%.6e", fs, fc);
      else fprintf(fp, ",");
      fprintf(fp, "\n");
    }
  }
  if (fclose(fp) != 0) {
    perror(path);
    return -1;
  }
  return 0;
}

/* The figure of error control: error and steps against the tolerance. */
static void WriteAdaptivePlot(const char *png, const char *csv, const Curve *cv, int ncv)
{
  char script[4200];
  FILE *fp;
  int c, first = 1;
  fp = bench_gnuplot_open("work_precision", png, script, sizeof script);
  if (fp == NULL) return;
  fprintf(fp,
          "# Heavy top, error control (generated by work_precision).\n"
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
          "  set terminal pngcairo size 1200,520 enhanced font 'sans,10'\n"
          "} else {\n"
          "  set terminal png size 1200,520\n"
          "}\n"
          "set output '%s'\n"
          "set datafile separator ','\n"
          "set logscale xy\nset grid\nset format x '10^{%%L}'\nset format y '10^{%%L}'\n"
          "set xlabel 'rtol = atol'\nset key top left font ',9'\n"
          "set multiplot layout 1,2 title 'Heavy top on [0, 1] s with error control "
          "(LGN\\_STEP\\_ADAPTIVE)'\n"
          "set ylabel 'error of the centre of mass at t = 1 s [m]'\n"
          "plot ",
          png);
  for (c = 0; c < ncv; c++) {
    if (cv[c].ida || !LIGNUM[cv[c].spec].adaptive) continue;
    fprintf(fp, "%s'%s' using (strcol(1) eq '%s' ? $2 : NaN):3 with linespoints lw 2 pt 7 "
                "lc rgb '%s' title '%s'",
            first ? "" : ", ", csv, LIGNUM[cv[c].spec].name,
            COLOURS[cv[c].spec % NCOLOURS], LIGNUM[cv[c].spec].name);
    first = 0;
  }
  fprintf(fp, "\nset ylabel 'steps'\nplot ");
  first = 1;
  for (c = 0; c < ncv; c++) {
    if (cv[c].ida || !LIGNUM[cv[c].spec].adaptive) continue;
    fprintf(fp, "%s'%s' using (strcol(1) eq '%s' ? $2 : NaN):4 with linespoints lw 2 pt 7 "
                "lc rgb '%s' title '%s', "
                "'%s' using (strcol(1) eq '%s' ? $2 : NaN):8 with linespoints dt 2 lw 1.5 "
                "pt 6 lc rgb '%s' title 'fixed h, same error'",
            first ? "" : ", ", csv, LIGNUM[cv[c].spec].name, COLOURS[cv[c].spec % NCOLOURS],
            LIGNUM[cv[c].spec].name, csv, LIGNUM[cv[c].spec].name,
            COLOURS[cv[c].spec % NCOLOURS]);
    first = 0;
  }
  fprintf(fp, "\nunset multiplot\n");
  bench_gnuplot_run("work_precision", fp, script, png);
}

/* ---------------------------------------------------------------------------
 * The figure (gnuplot): CPU time against error, log-log, one curve per method
 * ------------------------------------------------------------------------- */


static void WritePlot(const char *png, const Curve *cv, int ncv, const Run *runs)
{
  char script[4096];
  FILE *fp;
  int c, k;

  fp = bench_gnuplot_open("work_precision", png, script, sizeof script);
  if (fp == NULL) return;
  fprintf(fp, "# Heavy top work-precision diagram (generated by work_precision).\n");
  fprintf(fp, "$wp << EOD\n");
  for (c = 0; c < ncv; c++) {
    Point p[64];
    int np = 0, i;
    for (k = 0; k < cv[c].n && np < 64; k++) {
      const Run *r = &runs[cv[c].first + k];
      if (r->ok && r->err > 0.0 && r->cpu > 0.0) {
        p[np].err = r->err;
        p[np].cpu = r->cpu;
        np++;
      }
    }
    qsort(p, (size_t)np, sizeof *p, CmpPoint);
    fprintf(fp, "# %s\n", cv[c].ida ? IDA[cv[c].spec].name : LIGNUM[cv[c].spec].name);
    for (i = 0; i < np; i++) fprintf(fp, "%.6e %.6e\n", p[i].err, 1e3 * p[i].cpu);
    fprintf(fp, "NaN NaN\n\n\n"); /* keeps all-failed curves as valid blocks */
  }
  fprintf(fp, "EOD\n");
  for (c = 0; c < ncv; c++) {
    if (cv[c].ida)
      fprintf(fp, "set style line %d lc rgb '%s' dt 2 lw 3 pt %d ps 1.3\n", c + 1,
              cv[c].spec == 0 ? "#000000" : cv[c].spec == 1 ? "#555555" : "#999999",
              4 + 2 * cv[c].spec);
    else if (LIGNUM[cv[c].spec].adaptive) /* error control: thick dash-dot */
      fprintf(fp, "set style line %d lc rgb '%s' dt 4 lw 3.5 pt 9 ps 1.3\n", c + 1,
              COLOURS[cv[c].spec % NCOLOURS]);
    else
      fprintf(fp, "set style line %d lc rgb '%s' dt %d lw 2 pt %d ps 1.0\n", c + 1,
              COLOURS[cv[c].spec / 2 % NCOLOURS],
              LIGNUM[cv[c].spec].constraints == LGN_CONSTR_INDEX3 ? 1 : 3,
              LIGNUM[cv[c].spec].constraints == LGN_CONSTR_INDEX3 ? 7 : 6);
  }
  fprintf(fp, "array names[%d]\n", ncv);
  for (c = 0; c < ncv; c++)
    fprintf(fp, "names[%d] = \"%s\"\n", c + 1,
            cv[c].ida ? IDA[cv[c].spec].name : LIGNUM[cv[c].spec].name);
  fprintf(fp,
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
          "  set terminal pngcairo size 1100,800 enhanced font 'sans,10'\n"
          "} else {\n"
          "  set terminal png size 1100,800\n"
          "}\n"
          "set output '%s'\n"
          "set title 'Heavy top on [0, 1] s: work-precision (Lignum h = 4e-3..3.1e-5, "
          "EC: error control tol = 1e-3..1e-8, IDA rtol = 1e-3..1e-10; median CPU time)'\n"
          "set logscale xy\n"
          "set format x '10^{%%L}'\n"
          "set format y '10^{%%L}'\n"
          "set xlabel 'error of the centre of mass at t = 1 s [m]'\n"
          "set ylabel 'CPU time [ms]'\n"
          "set key outside right top font ',9' spacing 1.1\n"
          "set grid\n"
          "plot for [i=0:%d] $wp index i using 1:2 with linespoints ls i+1 "
          "title names[i+1]\n",
          png, ncv - 1);
  bench_gnuplot_run("work_precision", fp, script, png);
}

/* ---------------------------------------------------------------------------
 * --quick: correctness checks (CTest bench_work_precision_quick)
 * ------------------------------------------------------------------------- */

static int Check(int cond, const char *what)
{
  printf("  %-4s %s\n", cond ? "ok" : "FAIL", what);
  return cond ? 0 : 1;
}

static int QuickChecks(const LGNRefHeavyTop *ref)
{
  /* spec §5: lambda0 = (0, -319.525988166, -317.2624615385) */
  const double lam0[3] = {0.0, -319.525988166, -317.2624615385};
  const double rtols[4] = {1e-4, 1e-6, 1e-8, 1e-10};
  double y0[IDAHT_N], yp0[IDAHT_N], rn, jerr, dl, prev = INFINITY, err_ida[3];
  char msg[160];
  int fails = 0, i, k;

  printf("Quick checks\n");
  fails += Check(ida_heavy_top_initial(y0, yp0, &rn) == 0, "IDA: consistent initial values computed");
  snprintf(msg, sizeof msg, "IDA: max|F(0, y0, y'0)| = %.2e < 1e-10", rn);
  fails += Check(rn < 1e-10, msg);
  dl = 0.0;
  for (i = 0; i < 3; i++) dl = fmax(dl, fabs(y0[IDAHT_OL + i] - lam0[i]));
  snprintf(msg, sizeof msg, "IDA: lambda0 of the joint equals spec §5 (max diff %.2e < 1e-6)", dl);
  fails += Check(dl < 1e-6, msg);
  for (i = 0; i < 2; i++) {
    const double cj = i == 0 ? 1.0 : 1e4;
    jerr = ida_heavy_top_check_jacobian(cj);
    snprintf(msg, sizeof msg,
             "IDA: analytic Jacobian = central differences (c_j = %g, rel. diff %.1e < 1e-7)", cj, jerr);
    fails += Check(jerr < 1e-7, msg);
  }

  /* IDA dense-Jac converges to the reference as rtol decreases */
  for (k = 0; k < 4; k++) {
    Run r;
    double cpu;
    memset(&r, 0, sizeof r);
    r.ida = 1;
    r.spec = 1; /* dense-Jac */
    r.setting = rtols[k];
    r.ok = RunOnce(&r, ref, &cpu);
    snprintf(msg, sizeof msg, "IDA dense-Jac rtol %.0e: reaches t = 1, err %.3e < previous %.3e",
             rtols[k], r.ok ? r.err : NAN, prev);
    fails += Check(r.ok && r.err < prev, msg);
    if (r.ok) prev = r.err;
  }
  snprintf(msg, sizeof msg, "IDA dense-Jac rtol 1e-10: err %.3e < 1e-6", prev);
  fails += Check(prev < 1e-6, msg);

  /* the three linear solvers agree (same method, same tolerances) */
  for (k = 0; k < NIDA; k++) {
    Run r;
    double cpu;
    memset(&r, 0, sizeof r);
    r.ida = 1;
    r.spec = k;
    r.setting = 1e-7;
    r.ok = RunOnce(&r, ref, &cpu);
    err_ida[k] = r.ok ? r.err : NAN;
    snprintf(msg, sizeof msg, "%s rtol 1e-7: err %.3e < 1e-3", IDA[k].name, err_ida[k]);
    fails += Check(r.ok && r.err < 1e-3, msg);
  }

  /* Lignum: second order and within the known error levels (README table) */
  for (k = 0; k < NLIGNUM; k++) {
    const LignumSpec *s = &LIGNUM[k];
    Run a, b;
    double cpu;
    if (s->adaptive) continue; /* checked below */
    if (!(s->method == HT_GENALPHA && s->constraints == LGN_CONSTR_INDEX3) &&
        !(s->kinematics == LGN_KINEMATICS_EXACT && s->constraints == LGN_CONSTR_INDEX3))
      continue;
    memset(&a, 0, sizeof a);
    a.spec = k;
    a.setting = 1e-3;
    b = a;
    b.setting = 5e-4;
    a.ok = RunOnce(&a, ref, &cpu);
    b.ok = RunOnce(&b, ref, &cpu);
    snprintf(msg, sizeof msg, "%s: err(h=1e-3) = %.3e < 1e-2, err(5e-4) = %.3e, ratio %.2f > 3",
             s->name, a.err, b.err, a.err / b.err);
    fails += Check(a.ok && b.ok && a.err < 1e-2 && a.err / b.err > 3.0, msg);
  }
  /* error control: reaches t = 1, the error and the steps follow the
   * tolerance */
  for (k = 0; k < NLIGNUM; k++) {
    const double tols[3] = {1e-3, 1e-5, 1e-7};
    double e_prev = INFINITY, cpu;
    long int s_prev = 0;
    int j;
    if (!LIGNUM[k].adaptive || LIGNUM[k].kinematics != LGN_KINEMATICS_SIMPLIFIED ||
        LIGNUM[k].constraints != LGN_CONSTR_INDEX3 || LIGNUM[k].formulation != HT_LIE)
      continue;
    for (j = 0; j < 3; j++) {
      Run r;
      memset(&r, 0, sizeof r);
      r.spec = k;
      r.setting = tols[j];
      r.ok = RunOnce(&r, ref, &cpu);
      snprintf(msg, sizeof msg, "%s tol %.0e: reaches t = 1, err %.3e < %.3e, steps %ld > %ld",
               LIGNUM[k].name, tols[j], r.err, e_prev, r.steps, s_prev);
      fails += Check(r.ok && r.err < e_prev && r.steps > s_prev, msg);
      e_prev = r.err;
      s_prev = r.steps;
    }
    snprintf(msg, sizeof msg, "%s tol 1e-7: err %.3e < 1e-2", LIGNUM[k].name, e_prev);
    fails += Check(e_prev < 1e-2, msg);
  }
  printf("%s\n", fails ? "Quick checks FAILED" : "Quick checks passed");
  return fails;
}

/* ---------------------------------------------------------------------------
 * main
 * ------------------------------------------------------------------------- */

static void Usage(const char *prog)
{
  printf("usage: %s [--quick] [--reps N] [--csv FILE] [--png FILE | --no-png]\n"
         "  Heavy top work-precision: Lignum (h = 4e-3 * 2^-k, k = 0..7) against\n"
         "  IDA (GGL, rtol = 1e-3 .. 1e-10); CPU time = median of N runs (default 5).\n"
         "  --quick: correctness checks and a few settings, one run each.\n",
         prog);
}

int main(int argc, char **argv)
{
  const char *csv = "work_precision.csv", *png = "work_precision.png";
  int quick = 0, reps = 5, i, k, c, nruns = 0, ncv = 0, nh, nrt, ntol, fails = 0;
  double t1 = T_END, t_start = WallSeconds();
  LGNRefHeavyTop ref;
  Run *runs;
  Curve cv[NLIGNUM + NIDA];

  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--quick") == 0) quick = 1;
    else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csv = argv[++i];
    else if (strcmp(argv[i], "--png") == 0 && i + 1 < argc) png = argv[++i];
    else if (strcmp(argv[i], "--no-png") == 0) png = NULL;
    else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) reps = atoi(argv[++i]);
    else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
      Usage(argv[0]);
      return 0;
    } else {
      Usage(argv[0]);
      return 2;
    }
  }
  if (reps < 1 || reps > 64) {
    fprintf(stderr, "work_precision: --reps must be in 1..64\n");
    return 2;
  }
  if (quick) reps = 1;
  nh = quick ? 3 : NH;     /* quick: h = 4e-3, 2e-3, 1e-3     */
  nrt = quick ? 3 : NRTOL; /* quick: rtol = 1e-3, 1e-4, 1e-5  */
  ntol = quick ? 3 : NTOL;  /* quick: tol = 1e-3, 1e-4, 1e-5   */

  if (lgnref_heavy_top(&t1, 1, &ref, LGNREF_FEHLBERG_8) != 0) {
    fprintf(stderr, "work_precision: reference solution failed\n");
    return 1;
  }
  printf("Heavy top work-precision, t in [0, %g] s; error = |x(1) - x_ref(1)|_2 against\n"
         "ARKODE Fehlberg 7(8) (test/reference); CPU = median of %d run(s), process CPU time\n"
         "of the integration only.\n", T_END, reps);
  if (quick) fails = QuickChecks(&ref);

  runs = calloc((size_t)(NLIGNUM * (NH > NTOL ? NH : NTOL) + NIDA * NRTOL), sizeof *runs);
  if (runs == NULL) {
    fprintf(stderr, "work_precision: out of memory\n");
    return 1;
  }
  for (c = 0; c < NLIGNUM; c++) {
    const int adaptive = LIGNUM[c].adaptive;
    cv[ncv].first = nruns;
    cv[ncv].n = adaptive ? ntol : nh;
    cv[ncv].ida = 0;
    cv[ncv++].spec = c;
    for (k = 0; k < (adaptive ? ntol : nh); k++) {
      Run *r = &runs[nruns++];
      r->spec = c;
      /* quick: 1e-3, 1e-4, 1e-5 */
      r->setting = adaptive ? TOL0 * pow(10.0, -0.5 * (quick ? 2 * k : k))
                            : H0 / (double)(1L << k);
    }
  }
  for (c = 0; c < NIDA; c++) {
    cv[ncv].first = nruns;
    cv[ncv].n = nrt;
    cv[ncv].ida = 1;
    cv[ncv++].spec = c;
    for (k = 0; k < nrt; k++) {
      Run *r = &runs[nruns++];
      r->ida = 1;
      r->spec = c;
      r->setting = RTOL0 * pow(10.0, -k);
    }
  }
  for (i = 0; i < nruns; i++) Measure(&runs[i], &ref, reps);

  if (WriteCsv(csv, runs, nruns) != 0) fails++;
  PrintRuns(cv, ncv, runs);
  PrintSummary(cv, ncv, runs);
  {
    char acsv[4096], apng[4096];
    SiblingPath(csv, "_adaptive", ".csv", acsv, sizeof acsv);
    if (PrintAdaptive(cv, ncv, runs, acsv) != 0) fails++;
    printf("\nCSV: %s, %s\n", csv, acsv);
    fflush(stdout);
    if (png != NULL && !quick) {
      WritePlot(png, cv, ncv, runs);
      SiblingPath(png, "_adaptive", ".png", apng, sizeof apng);
      WriteAdaptivePlot(apng, acsv, cv, ncv);
    }
  }
  printf("Total wall time %.1f s\n", WallSeconds() - t_start);
  free(runs);
  return fails ? 1 : 0;
}
