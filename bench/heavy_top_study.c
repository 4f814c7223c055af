/* -----------------------------------------------------------------------------
 * Lignum benchmarks: accuracy study of the heavy top (doc/accuracy-study.md).
 *
 * Runs the heavy top on t in [0, 1] s with every method of METHODS[] below,
 * index 3 and index 2, rho_inf in {0.6, 0.9} for the generalized-alpha
 * methods (Newmark: beta = 1/4, gamma = 1/2, undamped), at
 * h = 2e-3 * 2^-k, k = 0..5, Newton tolerances rtol = atol = 1e-10, and
 * compares with the independent ARKODE reference (models/lgn_reference.c,
 * Fehlberg 7(8), table 1).  Everything goes through heavy_top_run().
 *
 * Output
 *   CSV (--csv FILE, default heavy_top_study.csv), exactly the columns
 *     method,constraints,rho_inf,h,err_com,err_rot,err_omega,err_lambda,
 *     err_com_max,newton_per_step,steps,status
 *   - constraints: 3 or 2 (index);  rho_inf: empty for Newmark methods;
 *   - err_com    = |x(1) - x_ref(1)|_2       (centre of mass, m)
 *     err_rot    = ||log(R_ref(1)^T R(1))||  (rotation angle, rad)
 *     err_omega  = |Omega(1) - Omega_ref(1)|_2 (body frame, rad/s)
 *     err_lambda = |lambda(1) - lambda_ref(1)|_2 (Phi = X - R^T x, N)
 *     err_com_max = max_k |x(t_k) - x_ref(t_k)|_2 over the COARSEST grid
 *       t_k = k * 2e-3, k = 0..500: the reference is computed once on that
 *       grid and every run is compared at those points (every 2^k-th point
 *       of its own grid, which hits them exactly since h is 2e-3 divided by
 *       a power of two).  All runs are thus measured on the same 501 points;
 *     errors are absolute;
 *   - newton_per_step = Newton iterations / steps taken (also for failed
 *     runs, over the steps done); steps = steps taken;
 *   - status: "ok" or the Lignum flag name (LGNGetReturnFlagName); failed
 *     runs leave the five err_* columns empty.
 *   Table on stdout per method / constraints / rho_inf (observed orders
 *   between successive h, ratio err_com / err_com of mod-lgnm resp.
 *   mod-lggalpha with the same constraints, rho_inf and h), a summary, and
 *   a two-panel PNG (--png FILE, default heavy_top_study.png) drawn with
 *   gnuplot if it is on PATH (script FILE.gp written next to it).
 *
 * Options: --csv FILE, --png FILE, --no-png, --quick (k = 0..2, rho 0.9).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>

#include "bench_gnuplot.h"
#include "models/heavy_top.h"
#include "lgn_reference.h"

#define CSV_HEADER                                                          \
  "method,constraints,rho_inf,h,err_com,err_rot,err_omega,err_lambda,"      \
  "err_com_max,newton_per_step,steps,status"

#define H0       2e-3 /* coarsest step size; h_k = H0 * 2^-k        */
#define NK_FULL  6    /* k = 0..5                                   */
#define NK_QUICK 3    /* k = 0..2                                   */
#define T_END    1.0
#define NGRID    500  /* coarsest grid: t_k = k * H0, k = 0..NGRID  */
#define NEWTON_TOL 1e-10

/* ---------------------------------------------------------------------------
 * The methods.  ** Compile-time list: add rows here to extend the study. **
 * Name, formulation (models/heavy_top.h), Newmark or
 * generalized-alpha, kinematics.  The ratio column compares each method with
 * "mod-lgnm" (Newmark) resp. "mod-lggalpha" (generalized-alpha); the figure
 * and the table follow this order.
 * ------------------------------------------------------------------------- */
typedef struct {
  const char *name;
  int formulation; /* HeavyTopFormulation */
  int method;      /* HeavyTopMethod      */
  int kinematics;  /* LGN_KINEMATICS_*    */
} MethodSpec;


/* The differentiation index (3 or 2) of a LGN_CONSTR_INDEX* constant, as
 * the CSV and the tables write it. */
static int IndexNumber(int constraints)
{
  return constraints == LGN_CONSTR_INDEX3 ? 3 : 2;
}

static const MethodSpec METHODS[] = {
  {"newmark-ep",     HT_EULER_PARAMETERS, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED},
  {"genalpha-ep",    HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED},
  {"lgnm",           HT_LIE,              HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED},
  {"lggalpha",       HT_LIE,              HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED},
  {"mod-lgnm",       HT_LIE,              HT_NEWMARK,  LGN_KINEMATICS_EXACT},
  {"mod-lggalpha",   HT_LIE,              HT_GENALPHA, LGN_KINEMATICS_EXACT},
  {"sigma-lgnm",     HT_LIE,              HT_NEWMARK,  LGN_KINEMATICS_SIGMA},
  {"sigma-lggalpha", HT_LIE,              HT_GENALPHA, LGN_KINEMATICS_SIGMA},
  /* the same on SE(3) */
  {"se3-lgnm",           HT_SE3, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED},
  {"se3-lggalpha",       HT_SE3, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED},
  {"se3-mod-lgnm",       HT_SE3, HT_NEWMARK,  LGN_KINEMATICS_EXACT},
  {"se3-mod-lggalpha",   HT_SE3, HT_GENALPHA, LGN_KINEMATICS_EXACT},
  {"se3-sigma-lgnm",     HT_SE3, HT_NEWMARK,  LGN_KINEMATICS_SIGMA},
  {"se3-sigma-lggalpha", HT_SE3, HT_GENALPHA, LGN_KINEMATICS_SIGMA},
};
#define NMETHODS ((int)(sizeof METHODS / sizeof METHODS[0]))

static const int CONSTRAINTS[] = {LGN_CONSTR_INDEX3, LGN_CONSTR_INDEX2};
#define NCONSTR 2
static const double RHOS[] = {0.6, 0.9};
#define NRHO 2

/* One run of the study. */
typedef struct {
  int method;      /* index into METHODS */
  int constraints; /* 3 or 2             */
  double rho;      /* < 0: Newmark       */
  int k;           /* h = H0 * 2^-k      */
  double h;
  int flag;
  double t;        /* time reached       */
  double err_com, err_rot, err_omega, err_lambda, err_com_max;
  double newton_per_step;
  long int steps;
  double seconds;
} Run;

/* A configuration (method, constraints, rho): runs[first .. first+nk-1]. */
typedef struct {
  int method, constraints;
  double rho;
  int first;
} Config;

static double Norm3Diff(const double a[3], const double b[3])
{
  double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

static double WallSeconds(void)
{
  struct timespec ts;
  timespec_get(&ts, TIME_UTC);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int IsNewmark(int method) { return METHODS[method].method == HT_NEWMARK; }

/* Character loop rather than strcmp: gcc -O3 -Wstring-compare misreads the
 * constant table here and warns falsely. */
static int SameName(const char *a, const char *b)
{
  while (*a != '\0' && *a == *b) {
    a++;
    b++;
  }
  return *a == *b;
}

static int FindMethod(const char *name)
{
  int i;
  for (i = 0; i < NMETHODS; i++)
    if (SameName(METHODS[i].name, name)) return i;
  return -1;
}

/* Run one configuration at one step size and measure its errors. */
static void RunOne(Run *r, const LGNRefHeavyTop *ref)
{
  const MethodSpec *ms = &METHODS[r->method];
  const long int stride = 1L << r->k;
  const long int npts = NGRID * stride + 1;
  HeavyTopOptions opt;
  HeavyTopResult res;
  double *hist, t0;
  long int i;

  heavy_top_default_options(&opt);
  opt.formulation = (HeavyTopFormulation)ms->formulation;
  opt.method = (HeavyTopMethod)ms->method;
  opt.rho_inf = r->rho >= 0.0 ? r->rho : 1.0;
  opt.beta = 0.25;
  opt.gamma = 0.5;
  opt.constraints = r->constraints;
  opt.kinematics = ms->kinematics;
  opt.h = r->h;
  opt.t_end = T_END;
  opt.rtol = NEWTON_TOL;
  opt.atol = NEWTON_TOL;
  hist = malloc(3 * (size_t)npts * sizeof *hist);
  opt.com_history = hist;
  opt.history_len = hist ? npts : 0;

  t0 = WallSeconds();
  heavy_top_run(&opt, &res);
  r->seconds = WallSeconds() - t0;

  r->flag = res.flag;
  r->t = res.t;
  r->steps = res.nsteps;
  r->newton_per_step = res.nsteps > 0 ? (double)res.nniters / (double)res.nsteps : 0.0;
  r->err_com = r->err_rot = r->err_omega = r->err_lambda = r->err_com_max = NAN;
  if (hist == NULL) {
    if (r->flag == LGN_SUCCESS) r->flag = LGN_MEM_FAIL;
    return;
  }
  if (r->flag == LGN_SUCCESS) {
    /* a successful run must have reached t_end on the full grid */
    if (res.history_points != npts || fabs(res.t - T_END) > 1e-12) {
      r->flag = LGN_UNRECOGNIZED_ERR;
    } else {
      const LGNRefHeavyTop *e = &ref[NGRID];
      double emax = 0.0;
      r->err_com = Norm3Diff(res.x, e->x);
      r->err_rot = lgnref_rotation_error(e->R, res.R);
      r->err_omega = Norm3Diff(res.Omega, e->Omega);
      r->err_lambda = Norm3Diff(res.lambda, e->lambda);
      for (i = 0; i <= NGRID; i++) {
        double d = Norm3Diff(hist + 3 * i * stride, ref[i].x);
        if (!(d <= emax)) emax = d; /* NaN propagates */
      }
      r->err_com_max = emax;
      if (!isfinite(r->err_com) || !isfinite(r->err_rot) ||
          !isfinite(r->err_omega) || !isfinite(r->err_lambda) || !isfinite(emax)) {
        r->flag = LGN_NONFINITE;
        r->err_com = r->err_rot = r->err_omega = r->err_lambda = r->err_com_max = NAN;
      }
    }
  }
  free(hist);
}

static const char *StatusName(int flag)
{
  return flag == LGN_SUCCESS ? "ok" : LGNGetReturnFlagName(flag);
}

static void CsvNum(FILE *fp, double v, int ok)
{
  if (ok) fprintf(fp, "%.6e", v);
  fputc(',', fp);
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
    const int ok = r->flag == LGN_SUCCESS;
    fprintf(fp, "%s,%d,", METHODS[r->method].name, IndexNumber(r->constraints));
    if (r->rho >= 0.0) fprintf(fp, "%.1f", r->rho);
    fprintf(fp, ",%.6e,", r->h);
    CsvNum(fp, r->err_com, ok);
    CsvNum(fp, r->err_rot, ok);
    CsvNum(fp, r->err_omega, ok);
    CsvNum(fp, r->err_lambda, ok);
    CsvNum(fp, r->err_com_max, ok);
    fprintf(fp, "%.4f,%ld,%s\n", r->newton_per_step, r->steps, StatusName(r->flag));
  }
  if (fclose(fp) != 0) {
    perror(path);
    return -1;
  }
  return 0;
}

/* The comparison configuration of a run: mod-lgnm for Newmark methods,
 * mod-lggalpha for generalized-alpha, same constraints / rho / k. */
static const Run *Baseline(const Run *r, const Config *cfg, int ncfg, const Run *runs)
{
  int m = FindMethod(IsNewmark(r->method) ? "mod-lgnm" : "mod-lggalpha"), c;
  if (m < 0) return NULL;
  for (c = 0; c < ncfg; c++)
    if (cfg[c].method == m && cfg[c].constraints == r->constraints &&
        cfg[c].rho == r->rho)
      return &runs[cfg[c].first + r->k];
  return NULL;
}

static void PrintTable(const Config *cfg, int ncfg, const Run *runs, int nk)
{
  int c, k;
  for (c = 0; c < ncfg; c++) {
    const Config *g = &cfg[c];
    char rho[16] = "-";
    if (g->rho >= 0.0) snprintf(rho, sizeof rho, "%.1f", g->rho);
    printf("\n%s, index %d, rho_inf %s\n", METHODS[g->method].name, IndexNumber(g->constraints), rho);
    printf("  %9s  %11s %6s  %10s  %10s  %10s  %11s  %8s  %9s\n", "h", "err_com",
           "order", "err_rot", "err_omega", "err_lambda", "err_com_max",
           "newton/st", "ratio");
    for (k = 0; k < nk; k++) {
      const Run *r = &runs[g->first + k], *p = k > 0 ? r - 1 : NULL;
      const Run *b = Baseline(r, cfg, ncfg, runs);
      char ord[16] = "-", ratio[16] = "-";
      printf("  %9.3e", r->h);
      if (r->flag != LGN_SUCCESS) {
        char f[32];
        snprintf(f, sizeof f, "F@%.4g", r->t);
        printf("  %11s %6s  %10s  %10s  %10s  %11s  %8.3f  %9s   %s\n", f, "-", "-",
               "-", "-", "-", r->newton_per_step, "-", StatusName(r->flag));
        continue;
      }
      if (p != NULL && p->flag == LGN_SUCCESS && r->err_com > 0.0)
        snprintf(ord, sizeof ord, "%.2f", log2(p->err_com / r->err_com));
      if (b != NULL && b->flag == LGN_SUCCESS && b->err_com > 0.0)
        snprintf(ratio, sizeof ratio, "%.3g", r->err_com / b->err_com);
      printf("  %11.3e %6s  %10.3e  %10.3e  %10.3e  %11.3e  %8.3f  %9s\n", r->err_com,
             ord, r->err_rot, r->err_omega, r->err_lambda, r->err_com_max,
             r->newton_per_step, ratio);
    }
  }
}

/* Least-squares slope of log(err_com) over log(h) for the ok runs. */
static int FitOrder(const Run *r, int nk, double *order)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int k, n = 0;
  for (k = 0; k < nk; k++) {
    double x, y;
    if (r[k].flag != LGN_SUCCESS || !(r[k].err_com > 0.0)) continue;
    x = log(r[k].h);
    y = log(r[k].err_com);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
    n++;
  }
  if (n < 2) return n;
  *order = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return n;
}

static void PrintSummary(const Config *cfg, int ncfg, const Run *runs, int nk)
{
  int c, k;
  printf("\nSummary (err_com at t = 1 s; order = least-squares fit over the ok runs;"
         " newton/step = mean over the ok runs)\n");
  printf("  %-18s %3s %4s  %11s  %11s  %6s  %5s  %9s\n", "method", "idx", "rho",
         "err(h_max)", "err(h_min)", "order", "ok", "newton/st");
  for (c = 0; c < ncfg; c++) {
    const Config *g = &cfg[c];
    const Run *r = &runs[g->first];
    char rho[16] = "-", e0[32], e1[32], ord[16] = "-";
    double order = 0.0, nsum = 0.0;
    int nok = 0;
    if (g->rho >= 0.0) snprintf(rho, sizeof rho, "%.1f", g->rho);
    for (k = 0; k < nk; k++)
      if (r[k].flag == LGN_SUCCESS) {
        nsum += r[k].newton_per_step;
        nok++;
      }
    if (r[0].flag == LGN_SUCCESS) snprintf(e0, sizeof e0, "%.3e", r[0].err_com);
    else snprintf(e0, sizeof e0, "F@%.4g", r[0].t);
    if (r[nk - 1].flag == LGN_SUCCESS) snprintf(e1, sizeof e1, "%.3e", r[nk - 1].err_com);
    else snprintf(e1, sizeof e1, "F@%.4g", r[nk - 1].t);
    if (FitOrder(r, nk, &order) >= 2) snprintf(ord, sizeof ord, "%.2f", order);
    printf("  %-18s %3d %4s  %11s  %11s  %6s  %2d/%-2d  ", METHODS[g->method].name,
           IndexNumber(g->constraints), rho, e0, e1, ord, nok, nk);
    if (nok > 0) printf("%9.3f\n", nsum / nok);
    else printf("%9s\n", "-");
  }
}

/* ---------------------------------------------------------------------------
 * The figure (gnuplot): left err_com vs h at index 3 (rho 0.9 + Newmark),
 * right mean Newton iterations per step per method (rho 0.9 + Newmark,
 * index 3 and index 2 side by side, mean over the ok runs).
 * ------------------------------------------------------------------------- */
static const char *const COLOURS[] = {"#9400d3", "#009e73", "#56b4e9", "#e69f00",
                                      "#d62728", "#0072b2", "#8c564b", "#000000"};
#define NCOLOURS ((int)(sizeof COLOURS / sizeof COLOURS[0]))

static int PlotRho(const Config *g, double rho_plot)
{
  return g->rho < 0.0 || g->rho == rho_plot;
}

static void WritePlot(const char *png, const Config *cfg, int ncfg, const Run *runs,
                      int nk, double rho_plot)
{
  char script[4096];
  FILE *fp;
  int c, i, k, ncurves = 0, nbars = 0, m;
  double vmax = 1.0;

  fp = bench_gnuplot_open("heavy_top_study", png, script, sizeof script);
  if (fp == NULL) return;
  fprintf(fp, "# Heavy top accuracy study (generated by heavy_top_study).\n");
  /* data block for the left panel: one index per curve */
  fprintf(fp, "$err << EOD\n");
  for (c = 0; c < ncfg; c++) {
    const Config *g = &cfg[c];
    if (g->constraints != LGN_CONSTR_INDEX3 || !PlotRho(g, rho_plot)) continue;
    fprintf(fp, "# %s\n", METHODS[g->method].name);
    for (k = 0; k < nk; k++) {
      const Run *r = &runs[g->first + k];
      if (r->flag == LGN_SUCCESS && r->err_com > 0.0)
        fprintf(fp, "%.6e %.6e\n", r->h, r->err_com);
    }
    fprintf(fp, "NaN NaN\n\n\n"); /* keeps all-failed curves as valid blocks */
    ncurves++;
  }
  fprintf(fp, "EOD\n");
  /* one line style per curve: colour by method family (the SE(3) variant
   * shares the colour of its R^3 x SO(3) counterpart), SE(3) dashed */
  for (c = 0, i = 0; c < ncfg; c++) {
    const Config *g = &cfg[c];
    const MethodSpec *ms = &METHODS[g->method];
    const int se3 = ms->formulation == HT_SE3;
    int base = se3 ? FindMethod(ms->name + 4) : g->method;
    if (g->constraints != LGN_CONSTR_INDEX3 || !PlotRho(g, rho_plot)) continue;
    if (base < 0) base = g->method;
    i++;
    fprintf(fp, "set style line %d lc rgb '%s' dt %d lw 2 pt %d ps 1.2\n", i,
            COLOURS[base % NCOLOURS], se3 ? 2 : 1, se3 ? 2 * (base % 6) + 4 : 2 * (base % 6) + 5);
  }
  fprintf(fp, "names = \"");
  for (c = 0; c < ncfg; c++)
    if (cfg[c].constraints == LGN_CONSTR_INDEX3 && PlotRho(&cfg[c], rho_plot))
      fprintf(fp, "%s ", METHODS[cfg[c].method].name);
  fprintf(fp, "\"\n");
  /* data block for the right panel: method, index 3, index 2 */
  fprintf(fp, "$newton << EOD\n");
  for (m = 0; m < NMETHODS; m++) {
    double v[2] = {NAN, NAN};
    int found = 0;
    for (c = 0; c < ncfg; c++) {
      const Config *g = &cfg[c];
      double s = 0.0;
      int n = 0;
      if (g->method != m || !PlotRho(g, rho_plot)) continue;
      for (k = 0; k < nk; k++)
        if (runs[g->first + k].flag == LGN_SUCCESS) {
          s += runs[g->first + k].newton_per_step;
          n++;
        }
      v[g->constraints == LGN_CONSTR_INDEX3 ? 0 : 1] = n ? s / n : NAN;
      if (n && s / n > vmax) vmax = s / n;
      found = 1;
    }
    if (!found) continue;
    fprintf(fp, "\"%s\" ", METHODS[m].name);
    fprintf(fp, isnan(v[0]) ? "NaN " : "%.4f ", v[0]);
    fprintf(fp, isnan(v[1]) ? "NaN\n" : "%.4f\n", v[1]);
    nbars++;
  }
  fprintf(fp, "EOD\n");
  fprintf(fp,
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
          "  set terminal pngcairo size 1400,560 enhanced font 'sans,10'\n"
          "} else {\n"
          "  set terminal png size 1400,560\n"
          "}\n"
          "set output '%s'\n"
          "set multiplot layout 1,2 title 'Heavy top, t = 1 s: "
          "generalized-alpha rho_{inf} = %.1f and Newmark (beta = 1/4, gamma = 1/2)'\n"
          "set logscale xy\n"
          "set format x '10^{%%L}'\n"
          "set format y '10^{%%L}'\n"
          "set xlabel 'h [s]'\n"
          "set ylabel 'error of the centre of mass at t = 1 s [m]'\n"
          "set title 'Error vs step size, index 3 (failed runs omitted)'\n"
          "set key top left font ',9' spacing 1.1\n"
          "set xrange [1.5e-5:3e-3]\n"
          "set yrange [*<1e-6:10]\n"
          "set grid\n"
          "plot for [i=0:%d] $err index i using 1:2 with linespoints ls i+1 "
          "title word(names, i+1)\n",
          png, rho_plot, ncurves - 1);
  fprintf(fp,
          "unset logscale\n"
          "set xrange [*:*]\n"
          "set format x '%%g'\n"
          "set format y '%%g'\n"
          "set title 'Average Newton iterations per step (ok runs)'\n"
          "set xlabel ''\n"
          "set ylabel 'Newton iterations / step'\n"
          "set style data histograms\n"
          "set style histogram clustered gap 1\n"
          "set style fill solid 0.8 border -1\n"
          "set boxwidth 0.9\n"
          "set xtics rotate by 40 right nomirror font ',9'\n"
          "set yrange [0:%.3g]\n"
          "set key top right\n"
          "plot $newton using 2:xtic(1) title 'index 3', '' using 3 title 'index 2'\n"
          "unset multiplot\n", 1.2 * vmax);
  (void)nbars;
  bench_gnuplot_run("heavy_top_study", fp, script, png);
}

static void Usage(const char *prog)
{
  printf("usage: %s [--quick] [--csv FILE] [--png FILE | --no-png]\n"
         "  Heavy top accuracy study on [0, 1] s, h = 2e-3 * 2^-k (k = 0..5;\n"
         "  --quick: k = 0..2 and rho_inf = 0.9 only).\n",
         prog);
}

int main(int argc, char **argv)
{
  const char *csv = "heavy_top_study.csv", *png = "heavy_top_study.png";
  int quick = 0, nk, nrho, i, k, m, ci, ri, ncfg = 0, nruns = 0;
  double times[NGRID + 1], t_start, t_ref, t_runs;
  LGNRefHeavyTop *ref;
  Config *cfg;
  Run *runs;

  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--quick") == 0) quick = 1;
    else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csv = argv[++i];
    else if (strcmp(argv[i], "--png") == 0 && i + 1 < argc) png = argv[++i];
    else if (strcmp(argv[i], "--no-png") == 0) png = NULL;
    else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
      Usage(argv[0]);
      return 0;
    } else {
      Usage(argv[0]);
      return 2;
    }
  }
  nk = quick ? NK_QUICK : NK_FULL;
  nrho = quick ? 1 : NRHO;

  t_start = WallSeconds();
  /* the reference on the coarsest grid t_k = k * H0 (t_NGRID = 1 exactly) */
  ref = malloc((NGRID + 1) * sizeof *ref);
  cfg = malloc((size_t)NMETHODS * NCONSTR * NRHO * sizeof *cfg);
  runs = malloc((size_t)NMETHODS * NCONSTR * NRHO * NK_FULL * sizeof *runs);
  if (ref == NULL || cfg == NULL || runs == NULL) {
    fprintf(stderr, "heavy_top_study: out of memory\n");
    return 1;
  }
  for (i = 0; i <= NGRID; i++) times[i] = (double)i * H0;
  times[NGRID] = T_END;
  if (lgnref_heavy_top(times, NGRID + 1, ref, LGNREF_FEHLBERG_8) != 0) {
    fprintf(stderr, "heavy_top_study: reference solution failed\n");
    return 1;
  }
  t_ref = WallSeconds() - t_start;

  /* configurations in the order method / constraints / rho */
  for (m = 0; m < NMETHODS; m++)
    for (ci = 0; ci < NCONSTR; ci++)
      for (ri = 0; ri < (IsNewmark(m) ? 1 : nrho); ri++) {
        Config *g = &cfg[ncfg++];
        g->method = m;
        g->constraints = CONSTRAINTS[ci];
        g->rho = IsNewmark(m) ? -1.0 : (quick ? 0.9 : RHOS[ri]);
        g->first = nruns;
        for (k = 0; k < nk; k++) {
          Run *r = &runs[nruns++];
          memset(r, 0, sizeof *r);
          r->method = m;
          r->constraints = g->constraints;
          r->rho = g->rho;
          r->k = k;
          r->h = H0 / (double)(1L << k);
        }
      }

  printf("Heavy top accuracy study: t in [0, %g] s, h = %g * 2^-k, k = 0..%d,"
         " Newton rtol = atol = %g\n", T_END, H0, nk - 1, NEWTON_TOL);
  printf("Reference: ARKODE Fehlberg 7(8) (models/lgn_reference.c), %d grid points, %.3f s\n",
         NGRID + 1, t_ref);
  fflush(stdout);
  for (i = 0; i < nruns; i++) RunOne(&runs[i], ref);
  t_runs = WallSeconds() - t_start - t_ref;

  if (WriteCsv(csv, runs, nruns) != 0) return 1;
  PrintTable(cfg, ncfg, runs, nk);
  PrintSummary(cfg, ncfg, runs, nk);
  printf("\n%d runs in %.2f s (reference %.3f s); CSV: %s\n", nruns, t_runs, t_ref, csv);
  {
    double tk[NK_FULL] = {0};
    for (i = 0; i < nruns; i++) tk[runs[i].k] += runs[i].seconds;
    printf("time per step size:");
    for (k = 0; k < nk; k++) printf(" h=%.3g: %.2f s;", H0 / (double)(1L << k), tk[k]);
    printf("\n");
  }
  fflush(stdout);
  if (png != NULL) WritePlot(png, cfg, ncfg, runs, nk, 0.9);
  printf("Total wall time %.2f s\n", WallSeconds() - t_start);

  free(runs);
  free(cfg);
  free(ref);
  return 0;
}
