/* -----------------------------------------------------------------------------
 * Lignum benchmarks: what a tolerance buys (issue 30, item 2). At
 * rtol = atol = tol = 1e-4 ... 1e-10 the global error of Lignum's BDF
 * (maxord 5) and generalized-alpha (rho_inf 0.9, LGNSetErrorPerUnitStep),
 * each with full and with modified Newton, and of SUNDIALS IDA (GGL index
 * 2 in Euler parameters, dense, difference-quotient Jacobian, algebraic
 * variables suppressed, rtol = atol = tol on every differential component),
 * on the heavy top (t = 1, error of the centre of mass against the ARKODE
 * reference, models/lgn_reference.c) and the 3-rod chain (t = 1, error of the tip
 * against IDA at rtol 1e-12, bench/work_precision --chain-reference), and
 * the suite's Andrews mechanism, car axis and IFToMM A01 pendulum
 * (bench/suite: its error measures and references; IDA at index 2).
 *
 * Printed per problem and method: tol, error, error / tol, steps, failed
 * error tests, Newton iterations, LU factorisations; then per method the
 * exponent p of a least-squares fit of log error against log tol, whether
 * the error falls at every decade, and the band of error / tol against
 * IDA's (Lignum / IDA at each tol). --csv FILE writes the rows.
 * A program to run by hand (`cmake --build build --target run_tolerance_band`);
 * the bands are asserted by test/core/test_tolerance.c.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_ls.h>

#include "ida_chain.h"
#include "suite_run.h"
#include "ida_heavy_top.h"
#include "lgn_reference.h"
#include "models/chain.h"
#include "models/heavy_top.h"

#define T_END  1.0
#define NTOL   7 /* tol = 1e-4 ... 1e-10 */
#define CHAIN_N 3
static const double CHAIN_TIP_REF[3] = {-1.855169400564356, -6.545653961586941e-03,
                                        -2.068593335280935};

static const char *const PROBLEMS[5] = {"top", "chain", "andrews", "caraxis", "pendulum"};

typedef struct {
  const char *name;
  int bdf;    /* > 0: BDF maxord; 0: generalized-alpha */
  int newton; /* LGN_NEWTON_* */
  int ida;
} Method;

static const Method METHODS[] = {
  {"BDF5 full",     5, LGN_NEWTON_FULL, 0},
  {"BDF5 modified", 5, LGN_NEWTON_MODIFIED, 0},
  {"g-alpha full",  0, LGN_NEWTON_FULL, 0},
  {"g-alpha mod.",  0, LGN_NEWTON_MODIFIED, 0},
  {"IDA",           0, 0, 1},
};
#define NMETHODS ((int)(sizeof METHODS / sizeof METHODS[0]))

typedef struct {
  int ok;
  double err;
  long int steps, netf, nni, nlu;
} Row;

static double Dist3(const double *a, const double *b)
{
  const double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

static void HeavyTop(const Method *m, double tol, const double xref[3], Row *r)
{
  memset(r, 0, sizeof *r);
  if (m->ida) {
    IdaHTOptions opt;
    IdaHTResult res;
    ida_heavy_top_default_options(&opt);
    opt.linsol = IDAHT_DENSE_DQ;
    opt.rtol = tol;
    opt.t_end = T_END;
    opt.scale_x = opt.scale_p = opt.scale_xd = opt.scale_pd = 1.0; /* atol = tol */
    opt.h0 = 1e-6; /* (IDA's own first step fails at tol <= 1e-7 here) */
    ida_heavy_top_run(&opt, &res);
    r->ok = res.flag == 0 && fabs(res.t - T_END) < 1e-12;
    r->err = Dist3(res.x, xref);
    r->steps = res.nsteps;
    r->netf = res.netf;
    r->nni = res.nniters;
    r->nlu = res.njevals;
  } else {
    HeavyTopOptions opt;
    HeavyTopResult res;
    heavy_top_default_options(&opt);
    opt.method = HT_GENALPHA;
    opt.rho_inf = 0.9;
    opt.kinematics = LGN_KINEMATICS_EXACT;
    opt.constraints = LGN_CONSTR_INDEX3;
    opt.newton = m->newton;
    opt.adaptive = 1;
    opt.rtol = opt.atol = tol;
    opt.h = T_END;
    opt.t_end = T_END;
    opt.analytic_jacobians = 1;
    opt.single_solve = 1;
    opt.bdf_maxord = m->bdf;
    opt.make_ls = LGNLinSol_Dense;
    heavy_top_run(&opt, &res);
    r->ok = res.flag == LGN_SUCCESS && fabs(res.t - T_END) < 1e-12;
    r->err = Dist3(res.x, xref);
    r->steps = res.nsteps;
    r->netf = res.netfails;
    r->nni = res.nniters;
    r->nlu = res.nlsetups;
  }
}

static void Chain(const Method *m, double tol, Row *r)
{
  memset(r, 0, sizeof *r);
  if (m->ida) {
    IdaChainOptions opt;
    IdaChainResult res;
    ida_chain_default_options(&opt);
    opt.n = CHAIN_N;
    opt.linsol = IDACH_DENSE_DQ;
    opt.rtol = tol;
    opt.t_end = T_END;
    opt.scale_v = 1.0; /* atol = tol */
    ida_chain_run(&opt, &res);
    r->ok = res.flag == 0 && fabs(res.t - T_END) < 1e-12;
    r->err = Dist3(res.tip, CHAIN_TIP_REF);
    r->steps = res.nsteps;
    r->nni = res.nniters;
    r->nlu = res.njevals;
  } else {
    SUNContext ctx = NULL;
    RigidSystem *sys = NULL;
    RigidRunOptions opt;
    RigidRunResult res;
    double tip[3] = {NAN, NAN, NAN};
    memset(&res, 0, sizeof res);
    if (SUNContext_Create(NULL, &ctx) != 0) return;
    sys = chain_create(CHAIN_N, RB_R3XSO3, ctx);
    if (sys != NULL) {
      rigid_default_run_options(&opt);
      opt.solver = RB_DENSE;
      opt.method = 1;
      opt.rho_inf = 0.9;
      opt.kinematics = LGN_KINEMATICS_EXACT;
      opt.constraints = LGN_CONSTR_INDEX3;
      opt.newton = m->newton;
      opt.analytic = 1;
      opt.t_end = T_END;
      opt.outputs = 1;
      opt.bdf_maxord = m->bdf;
      opt.own_dense_lu = 1;
      opt.adaptive = 1;
      opt.rtol = opt.atol = tol;
      opt.h = 1e-4;
      rigid_run(sys, &opt, &res);
      if (res.q != NULL) ida_chain_tip(CHAIN_N, res.q, tip);
      r->ok = res.flag == LGN_SUCCESS && fabs(res.t - T_END) < 1e-12;
      r->err = Dist3(tip, CHAIN_TIP_REF);
      r->steps = res.nsteps;
      r->netf = res.netf;
      r->nni = res.nni;
      r->nlu = res.nlsetups;
      rigid_result_free(&res);
      rigid_free(&sys);
    }
    SUNContext_Free(&ctx);
  }
}

/* The suite's problems (bench/suite): its error measure, Lignum's public
 * API on R^n, IDA at index 2 with IDASetId / IDASetSuppressAlg.
 * Generalized-alpha (order 2, error per unit step) only down to GA_TOL_MIN
 * (A01 over 2000 s: 1e-6): its steps grow like tol^(-1/2). */
static void Suite(const char *name, const Method *m, double tol, Row *r)
{
  const SuiteProblem *pb = suite_problem(name);
  SuiteResult res;
  memset(r, 0, sizeof *r);
  r->err = NAN;
  if (pb == NULL) return;
  if (!m->ida && m->bdf == 0 && tol < (strcmp(name, "pendulum") == 0 ? 1e-6 : 1e-8)) return;
  if (m->ida) {
    suite_ida_run(pb, tol, 0, SUITE_IDA_INDEX2, &res);
  } else {
    SuiteLignumMethod lm;
    lm.bdf_maxord = m->bdf;
    lm.rho_inf = 0.9;
    lm.constraints = LGN_CONSTR_INDEX3;
    lm.newton = m->newton;
    suite_lignum_run(pb, &lm, tol, &res);
  }
  r->ok = res.flag == 0;
  r->err = res.err;
  r->steps = res.nsteps;
  r->netf = res.nrejected;
  r->nni = res.nniters;
  r->nlu = res.nlu;
}

/* slope of log err against log tol (least squares) */
static double Exponent(const Row *rows, const double *tols, int n)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int i, k = 0;
  for (i = 0; i < n; i++) {
    double x, y;
    if (!rows[i].ok || !(rows[i].err > 0.0)) continue;
    x = log10(tols[i]);
    y = log10(rows[i].err);
    sx += x; sy += y; sxx += x * x; sxy += x * y;
    k++;
  }
  if (k < 2) return NAN;
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

int main(int argc, char **argv)
{
  const char *csvname = NULL, *only = NULL;
  double tols[NTOL];
  Row rows[5][NMETHODS][NTOL];
  LGNRefHeavyTop ref;
  const double tref = T_END;
  FILE *csv = NULL;
  int i, j, p, ntol = NTOL;
  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csvname = argv[++i];
    else if (strcmp(argv[i], "--problem") == 0 && i + 1 < argc) only = argv[++i];
    else {
      printf("usage: %s [--csv FILE] [--problem top|chain|andrews|caraxis|pendulum]\n",
             argv[0]);
      return 2;
    }
  }
  for (i = 0; i < ntol; i++) tols[i] = pow(10.0, -4.0 - i);
  if (lgnref_heavy_top(&tref, 1, &ref, 1) != 0) return 1;
  if (csvname != NULL && (csv = fopen(csvname, "w")) == NULL) return 1;
  if (csv) fprintf(csv, "problem,method,tol,err,steps,netf,nni,nlu\n");
  for (p = 0; p < 5; p++) {
    const char *pname = PROBLEMS[p];
    if (only != NULL && strcmp(only, pname) != 0) continue;
    printf("\n== %s: error / tol (steps, failed tests, Newton its, LUs)\n", pname);
    for (j = 0; j < NMETHODS; j++) {
      printf("%-14s", METHODS[j].name);
      for (i = 0; i < ntol; i++) {
        Row *r = &rows[p][j][i];
        if (p == 0) HeavyTop(&METHODS[j], tols[i], ref.x, r);
        else if (p == 1) Chain(&METHODS[j], tols[i], r);
        else Suite(pname, &METHODS[j], tols[i], r);
        if (csv)
          fprintf(csv, "%s,%s,%g,%.6e,%ld,%ld,%ld,%ld\n", pname,
                  METHODS[j].name, tols[i], r->ok ? r->err : NAN, r->steps, r->netf, r->nni,
                  r->nlu);
      }
      printf("\n");
      for (i = 0; i < ntol; i++) {
        const Row *r = &rows[p][j][i];
        printf("  tol %.0e  err %.3e  err/tol %9.1f  (%ld, %ld, %ld, %ld)%s\n", tols[i], r->err,
               r->err / tols[i], r->steps, r->netf, r->nni, r->nlu, r->ok ? "" : "  FAILED");
      }
    }
    printf("-- %s summary: exponent p, monotone, max err/tol, max ratio to IDA\n", pname);
    for (j = 0; j < NMETHODS; j++) {
      int mono = 1;
      double worst = 0.0, ratio = 0.0;
      for (i = 0; i < ntol; i++) {
        const Row *r = &rows[p][j][i];
        if (r->steps == 0) continue; /* not run */
        worst = fmax(worst, r->err / tols[i]);
        if (rows[p][NMETHODS - 1][i].ok) ratio = fmax(ratio, r->err / rows[p][NMETHODS - 1][i].err);
        if (i > 0 && !(r->err < rows[p][j][i - 1].err)) mono = 0;
      }
      printf("%-14s p = %.3f  %s  max err/tol %.1f  max err/IDA %.2f\n", METHODS[j].name,
             Exponent(rows[p][j], tols, ntol), mono ? "monotone" : "NOT monotone", worst, ratio);
    }
  }
  if (csv) fclose(csv);
  return 0;
}
