/* -----------------------------------------------------------------------------
 * Lignum study tool: the heavy top (Brüls and Cardona 2010) from the command line.
 *
 *   heavy_top [--formulation lie|se3|ep] [--method newmark|genalpha] [--rho-inf R]
 *             [--beta B --gamma G] [--constraints index3|index2|ggl]
 *             [--kinematics simplified|exact|sigma] [--jacobian analytic|dq]
 *             [--h H] [--t-end T] [--a0 consistent|zero]
 *             [--predictor zero|extrapolate] [--newton full|modified] [--msbp N]
 *             [--rtol R] [--atol A] [--adaptive] [--csv FILE]
 *             [--linsol sundials|lignum] [--single-solve]
 *             [--reference-h H [--bound B]]
 *
 * Prints the final state, one line "com_final <x> <y> <z>" with 17
 * significant digits, and the integrator statistics. Exit status 0 on success.
 *
 * --adaptive: error control (LGN_STEP_ADAPTIVE). --rtol and --atol are then
 * the error test's tolerances (default 1e-6 both here), --h is the output
 * interval (LGN_NORMAL interpolates there), and the run lands on t_end
 * exactly (LGNSetStopTime). Without it they are the Newton tolerances.
 *
 * --linsol: the dense linear solver, SUNLinSol_Dense (default) or Lignum's
 * LGNLinSol_Dense (bench/heavy_top_profile measures the floor with both).
 * --single-solve: one LGNSolve call to t_end, no per-step output (max_phi
 * is then not measured), so that cpu_seconds is the integration only.
 *
 * --reference-h H: also run the same method with the fixed step H (Newton
 * tolerances 1e-10) and print |com_final - com_ref|_max; with --bound B the
 * exit status is 1 unless it is below B.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/heavy_top.h"

static void Usage(const char *prog)
{
  fprintf(stderr,
          "usage: %s [--formulation lie|se3|ep] [--method newmark|genalpha]\n"
          "          [--rho-inf R] [--beta B --gamma G] [--constraints index3|index2|ggl]\n"
          "          [--kinematics simplified|exact|sigma]\n"
          "          [--jacobian analytic|dq] [--h H] [--t-end T]\n"
          "          [--a0 consistent|zero] [--predictor zero|extrapolate]\n"
          "          [--newton full|modified] [--msbp N] (modified Newton:\n"
          "          max steps between matrix setups)\n"
          "          [--rtol R] [--atol A] (Newton tolerances; with --adaptive\n"
          "          the error test's, default 1e-6)\n"
          "          [--adaptive] (error control; --h is then the output interval)\n"
          "          [--csv FILE] [--linsol sundials|lignum] [--single-solve]\n"
          "          [--reference-h H [--bound B]] (compare com_final with a\n"
          "          fixed-step run of step H; fail unless within B)\n", prog);
}

/* Parse a number; returns 0 on success. */
static int ParseReal(const char *s, double *x)
{
  char *end;
  *x = strtod(s, &end);
  return (end == s || *end != '\0' || !isfinite(*x)) ? 1 : 0;
}

static int ParseArgs(int argc, char **argv, HeavyTopOptions *opt,
                     const char **csv_path, double *ref_h, double *bound)
{
  int i = 1;
  while (i < argc) {
    const char *key = argv[i], *val;
    int bad = 0;
    /* flags without a value */
    if (!strcmp(key, "--adaptive")) {
      opt->adaptive = 1;
      i++;
      continue;
    }
    if (!strcmp(key, "--single-solve")) {
      opt->single_solve = 1;
      i++;
      continue;
    }
    /* every other option takes a value */
    if (i + 1 >= argc) {
      fprintf(stderr, "heavy_top: option %s needs a value\n", key);
      return 1;
    }
    val = argv[i + 1];
    i += 2;
    if (!strcmp(key, "--formulation")) {
      if (!strcmp(val, "lie")) opt->formulation = HT_LIE;
      else if (!strcmp(val, "se3")) opt->formulation = HT_SE3;
      else if (!strcmp(val, "ep")) opt->formulation = HT_EULER_PARAMETERS;
      else bad = 1;
    } else if (!strcmp(key, "--method")) {
      if (!strcmp(val, "newmark")) opt->method = HT_NEWMARK;
      else if (!strcmp(val, "genalpha")) opt->method = HT_GENALPHA;
      else bad = 1;
    } else if (!strcmp(key, "--constraints")) {
      if (!strcmp(val, "index3")) opt->constraints = LGN_CONSTR_INDEX3;
      else if (!strcmp(val, "index2")) opt->constraints = LGN_CONSTR_INDEX2;
      else if (!strcmp(val, "ggl")) opt->constraints = LGN_CONSTR_GGL;
      else bad = 1;
    } else if (!strcmp(key, "--kinematics")) {
      if (!strcmp(val, "simplified")) opt->kinematics = LGN_KINEMATICS_SIMPLIFIED;
      else if (!strcmp(val, "exact")) opt->kinematics = LGN_KINEMATICS_EXACT;
      else if (!strcmp(val, "sigma")) opt->kinematics = LGN_KINEMATICS_SIGMA;
      else bad = 1;
    } else if (!strcmp(key, "--jacobian")) {
      if (!strcmp(val, "analytic")) opt->analytic_jacobians = 1;
      else if (!strcmp(val, "dq")) opt->analytic_jacobians = 0;
      else bad = 1;
    } else if (!strcmp(key, "--newton")) {
      if (!strcmp(val, "full")) opt->newton = LGN_NEWTON_FULL;
      else if (!strcmp(val, "modified")) opt->newton = LGN_NEWTON_MODIFIED;
      else bad = 1;
    } else if (!strcmp(key, "--linsol")) {
      if (!strcmp(val, "sundials")) opt->make_ls = NULL;
      else if (!strcmp(val, "lignum")) opt->make_ls = LGNLinSol_Dense;
      else bad = 1;
    } else if (!strcmp(key, "--msbp")) {
      double msbp;
      bad = ParseReal(val, &msbp) || msbp != floor(msbp);
      opt->msbp = (long int)msbp;
    } else if (!strcmp(key, "--predictor")) {
      if (!strcmp(val, "zero")) opt->predictor = LGN_PREDICTOR_ZERO;
      else if (!strcmp(val, "extrapolate")) opt->predictor = LGN_PREDICTOR_EXTRAPOLATE;
      else bad = 1;
    } else if (!strcmp(key, "--a0")) {
      if (!strcmp(val, "consistent")) opt->zero_a0 = 0;
      else if (!strcmp(val, "zero")) opt->zero_a0 = 1;
      else bad = 1;
    } else if (!strcmp(key, "--rho-inf")) bad = ParseReal(val, &opt->rho_inf);
    else if (!strcmp(key, "--beta")) bad = ParseReal(val, &opt->beta);
    else if (!strcmp(key, "--gamma")) bad = ParseReal(val, &opt->gamma);
    else if (!strcmp(key, "--h")) bad = ParseReal(val, &opt->h) || !(opt->h > 0.0);
    else if (!strcmp(key, "--t-end")) bad = ParseReal(val, &opt->t_end) || !(opt->t_end > 0.0);
    else if (!strcmp(key, "--rtol")) bad = ParseReal(val, &opt->rtol) || opt->rtol < 0.0;
    else if (!strcmp(key, "--atol")) bad = ParseReal(val, &opt->atol) || opt->atol < 0.0;
    else if (!strcmp(key, "--csv")) *csv_path = val;
    else if (!strcmp(key, "--reference-h")) bad = ParseReal(val, ref_h) || !(*ref_h > 0.0);
    else if (!strcmp(key, "--bound")) bad = ParseReal(val, bound) || !(*bound > 0.0);
    else bad = 1;
    if (bad) {
      fprintf(stderr, "heavy_top: bad option or value: %s %s\n", key, val);
      return 1;
    }
  }
  return 0;
}

int main(int argc, char **argv)
{
  HeavyTopOptions opt;
  HeavyTopResult res;
  const char *csv_path = NULL;
  char name[128];
  double ref_h = 0.0, bound = 0.0;
  int flag, status;

  heavy_top_default_options(&opt);
  if (ParseArgs(argc, argv, &opt, &csv_path, &ref_h, &bound)) {
    Usage(argv[0]);
    return 2;
  }
  /* error control: tolerances of the error test (the library's defaults,
   * 1e-8, are those of the Newton iteration: too tight as a default here) */
  if (opt.adaptive && opt.rtol <= 0.0) opt.rtol = 1e-6;
  if (opt.adaptive && opt.atol <= 0.0) opt.atol = 1e-6;
  if (csv_path != NULL) {
    opt.csv = fopen(csv_path, "w");
    if (opt.csv == NULL) {
      fprintf(stderr, "heavy_top: cannot open %s\n", csv_path);
      return 2;
    }
  }
  heavy_top_describe(&opt, name, sizeof name);
  printf("Heavy top (Brüls-Cardona 2010), %s, %s formulation\n", name,
         opt.formulation == HT_LIE   ? "R^3 x SO(3)"
         : opt.formulation == HT_SE3 ? "SE(3)"
                                     : "Euler parameters");
  if (opt.adaptive)
    printf("error control: rtol = %g, atol = %g, output every %g, t_end = %g, "
           "Jacobians: %s\n\n", opt.rtol, opt.atol, opt.h, opt.t_end,
           opt.analytic_jacobians ? "analytic" : "difference quotients");
  else
    printf("h = %g, t_end = %g, Jacobians: %s\n\n", opt.h, opt.t_end,
           opt.analytic_jacobians ? "analytic" : "difference quotients");

  flag = heavy_top_run(&opt, &res);
  if (opt.csv != NULL) fclose(opt.csv);

  printf("status     %s\n", LGNGetReturnFlagName(flag));
  printf("t_final    %.17g\n", res.t);
  printf("com_final %.17g %.17g %.17g\n", res.x[0], res.x[1], res.x[2]);
  printf("quat_final %.17g %.17g %.17g %.17g\n", res.p[0], res.p[1], res.p[2], res.p[3]);
  printf("omega_final %.17g %.17g %.17g\n", res.Omega[0], res.Omega[1], res.Omega[2]);
  printf("lambda_final %.17g %.17g %.17g\n", res.lambda[0], res.lambda[1], res.lambda[2]);
  printf("max_phi    %.3e\n\n", res.max_phi);
  printf("steps                 %ld\n", res.nsteps);
  printf("error_test_fails      %ld\n", res.netfails);
  printf("newton_conv_fails     %ld\n", res.nncfails);
  printf("newton_iters          %ld\n", res.nniters);
  printf("newton_per_step       %.4f\n",
         res.nsteps > 0 ? (double)res.nniters / (double)res.nsteps : 0.0);
  printf("residual_evals        %ld\n", res.nres);
  printf("dq_evals              %ld\n", res.ndq);
  printf("jacobian_evals        %ld\n", res.njevals);
  printf("linear_solves         %ld\n", res.nlsolves);
  printf("linear_setups         %ld\n", res.nlsetups);
  printf("cpu_seconds           %.4f\n", res.cpu_seconds);
  status = flag == LGN_SUCCESS ? 0 : 1;

  if (ref_h > 0.0 && status == 0) {
    /* the same method with a fine fixed step */
    HeavyTopOptions ref = opt;
    HeavyTopResult rres;
    double d = 0.0;
    int k, rflag;
    ref.adaptive = 0;
    ref.h        = ref_h;
    ref.rtol = ref.atol = 1e-10;
    ref.csv          = NULL;
    ref.single_solve = 1;
    rflag = heavy_top_run(&ref, &rres);
    for (k = 0; k < 3; k++) d = fmax(d, fabs(res.x[k] - rres.x[k]));
    printf("\nreference  h = %g: status %s, steps %ld, cpu %.4f s\n", ref_h,
           LGNGetReturnFlagName(rflag), rres.nsteps, rres.cpu_seconds);
    printf("com_ref    %.17g %.17g %.17g\n", rres.x[0], rres.x[1], rres.x[2]);
    printf("com_error_vs_reference %.3e", d);
    if (bound > 0.0) printf(" (must be < %g)", bound);
    printf("\n");
    if (rflag != LGN_SUCCESS || (bound > 0.0 && !(d < bound))) status = 1;
  }
  return status;
}
