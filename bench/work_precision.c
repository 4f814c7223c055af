/* -----------------------------------------------------------------------------
 * Lignum benchmarks: work-precision diagram of the heavy top (doc/accuracy-study.md) on t in [0, 1] s, Lignum against SUNDIALS IDA, in one process.
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
 * independent ARKODE reference (models/lgn_reference.c, Fehlberg 7(8)).  CPU time:
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
#include <lignum/lignum_ls.h>

#include "bench_gnuplot.h"
#include "ida_chain.h"
#include "ida_heavy_top.h"
#include "lgn_reference.h"
#include "models/chain.h"
#include "models/heavy_top.h"

#define CSV_HEADER \
  "solver,method,setting,err_com,cpu_s,steps,newton_iters,res_evals,jac_evals,problem,sundials"
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
  int bdf;         /* > 0: BDF of this highest order (LGNSetBDF); needs adaptive */
} LignumSpec;

static const LignumSpec LIGNUM[] = {
  {"LGNM idx3 lie",          HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"LGNM idx2 lie",          HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"mod. LGNM idx3 lie",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"mod. LGNM idx2 lie",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"LGGalpha idx3 lie",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"LGGalpha idx2 lie",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"mod. LGGalpha idx3 lie", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"mod. LGGalpha idx2 lie", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"Newmark idx3 ep",        HT_EULER_PARAMETERS, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"Newmark idx2 ep",        HT_EULER_PARAMETERS, HT_NEWMARK,  LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"gen-alpha idx3 ep",      HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  {"gen-alpha idx2 ep",      HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 0, 0},
  /* modified Newton (LGNSetNewtonMode): reuse of the factorised matrix */
  {"mod. LGNM idx3 lie mN",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0, 0},
  {"mod. LGNM idx2 lie mN",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0, 0},
  {"LGGalpha idx3 lie mN",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0, 0},
  {"mod. LGGalpha idx3 lie mN", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0, 0},
  {"mod. LGGalpha idx2 lie mN", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0, 0},
  {"gen-alpha idx3 ep mN",      HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 0, 0},
  /* ... with the Newton tolerance tied to the step: h^2, about 1/100 of the
   * global error of these second-order methods (the measured error decides) */
  {"mod. LGNM idx3 lie mN h2",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 1, 0, 0},
  {"mod. LGGalpha idx3 lie mN h2", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 1, 0, 0},
  {"mod. LGGalpha idx3 lie h2",    HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 1, 0, 0},
  /* error control (LGNSetStepControl(LGN_STEP_ADAPTIVE)): tolerance sweep */
  {"LGGalpha idx3 lie EC",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1, 0},
  {"mod. LGGalpha idx3 lie EC", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1, 0},
  /* (undamped Newmark at index 3 is refused under error control: index 2) */
  {"mod. LGNM idx2 lie EC",     HT_LIE, HT_NEWMARK,  LGN_KINEMATICS_EXACT,      LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1, 0},
  {"LGGalpha idx2 lie EC",      HT_LIE, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX2, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1, 0},
  {"gen-alpha idx3 ep EC",      HT_EULER_PARAMETERS, HT_GENALPHA, LGN_KINEMATICS_SIMPLIFIED, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL, 0, 1, 0},
  /* the BDF family (LGNSetBDF), error control */
  {"BDF4 idx3 lie EC",    HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_FULL,     0, 1, 4},
  {"BDF4 idx3 lie mN EC", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 1, 4},
  {"BDF5 idx3 lie mN EC", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 1, 5},
  {"BDF3 idx3 lie mN EC", HT_LIE, HT_GENALPHA, LGN_KINEMATICS_EXACT, LGN_CONSTR_INDEX3, LGN_PREDICTOR_ZERO, LGN_NEWTON_MODIFIED, 0, 1, 3},
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
#define NH      9
#define RTOL0   1e-3 /* rtol_k = RTOL0 * 10^-k       */
#define NRTOL   8
#define TOL0    1e-3 /* error control: rtol = atol = TOL0 * 10^-(k/2) */
#define NTOL    17   /* 1e-3 .. 1e-11 (BDF reaches 1e-6 near 1e-10) */

static const double LEVELS[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
#define NLEVELS 5

/* ---------------------------------------------------------------------------
 * The second problem: the N-body chain of models/chain.c (N rods,
 * spherical joints, at rest in a bent configuration, falling and whipping),
 * N = CHAIN_N, t in [0, 1] s.  Lignum: the rows of LIGNUM[] named in
 * CHAIN_ROWS[] through rigid_run() (R^3 x SO(3) per body, dense, analytic
 * K_t, C_t, Z); IDA: ida_chain.c (GGL index 2 in Euler parameters) with
 * the three linear-solver set-ups of IDA[] (dense-DQ, dense-Jac, KLU).
 * Error: |tip(1) - tip_ref(1)|_2, the free end of the last rod.
 * ------------------------------------------------------------------------- */
#define CHAIN_N 3
#define CHAIN_H0 4e-2    /* Lignum: h = CHAIN_H0 * 2^-k, k = 0..CHAIN_NH-1 */
#define CHAIN_NH 11
#define CHAIN_RTOL0 1e-2 /* IDA: rtol = CHAIN_RTOL0 * 10^-k, k = 0..CHAIN_NRTOL-1 */
#define CHAIN_NRTOL 9
#define CHAIN_REF_X -1.855169400564356
#define CHAIN_REF_Y -6.545653961586941e-03
#define CHAIN_REF_Z -2.068593335280935
static const char *const CHAIN_ROWS[] = {
  "LGGalpha idx3 lie", "LGGalpha idx2 lie", "mod. LGGalpha idx3 lie", "mod. LGGalpha idx2 lie",
  "mod. LGNM idx2 lie", "LGGalpha idx3 lie mN", "mod. LGGalpha idx3 lie mN",
  "mod. LGGalpha idx3 lie mN h2", "BDF4 idx3 lie mN EC", "BDF5 idx3 lie mN EC",
  "BDF4 idx3 lie EC",
};
#define NCHAIN_ROWS ((int)(sizeof CHAIN_ROWS / sizeof CHAIN_ROWS[0]))
/* Reference tip position at t = 1 (see ChainReference(), --chain-reference) */
static const double CHAIN_TIP_REF[3] = {CHAIN_REF_X, CHAIN_REF_Y, CHAIN_REF_Z};

static const char *const PROBLEM_NAME[2] = {"top", "chain"};

/* The most steps one Lignum run may take (LGNSetMaxNumSteps): a setting
 * whose steps collapse fails after this many, printed as failed (F@t, with
 * its flag), instead of running to the default 10^6 steps (6-7 s each on
 * the heavy top, minutes under the sanitizers). Full benchmark: above the
 * most any run reaching t = 1 needs (mod. LGGalpha index 2, tol 1e-8:
 * 219,081; the finest fixed step: 64,000); --quick (tol >= 1e-5): 10^5. */
#define MAX_STEPS_FULL  500000L
#define MAX_STEPS_QUICK 100000L
static long int g_max_steps = MAX_STEPS_FULL;

/* One run (one method at one setting). */
typedef struct {
  int problem;      /* 0: heavy top, 1: chain     */
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

/* the best (smallest) of n CPU times: the least disturbed by the other
 * processes of a shared machine */
static double BestOf(double *v, int n)
{
  qsort(v, (size_t)n, sizeof *v, CmpDouble);
  return v[0];
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
  opt->bdf_maxord = s->bdf;
  opt->max_steps = g_max_steps;
  opt->make_ls = LGNLinSol_Dense; /* Lignum's own dense LU (lignum_ls.h) */
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

static double Dist3(const double a[3], const double b[3])
{
  double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

/* The chain with Lignum: spec's method at step h (tip at t_end in tip). */
static void ChainLignum(const LignumSpec *s, double h, double t_end, RigidRunResult *res,
                        double tip[3])
{
  SUNContext ctx = NULL;
  RigidSystem *sys = NULL;
  RigidRunOptions opt;
  memset(res, 0, sizeof *res);
  res->flag = -100;
  tip[0] = tip[1] = tip[2] = NAN;
  if (SUNContext_Create(NULL, &ctx) != 0) return;
  sys = chain_create(CHAIN_N, RB_R3XSO3, ctx);
  if (sys != NULL) {
    rigid_default_run_options(&opt);
    opt.solver = RB_DENSE;
    opt.method = s->method == HT_GENALPHA ? 1 : 0;
    opt.rho_inf = 0.9;
    opt.beta = 0.25;
    opt.gamma = 0.5;
    opt.kinematics = s->kinematics;
    opt.constraints = s->constraints;
    opt.newton = s->newton;
    opt.predictor = s->predictor;
    opt.analytic = 1;
    opt.h = h;
    opt.t_end = t_end;
    opt.outputs = 1; /* one LGNSolve call to t_end */
    if (s->tol_h2 > 0.0) opt.rtol = opt.atol = s->tol_h2 * h * h;
    opt.bdf_maxord   = s->bdf;
    opt.own_dense_lu = 1;
    opt.max_steps    = g_max_steps;
    if (s->adaptive) { /* h is the tolerance */
      opt.adaptive = 1;
      opt.rtol = opt.atol = h;
      opt.h = 1e-4; /* the first step tried */
    }
    rigid_run(sys, &opt, res);
    if (res->q != NULL) ida_chain_tip(CHAIN_N, res->q, tip);
    rigid_free(&sys);
  }
  SUNContext_Free(&ctx);
}

/* One measurement; returns 1 if the run reached T_END. */
static int RunOnce(Run *r, const LGNRefHeavyTop *ref, double *cpu)
{
  if (r->problem == 1 && !r->ida) {
    RigidRunResult res;
    double tip[3];
    ChainLignum(&LIGNUM[r->spec], r->setting, T_END, &res, tip);
    r->flag = res.flag;
    r->t = res.t;
    r->err = Dist3(tip, CHAIN_TIP_REF);
    r->steps = res.nsteps;
    r->nni = res.nni;
    r->nres = res.nre + res.ndq;
    r->njac = res.nje;
    r->netf = res.netf;
    r->nncf = res.nncf;
    *cpu = res.cpu_seconds;
    rigid_result_free(&res);
  } else if (r->problem == 1) {
    IdaChainOptions opt;
    IdaChainResult res;
    ida_chain_default_options(&opt);
    opt.n = CHAIN_N;
    opt.linsol = (IdaChainLinSol)IDA[r->spec].linsol; /* same three set-ups */
    opt.rtol = r->setting;
    opt.t_end = T_END;
    ida_chain_run(&opt, &res);
    r->flag = res.flag;
    r->t = res.t;
    r->err = Dist3(res.tip, CHAIN_TIP_REF);
    r->steps = res.nsteps;
    r->nni = res.nniters;
    r->nres = res.nres;
    r->njac = res.njevals;
    *cpu = res.cpu_seconds;
  } else if (!r->ida) {
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
  r->cpu = BestOf(cpu, i);
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

static int WriteCsv(const char *path, const Run *runs, int nruns, const char *sundials)
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
    fprintf(fp, ",%.6e,%ld,%ld,%ld,%ld,%s,%s\n", r->cpu, r->steps, r->nni, r->nres, r->njac,
            PROBLEM_NAME[r->problem], sundials);
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
      printf("%-24s %9.3g  %10s  %10.3f  %7ld  %6.2f  %7ld  %6ld", MethodName(r),
             r->setting, e, 1e3 * r->cpu, r->steps,
             r->steps > 0 ? (double)r->nni / (double)r->steps : 0.0, r->nres, r->njac);
      if (r->ok) printf("\n");
      else printf("  (%s failed, flag %d)\n", r->ida ? "IDA" : "Lignum", r->flag);
    }
}

/* The table of issue 6 and the PASS/MISS lines. */
static void PrintSummary(const Curve *cv, int ncv, const Run *runs, int problem)
{
  double ratio[NLEVELS];
  int have[NLEVELS], l, all = 1;
  printf("\nWork-precision summary (%s): CPU time to reach %s = level\n"
         "(interpolated on each method's log-log curve; best = fastest method)\n",
         problem ? "chain" : "heavy top",
         problem ? "|tip(1) - tip_ref(1)|" : "|x(1) - x_ref(1)|");
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
  if (problem) return;
  printf("\nTargets of issue 6 (reported, never enforced):\n");
  if (have[1])
    printf("  %s  Lignum's best at least 5x faster than IDA's best at error 1e-3: factor %.2f\n",
           ratio[1] >= 5.0 ? "PASS" : "MISS", ratio[1]);
  else
    printf("  MISS  Lignum's best at least 5x faster than IDA's best at error 1e-3: "
           "level not reached by both\n");
  for (l = 0; l < NLEVELS; l++)
    if (!have[l] || !(ratio[l] > 1.0)) all = 0;
  printf("  %s  Lignum faster at every level 1e-2 .. 1e-6: factors", all ? "PASS" : "MISS");
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
 * --chain-reference: how CHAIN_TIP_REF was computed.  IDA (dense-DQ) at
 * rtol = 1e-9 .. 1e-12, and Lignum's LGGalpha / mod. LGGalpha (index 3) at
 * h = 1e-4 / 2^k with Richardson extrapolation (second order:
 * (4 tip(h/2) - tip(h)) / 3); prints the tips and their distances.
 * ------------------------------------------------------------------------- */

static int LignumRow(const char *name)
{
  int k;
  for (k = 0; k < NLIGNUM; k++)
    if (strcmp(LIGNUM[k].name, name) == 0) return k;
  return -1;
}

static void ChainReference(void)
{
  double tip_ida[3] = {0, 0, 0}, prev[3] = {0, 0, 0};
  int k, i, row;
  printf("Chain (N = %d) reference: tip at t = %g (%s, %d rows)\n", CHAIN_N, T_END, PROBLEM_NAME[1], NCHAIN_ROWS);
  for (k = 9; k <= 12; k++) {
    IdaChainOptions opt;
    IdaChainResult res;
    ida_chain_default_options(&opt);
    opt.n = CHAIN_N;
    opt.rtol = pow(10.0, -k);
    opt.t_end = T_END;
    ida_chain_run(&opt, &res);
    printf("  IDA rtol 1e-%d: flag %d steps %ld tip %.15e %.15e %.15e  |d prev| %.2e |Phi| %.1e cpu %.2f s\n",
           k, res.flag, res.nsteps, res.tip[0], res.tip[1], res.tip[2],
           k > 9 ? Dist3(res.tip, tip_ida) : 0.0, res.max_phi_end, res.cpu_seconds);
    for (i = 0; i < 3; i++) tip_ida[i] = res.tip[i];
  }
  for (row = 0; row < 2; row++) {
    const int spec = LignumRow(row == 0 ? "LGGalpha idx3 lie" : "mod. LGGalpha idx3 lie");
    for (k = 0; k < 4; k++) {
      RigidRunResult res;
      double tip[3], rich[3];
      const double h = 1e-4 / (double)(1 << k);
      ChainLignum(&LIGNUM[spec], h, T_END, &res, tip);
      for (i = 0; i < 3; i++) rich[i] = (4.0 * tip[i] - prev[i]) / 3.0;
      printf("  %s h %.3e: flag %d tip %.15e %.15e %.15e  |d IDA| %.2e", LIGNUM[spec].name, h,
             res.flag, tip[0], tip[1], tip[2], Dist3(tip, tip_ida));
      if (k > 0) printf("  Richardson %.15e %.15e %.15e |d IDA| %.2e", rich[0], rich[1], rich[2],
                        Dist3(rich, tip_ida));
      printf("\n");
      for (i = 0; i < 3; i++) prev[i] = tip[i];
      rigid_result_free(&res);
    }
  }
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
  /* the heavy top's consistent multiplier (doc/accuracy-study.md): lambda0 = (0, -319.525988166, -317.2624615385) */
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
  snprintf(msg, sizeof msg, "IDA: lambda0 of the joint equals the reference value (max diff %.2e < 1e-6)", dl);
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
  /* the chain: constraint Jacobian, consistent start, IDA converging to the
   * reference, Lignum second order towards it */
  {
    static double cy[22 * IDACH_MAXN], cyp[22 * IDACH_MAXN];
    const double bj = ida_chain_check_constraint_jacobian(CHAIN_N);
    double e_prev = INFINITY, cpu;
    snprintf(msg, sizeof msg, "chain: B = dPhi/dq against central differences (%.1e < 1e-7)", bj);
    fails += Check(bj < 1e-7, msg);
    fails += Check(ida_chain_initial(CHAIN_N, cy, cyp, &rn) == 0, "chain: IDA initial values computed");
    for (i = 0; i < 2; i++) {
      const double cj = i == 0 ? 1.0 : 1e4;
      jerr = ida_chain_check_jacobian(CHAIN_N, cj);
      snprintf(msg, sizeof msg,
               "chain: IDA analytic Jacobian = central differences (c_j = %g, rel. diff %.1e < 1e-7)",
               cj, jerr);
      fails += Check(jerr < 1e-7, msg);
    }
    for (i = 0; i < NIDA; i++) {
      Run r;
      memset(&r, 0, sizeof r);
      r.problem = 1;
      r.ida = 1;
      r.spec = i;
      r.setting = 1e-7;
      r.ok = RunOnce(&r, ref, &cpu);
      snprintf(msg, sizeof msg, "chain: %s rtol 1e-7: tip err %.3e < 1e-4", IDA[i].name, r.err);
      fails += Check(r.ok && r.err < 1e-4, msg);
    }
    snprintf(msg, sizeof msg, "chain: IDA max|F(0, y0, y'0)| = %.2e < 1e-10", rn);
    fails += Check(rn < 1e-10, msg);
    for (k = 0; k < 3; k++) {
      Run r;
      memset(&r, 0, sizeof r);
      r.problem = 1;
      r.ida = 1;
      r.setting = k == 0 ? 1e-5 : k == 1 ? 1e-7 : 1e-9;
      r.ok = RunOnce(&r, ref, &cpu);
      snprintf(msg, sizeof msg, "chain: IDA dense-DQ rtol %.0e: reaches t = 1, tip err %.3e < %.3e",
               r.setting, r.err, e_prev);
      fails += Check(r.ok && r.err < e_prev, msg);
      e_prev = r.err;
    }
    snprintf(msg, sizeof msg, "chain: IDA rtol 1e-9: tip err %.3e < 1e-6", e_prev);
    fails += Check(e_prev < 1e-6, msg);
    for (k = 0; k < NCHAIN_ROWS; k += 2) {
      Run a, b;
      memset(&a, 0, sizeof a);
      a.problem = 1;
      a.spec = LignumRow(CHAIN_ROWS[k]);
      if (LIGNUM[a.spec].adaptive) continue; /* (a tolerance, not a step) */
      a.setting = 1e-3;
      b = a;
      b.setting = 5e-4;
      a.ok = RunOnce(&a, ref, &cpu);
      b.ok = RunOnce(&b, ref, &cpu);
      snprintf(msg, sizeof msg, "chain: %s: tip err(h=1e-3) = %.3e < 1e-3, err(5e-4) = %.3e, ratio %.2f > 3",
               CHAIN_ROWS[k], a.err, b.err, a.err / b.err);
      fails += Check(a.ok && b.ok && a.err < 1e-3 && a.err / b.err > 3.0, msg);
    }
  }
  printf("%s\n", fails ? "Quick checks FAILED" : "Quick checks passed");
  return fails;
}

/* ---------------------------------------------------------------------------
 * main
 * ------------------------------------------------------------------------- */


/* ---------------------------------------------------------------------------
 * Which SUNDIALS this process loaded (from /proc/self/maps): "debian" when
 * every libsundials_* mapped comes from /usr/lib or /lib, "O2" when every
 * one comes from a directory whose parent holds the stamp
 * lignum-ida-O2.stamp written by bench/build-ida-O2, "mixed" otherwise,
 * "unknown" without /proc.  ARKODE (the heavy top's reference only, never
 * timed) is not part of the -O2 build and is not counted.
 * ------------------------------------------------------------------------- */

static const char *const SUNDIALS_LIBS[] = {
  "libsundials_ida.so", "libsundials_sunlinsoldense.so", "libsundials_sunmatrixdense.so",
  "libsundials_nvecserial.so", "libsundials_sunlinsolklu.so", "libsundials_sunmatrixsparse.so",
};
#define NSUNDIALS_LIBS ((int)(sizeof SUNDIALS_LIBS / sizeof SUNDIALS_LIBS[0]))

static int IsO2Path(const char *path)
{
  char stamp[4200];
  const char *slash = strrchr(path, '/');
  size_t n;
  FILE *fp;
  if (slash == NULL) return 0;
  n = (size_t)(slash - path); /* the library's directory */
  while (n > 0 && path[n - 1] != '/') n--;
  if (n == 0) return 0;
  snprintf(stamp, sizeof stamp, "%.*slignum-ida-O2.stamp", (int)n, path);
  fp = fopen(stamp, "r");
  if (fp == NULL) return 0;
  fclose(fp);
  return 1;
}

static const char *DetectSundials(int verbose)
{
  char line[4608], found[NSUNDIALS_LIBS][4200];
  int k, deb = 0, o2 = 0, other = 0;
  FILE *fp = fopen("/proc/self/maps", "r");
  if (fp == NULL) return "unknown";
  for (k = 0; k < NSUNDIALS_LIBS; k++) found[k][0] = '\0';
  while (fgets(line, sizeof line, fp) != NULL) {
    char *path = strchr(line, '/'), *nl;
    if (path == NULL) continue;
    if ((nl = strchr(path, '\n')) != NULL) *nl = '\0';
    for (k = 0; k < NSUNDIALS_LIBS; k++)
      if (found[k][0] == '\0' && strstr(path, SUNDIALS_LIBS[k]) != NULL)
        snprintf(found[k], sizeof found[k], "%s", path);
  }
  fclose(fp);
  for (k = 0; k < NSUNDIALS_LIBS; k++) {
    const char *f = found[k];
    if (f[0] == '\0') continue;
    if (IsO2Path(f)) o2++;
    else if (strncmp(f, "/usr/lib/", 9) == 0 || strncmp(f, "/lib/", 5) == 0) deb++;
    else other++;
    if (verbose) printf("  loaded %s\n", f);
  }
  if (o2 > 0 && deb == 0 && other == 0) return "O2";
  if (deb > 0 && o2 == 0 && other == 0) return "debian";
  return o2 + deb + other == 0 ? "unknown" : "mixed";
}

/* ---------------------------------------------------------------------------
 * The runs of a full (or --quick) benchmark, in a fixed order: heavy top
 * (LIGNUM[], IDA[]), then the chain (CHAIN_ROWS[], IDA dense-DQ).
 * Curves cv[0 .. *ncv_top - 1] are the heavy top's.
 * ------------------------------------------------------------------------- */

#define MAXCURVES (NLIGNUM + NIDA + NCHAIN_ROWS + NIDA)
#define MAXRUNS                                                                  \
  (NLIGNUM * (NH > NTOL ? NH : NTOL) + NIDA * NRTOL +                         \
   NCHAIN_ROWS * (CHAIN_NH > NTOL ? CHAIN_NH : NTOL) +                         \
   NIDA * CHAIN_NRTOL)

static int BuildRuns(int quick, Run *runs, Curve *cv, int *ncv, int *ncv_top)
{
  const int nh = quick ? 3 : NH, nrt = quick ? 3 : NRTOL, ntol = quick ? 3 : NTOL;
  int c, k, nruns = 0;
  *ncv = 0;
  for (c = 0; c < NLIGNUM; c++) {
    const int adaptive = LIGNUM[c].adaptive;
    Curve *v = &cv[(*ncv)++];
    v->first = nruns;
    v->n = adaptive ? ntol : nh;
    v->ida = 0;
    v->spec = c;
    for (k = 0; k < v->n; k++) {
      Run *r = &runs[nruns++];
      memset(r, 0, sizeof *r);
      r->spec = c;
      /* quick: 1e-3, 1e-4, 1e-5 */
      r->setting = adaptive ? TOL0 * pow(10.0, -0.5 * (quick ? 2 * k : k))
                            : H0 / (double)(1L << k);
    }
  }
  for (c = 0; c < NIDA; c++) {
    Curve *v = &cv[(*ncv)++];
    v->first = nruns;
    v->n = nrt;
    v->ida = 1;
    v->spec = c;
    for (k = 0; k < nrt; k++) {
      Run *r = &runs[nruns++];
      memset(r, 0, sizeof *r);
      r->ida = 1;
      r->spec = c;
      r->setting = RTOL0 * pow(10.0, -k);
    }
  }
  *ncv_top = *ncv;
  for (c = 0; c < NCHAIN_ROWS + NIDA; c++) {
    const int ida = c >= NCHAIN_ROWS, spec = ida ? c - NCHAIN_ROWS : LignumRow(CHAIN_ROWS[c]);
    Curve *v = &cv[(*ncv)++];
    v->first = nruns;
    const int tolsweep = !ida && LIGNUM[spec].adaptive;
    v->n = quick ? 3 : ida ? CHAIN_NRTOL : tolsweep ? NTOL : CHAIN_NH;
    v->ida = ida;
    v->spec = spec;
    for (k = 0; k < v->n; k++) {
      Run *r = &runs[nruns++];
      memset(r, 0, sizeof *r);
      r->problem = 1;
      r->ida = ida;
      r->spec = spec;
      r->setting = ida        ? CHAIN_RTOL0 * pow(10.0, -k)
                   : tolsweep ? TOL0 * pow(10.0, -0.5 * (quick ? 2 * k : k))
                              : CHAIN_H0 / (double)(1L << k);
    }
  }
  return nruns;
}

/* ---------------------------------------------------------------------------
 * --merge: best CPU time over several raw CSVs (one per process, each of
 * one SUNDIALS build: column "sundials"), per build; the table, CSV and
 * figure of the fair comparison.
 * ------------------------------------------------------------------------- */

#define MERGE_HEADER                                                                     \
  "problem,level,lignum_method,lignum_debian_ms,lignum_O2_ms,lignum_steps,ida_method,"   \
  "ida_debian_ms,ida_O2_ms,ida_steps,ratio_debian,ratio_O2"

/* split a CSV line in place (no quoting; empty fields kept) */
static int SplitCsv(char *line, char **f, int maxf)
{
  int n = 0;
  char *p = line, *e;
  if ((e = strpbrk(line, "\r\n")) != NULL) *e = '\0';
  while (n < maxf) {
    f[n++] = p;
    if ((e = strchr(p, ',')) == NULL) break;
    *e = '\0';
    p = e + 1;
  }
  return n;
}

static int ReadRaw(const char *path, Run *runs[2], int nruns, int *have, int *nfiles)
{
  char line[1024], *f[16];
  FILE *fp = fopen(path, "r");
  int b = -1, nrows = 0;
  if (fp == NULL) {
    perror(path);
    return -1;
  }
  if (fgets(line, sizeof line, fp) == NULL || strncmp(line, CSV_HEADER, strlen(CSV_HEADER)) != 0) {
    fprintf(stderr, "work_precision: %s: not a work_precision CSV\n", path);
    fclose(fp);
    return -1;
  }
  while (fgets(line, sizeof line, fp) != NULL) {
    int i, ida, problem, nf = SplitCsv(line, f, 16);
    double setting, cpu;
    if (nf < 11) continue;
    if (strcmp(f[10], "debian") == 0) b = 0;
    else if (strcmp(f[10], "O2") == 0) b = 1;
    else {
      fprintf(stderr, "work_precision: %s: SUNDIALS build '%s' is neither debian nor O2: skipped\n",
              path, f[10]);
      fclose(fp);
      return 0;
    }
    ida = strcmp(f[0], "ida") == 0;
    problem = strcmp(f[9], "chain") == 0;
    setting = atof(f[2]);
    cpu = atof(f[4]);
    for (i = 0; i < nruns; i++) {
      Run *r = &runs[b][i];
      if (r->problem != problem || r->ida != ida || strcmp(MethodName(r), f[1]) != 0 ||
          fabs(r->setting - setting) > 1e-4 * r->setting)
        continue;
      if (f[3][0] != '\0') {
        r->ok = 1;
        r->t = T_END;
        r->err = atof(f[3]);
        r->steps = atol(f[5]);
        r->nni = atol(f[6]);
        r->nres = atol(f[7]);
        r->njac = atol(f[8]);
        if (!(r->cpu > 0.0) || cpu < r->cpu) r->cpu = cpu;
      }
      nrows++;
      break;
    }
  }
  fclose(fp);
  if (b >= 0) {
    have[b] = 1;
    nfiles[b]++;
  }
  printf("  %s: %s SUNDIALS, %d rows\n", path, b == 1 ? "-O2" : "Debian's", nrows);
  return 0;
}

static int Merge(const char *out_csv, const char *png, int nin, char **in)
{
  static Run rd[MAXRUNS], ro[MAXRUNS];
  Run *runs[2] = {rd, ro};
  Curve cv[MAXCURVES];
  int ncv, ncv_top, nruns, i, b, p, l, have[2] = {0, 0}, nfiles[2] = {0, 0}, differ = 0;
  FILE *fp;
  char script[4096];

  nruns = BuildRuns(0, rd, cv, &ncv, &ncv_top);
  BuildRuns(0, ro, cv, &ncv, &ncv_top);
  printf("Merging %d raw CSV file(s) (best CPU time per run and SUNDIALS build):\n", nin);
  for (i = 0; i < nin; i++)
    if (ReadRaw(in[i], runs, nruns, have, nfiles) != 0) return 1;
  if (!have[0]) {
    fprintf(stderr, "work_precision: no run with Debian's SUNDIALS among the inputs\n");
    return 1;
  }
  for (i = 0; i < nruns && have[1]; i++)
    if (rd[i].ok && ro[i].ok && rd[i].err != ro[i].err) differ++;
  fp = fopen(out_csv, "w");
  if (fp == NULL) {
    perror(out_csv);
    return 1;
  }
  fprintf(fp, "%s\n", MERGE_HEADER);
  printf("\nFair comparison: best CPU time [ms] over %d process(es) with Debian's SUNDIALS (-O0)"
         " and %d with the -O2 build (bench/build-ida-O2)%s.\n"
         "Same binary; per error level the fastest Lignum method and the fastest IDA set-up\n"
         "(interpolated on each method's log-log curve; steps of that method at that level).\n",
         nfiles[0], nfiles[1], have[1] ? "" : " -- the -O2 build was NOT run: Debian's column only");
  if (have[1])
    printf("Errors identical between the two builds in all but %d run(s).\n", differ);
  for (p = 0; p < 2; p++) {
    const Curve *pc = p == 0 ? cv : cv + ncv_top;
    const int pn = p == 0 ? ncv_top : ncv - ncv_top;
    printf("\n%s, error %s at t = 1 s\n", p == 0 ? "Heavy top" : "Chain of 3 rods",
           p == 0 ? "|x - x_ref| of the centre of mass" : "|tip - tip_ref| of the free end");
    printf("%6s | %-28s %9s %9s %7s | %-17s %9s %9s %6s | %8s %8s\n", "level", "best Lignum",
           "Deb [ms]", "O2 [ms]", "steps", "best IDA", "Deb [ms]", "O2 [ms]", "steps",
           "IDA/Lig", "IDA/Lig");
    printf("%6s | %-28s %9s %9s %7s | %-17s %9s %9s %6s | %8s %8s\n", "", "", "", "", "", "", "",
           "", "", "Debian", "-O2");
    for (l = 0; l < NLEVELS; l++) {
      double cl[2] = {0, 0}, ci[2] = {0, 0}, sl = 0, si = 0;
      int hl[2] = {0, 0}, hi[2] = {0, 0}, wl[2] = {-1, -1}, wi[2] = {-1, -1}, bl, bi;
      char s[8][32];
      for (b = 0; b < 2; b++) {
        if (!have[b]) continue;
        hl[b] = Best(pc, pn, runs[b], 0, LEVELS[l], &cl[b], &wl[b]);
        hi[b] = Best(pc, pn, runs[b], 1, LEVELS[l], &ci[b], &wi[b]);
      }
      bl = have[1] && hl[1] ? 1 : 0; /* whose best method is named */
      bi = have[1] && hi[1] ? 1 : 0;
      if (hl[bl]) ValueAtLevel(&runs[bl][pc[wl[bl]].first], pc[wl[bl]].n, LEVELS[l], 1, &sl);
      if (hi[bi]) ValueAtLevel(&runs[bi][pc[wi[bi]].first], pc[wi[bi]].n, LEVELS[l], 1, &si);
      for (i = 0; i < 8; i++) snprintf(s[i], sizeof s[i], "-");
      for (b = 0; b < 2; b++) {
        if (hl[b]) snprintf(s[b], sizeof s[b], "%.3f", 1e3 * cl[b]);
        if (hi[b]) snprintf(s[2 + b], sizeof s[2 + b], "%.3f", 1e3 * ci[b]);
        if (hl[b] && hi[b]) snprintf(s[4 + b], sizeof s[4 + b], "%.2f", ci[b] / cl[b]);
      }
      if (hl[bl]) snprintf(s[6], sizeof s[6], "%.0f", sl);
      if (hi[bi]) snprintf(s[7], sizeof s[7], "%.0f", si);
      printf("%6.0e | %-28s %9s %9s %7s | %-17s %9s %9s %6s | %8s %8s\n", LEVELS[l],
             hl[bl] ? LIGNUM[pc[wl[bl]].spec].name : "not reached", s[0], s[1], s[6],
             hi[bi] ? IDA[pc[wi[bi]].spec].name : "not reached", s[2], s[3], s[7], s[4], s[5]);
      fprintf(fp, "%s,%g,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", PROBLEM_NAME[p], LEVELS[l],
              hl[bl] ? LIGNUM[pc[wl[bl]].spec].name : "", hl[0] ? s[0] : "", hl[1] ? s[1] : "",
              hl[bl] ? s[6] : "", hi[bi] ? IDA[pc[wi[bi]].spec].name : "", hi[0] ? s[2] : "",
              hi[1] ? s[3] : "", hi[bi] ? s[7] : "", hl[0] && hi[0] ? s[4] : "",
              hl[1] && hi[1] ? s[5] : "");
    }
  }
  if (fclose(fp) != 0) {
    perror(out_csv);
    return 1;
  }
  printf("\nCSV: %s\n", out_csv);
  fflush(stdout);
  if (png == NULL) return 0;
  /* figure: per problem, the best time over all methods at 4 levels per
   * decade, 1e-2 .. 1e-6, for Lignum and IDA under both builds */
  fp = bench_gnuplot_open("work_precision", png, script, sizeof script);
  if (fp == NULL) return 0;
  fprintf(fp, "# Fair work-precision comparison (generated by work_precision --merge).\n");
  for (p = 0; p < 2; p++) {
    const Curve *pc = p == 0 ? cv : cv + ncv_top;
    const int pn = p == 0 ? ncv_top : ncv - ncv_top;
    fprintf(fp, "$d%d << EOD\n", p);
    for (l = 0; l <= 16; l++) {
      const double level = 1e-2 * pow(10.0, -0.25 * l);
      fprintf(fp, "%.4e", level);
      for (b = 0; b < 2; b++) {
        int ida;
        for (ida = 0; ida < 2; ida++) {
          double c = 0.0;
          int w;
          if (have[b] && Best(pc, pn, runs[b], ida, level, &c, &w)) fprintf(fp, " %.6e", 1e3 * c);
          else fprintf(fp, " NaN");
        }
      }
      fprintf(fp, "\n");
    }
    fprintf(fp, "EOD\n");
  }
  fprintf(fp,
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
          "  set terminal pngcairo size 1200,520 enhanced font 'sans,10'\n"
          "} else {\n"
          "  set terminal png size 1200,520\n"
          "}\n"
          "set output '%s'\n"
          "set logscale xy\nset grid\nset format x '10^{%%L}'\nset format y '10^{%%L}'\n"
          "set xrange [1e-6:1e-2]\n"
          "set ylabel 'best CPU time [ms]'\nset key top left font ',9'\n"
          "set multiplot layout 1,2 title 'Lignum vs SUNDIALS IDA, Debian SUNDIALS (-O0) and "
          "-O2 build%s (best method per error level)'\n",
          png, have[1] ? "" : " [-O2 build not run]");
  for (p = 0; p < 2; p++)
    fprintf(fp,
            "set title '%s'\nset xlabel '%s'\n"
            "plot $d%d using 1:2 with linespoints lw 2 pt 7 lc rgb '#d62728' title 'Lignum, Debian SUNDIALS', "
            "$d%d using 1:4 with linespoints lw 2 pt 6 dt 2 lc rgb '#d62728' title 'Lignum, -O2 SUNDIALS', "
            "$d%d using 1:3 with linespoints lw 2 pt 5 lc rgb '#0072b2' title 'IDA, Debian (-O0)', "
            "$d%d using 1:5 with linespoints lw 2 pt 4 dt 2 lc rgb '#0072b2' title 'IDA, -O2'\n",
            p == 0 ? "Heavy top, t in [0, 1] s" : "Chain of 3 rods, t in [0, 1] s",
            p == 0 ? "error of the centre of mass at t = 1 [m]" : "error of the tip at t = 1 [m]",
            p, p, p, p);
  fprintf(fp, "unset multiplot\n");
  bench_gnuplot_run("work_precision", fp, script, png);
  return 0;
}

/* ---------------------------------------------------------------------------
 * main
 * ------------------------------------------------------------------------- */

static void Usage(const char *prog)
{
  printf("usage: %s [--quick] [--reps N] [--csv FILE] [--png FILE | --no-png]\n"
         "          [--expect-sundials debian|O2] [--chain-reference]\n"
         "       %s --merge OUT.csv [--png FILE | --no-png] RAW.csv...\n"
         "  Work-precision of the heavy top and of a 3-rod chain: Lignum\n"
         "  (h = 4e-3 * 2^-k, k = 0..8) against IDA (GGL, rtol = 1e-3 .. 1e-10); CPU time =\n"
         "  best of N runs (default 3).  The header says which SUNDIALS libraries the\n"
         "  process loaded (Debian's or bench/build-ida-O2's, via LD_LIBRARY_PATH);\n"
         "  --expect-sundials refuses to run (exit 3) if that is not the one named.\n"
         "  --merge: the fair table from raw CSVs of both builds (scripts/work-precision).\n"
         "  --quick: correctness checks and a few settings, one run each.\n",
         prog, prog);
}

int main(int argc, char **argv)
{
  const char *csv = "work_precision.csv", *png = "work_precision.png", *expect = NULL;
  const char *merge = NULL, *sundials;
  int quick = 0, reps = 3, i, nruns = 0, ncv = 0, ncv_top = 0, fails = 0, nin = 0;
  double t1 = T_END, t_start = WallSeconds();
  LGNRefHeavyTop ref;
  static Run runs[MAXRUNS];
  static char *inputs[256];
  Curve cv[MAXCURVES];

  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--quick") == 0) quick = 1;
    else if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csv = argv[++i];
    else if (strcmp(argv[i], "--png") == 0 && i + 1 < argc) png = argv[++i];
    else if (strcmp(argv[i], "--no-png") == 0) png = NULL;
    else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) reps = atoi(argv[++i]);
    else if (strcmp(argv[i], "--expect-sundials") == 0 && i + 1 < argc) expect = argv[++i];
    else if (strcmp(argv[i], "--merge") == 0 && i + 1 < argc) merge = argv[++i];
    else if (strcmp(argv[i], "--chain-reference") == 0) {
      ChainReference();
      return 0;
    } else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
      Usage(argv[0]);
      return 0;
    } else if (merge != NULL && argv[i][0] != '-' && nin < 256) {
      inputs[nin++] = argv[i];
    } else {
      Usage(argv[0]);
      return 2;
    }
  }
  if (merge != NULL) {
    if (nin == 0) {
      Usage(argv[0]);
      return 2;
    }
    return Merge(merge, png, nin, inputs);
  }
  if (reps < 1 || reps > 64) {
    fprintf(stderr, "work_precision: --reps must be in 1..64\n");
    return 2;
  }
  if (quick) reps = 1;
  if (quick) g_max_steps = MAX_STEPS_QUICK;

  printf("SUNDIALS libraries loaded by this process (IDA, and Lignum's dense LU and vectors):\n");
  sundials = DetectSundials(1);
  printf("SUNDIALS build: %s\n", strcmp(sundials, "O2") == 0 ? "-O2 (bench/build-ida-O2)"
                                 : strcmp(sundials, "debian") == 0 ? "Debian's packages (-O0)"
                                                                    : sundials);
  if (expect != NULL && strcmp(expect, sundials) != 0) {
    fprintf(stderr, "work_precision: expected the %s SUNDIALS build but loaded '%s': refusing "
                    "to label this run\n", expect, sundials);
    return 3;
  }

  if (lgnref_heavy_top(&t1, 1, &ref, LGNREF_FEHLBERG_8) != 0) {
    fprintf(stderr, "work_precision: reference solution failed\n");
    return 1;
  }
  printf("Heavy top and 3-rod chain work-precision, t in [0, %g] s; heavy top error =\n"
         "|x(1) - x_ref(1)|_2 against ARKODE Fehlberg 7(8) (models/lgn_reference.c); chain error =\n"
         "|tip(1) - tip_ref(1)|_2 against IDA at rtol 1e-12 (--chain-reference); CPU = best\n"
         "of %d run(s), process CPU time of the integration only.\n", T_END, reps);
  if (quick) fails = QuickChecks(&ref);

  nruns = BuildRuns(quick, runs, cv, &ncv, &ncv_top);
  for (i = 0; i < nruns; i++) Measure(&runs[i], &ref, reps);

  if (WriteCsv(csv, runs, nruns, sundials) != 0) fails++;
  printf("\nHeavy top");
  PrintRuns(cv, ncv_top, runs);
  printf("\nChain of %d rods (tip error)", CHAIN_N);
  PrintRuns(cv + ncv_top, ncv - ncv_top, runs);
  PrintSummary(cv, ncv_top, runs, 0);
  PrintSummary(cv + ncv_top, ncv - ncv_top, runs, 1);
  {
    char acsv[4096], apng[4096];
    SiblingPath(csv, "_adaptive", ".csv", acsv, sizeof acsv);
    if (PrintAdaptive(cv, ncv_top, runs, acsv) != 0) fails++;
    printf("\nCSV: %s, %s\n", csv, acsv);
    fflush(stdout);
    if (png != NULL && !quick) {
      WritePlot(png, cv, ncv_top, runs);
      SiblingPath(png, "_adaptive", ".png", apng, sizeof apng);
      WriteAdaptivePlot(apng, acsv, cv, ncv_top);
    }
  }
  printf("Total wall time %.1f s (SUNDIALS: %s)\n", WallSeconds() - t_start, sundials);
  return fails ? 1 : 0;
}
