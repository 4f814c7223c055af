/* -----------------------------------------------------------------------------
 * Lignum study: the two forms of the BDF (LGNSetBDFForm) under error control
 * on the heavy top (R^3 x SO(3), the body and joint helpers, as test_bdf):
 * variable coefficients (LGN_BDF_VARIABLE_COEFF) and fixed leading
 * coefficient (LGN_BDF_FIXED_LEADING), maxord 4 and 5, full and modified
 * Newton, tol = 1e-6, 3.16e-7, 1e-7, ..., 1e-10 (half decades: a controller
 * that settles early shows there as an error out of line with its
 * neighbours). For each run: the error of the centre of mass at t = 1
 * against the ARKODE reference (Fehlberg 8, about 1e-13), steps, Newton
 * iterations, Jacobian (iteration matrix) evaluations, error test failures,
 * steps at orders 1 ... 5; then per series the fitted exponent of error
 * against tol and the largest ratio of a half-decade error to the
 * geometric mean of its two decade neighbours.
 *
 *   bdf_forms [file.csv]    the table on stdout, the same rows as CSV
 *                           (default bdf_forms.csv)
 *   bdf_forms --perturb tol the steps and errors at tol (1 + i 1e-13),
 *                           i = 0 ... 5: the controller's sensitivity
 *   bdf_forms --run VC|FLC maxord tol   one run (modified Newton), e.g.
 *                           under valgrind --tool=callgrind
 *   bdf_forms --series VC|FLC maxord [n]  modified Newton at n tolerances
 *                           per decade from 1e-6 to 1e-10 (default 2, the
 *                           half decades): error, steps, orders, and the
 *                           regularity (each interior point against the
 *                           geometric mean of its two neighbours) and the
 *                           fitted exponent of error against tol
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "lgn_reference.h"

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Top;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Top *)ud)->bodies);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Top *)ud)->bodies);
}
static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  Top *top = (Top *)ud;
  if (LGNBodies_StiffnessFn(t, q, v, vdot, lambda, K, top->bodies)) return -1;
  return LGNJoints_Stiffness(top->joints, t, q, lambda, K) ? -1 : 0;
}
static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  return LGNBodies_DampingFn(t, q, v, C, ((Top *)ud)->bodies);
}
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Top *)ud)->joints, t, q, phi) ? -1 : 0;
}
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Top *)ud)->joints, t, q, B) ? -1 : 0;
}
static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Top *)ud)->joints, t, q, v, z) ? -1 : 0;
}

typedef struct {
  double err;
  long int nst, nni, nje, netf, nord[6];
  int flag;
} Result;

/* One error-controlled run to t = 1. */
static Result HeavyTop(SUNContext ctx, int form, int maxord, int newton, double tol,
                       const LGNRefHeavyTop *ref)
{
  const sunrealtype J[3] = {0.234375, 0.46875, 0.234375}, grav[3] = {0, 0, -9.81};
  const sunrealtype s[3] = {0, -1, 0}, o[3] = {0, 0, 0};
  const sunrealtype Om[3] = {0, 150, -4.61538}, X[3] = {0, 1, 0};
  LGNGroup G = LGNGroup_R3xSO3();
  Top top;
  N_Vector q = N_VNew_Serial(7, ctx), v = N_VNew_Serial(6, ctx), y = N_VNew_Serial(9, ctx);
  SUNMatrix A = SUNDenseMatrix(9, 9, ctx);
  SUNLinearSolver LS = LGNLinSol_Dense(y, A, ctx);
  void *mem = LGNCreate(ctx);
  sunrealtype *qq = N_VGetArrayPointer(q), *vv = N_VGetArrayPointer(v), t;
  Result r;
  int flag, i;
  memset(&r, 0, sizeof r);
  r.err = HUGE_VAL;
  top.bodies = LGNBodies_Create(G);
  top.joints = LGNJoints_Create(G);
  LGNBodies_SetPrincipalInertia(top.bodies, 0, 15.0, J);
  LGNBodies_SetGravity(top.bodies, grav);
  LGNJoints_AddSpherical(top.joints, 0, s, LGN_GROUND, o);
  qq[0] = X[0]; qq[1] = X[1]; qq[2] = X[2];
  qq[3] = 1; qq[4] = qq[5] = qq[6] = 0;
  vv[0] = Om[1] * X[2] - Om[2] * X[1];
  vv[1] = Om[2] * X[0] - Om[0] * X[2];
  vv[2] = Om[0] * X[1] - Om[1] * X[0];
  vv[3] = Om[0]; vv[4] = Om[1]; vv[5] = Om[2];
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetErrFile(mem, NULL); /* the stall notes */
  if (!flag) flag = LGNSetUserData(mem, &top);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetConstraints(mem, 3, Constr, ConstrJac);
  if (!flag) flag = LGNSetStiffnessFn(mem, Stiffness);
  if (!flag) flag = LGNSetDampingFn(mem, Damping);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetBDF(mem, maxord);
  if (!flag) flag = LGNSetBDFForm(mem, form);
  if (!flag) flag = LGNSetNewtonMode(mem, newton);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, tol, tol);
  if (!flag) flag = LGNSetStopTime(mem, 1.0);
  if (!flag) flag = LGNSolve(mem, 1.0, &t, q, v, LGN_NORMAL);
  if (flag == LGN_TSTOP_RETURN) flag = LGN_SUCCESS;
  r.flag = flag;
  if (!flag) {
    r.err = 0.0;
    for (i = 0; i < 3; i++) r.err = fmax(r.err, fabs(qq[i] - ref->x[i]));
  }
  LGNGetNumSteps(mem, &r.nst);
  LGNGetNumNewtonIters(mem, &r.nni);
  LGNGetNumJacEvals(mem, &r.nje);
  LGNGetNumErrTestFails(mem, &r.netf);
  LGNGetNumStepsAtOrder(mem, r.nord);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(y);
  LGNJoints_Destroy(&top.joints);
  LGNBodies_Destroy(&top.bodies);
  LGNGroup_Destroy(G);
  return r;
}

#define NTOL 9

/* --perturb tol: maxord 4 and 5, modified Newton, each form at tol (1 + i
 * 1e-13), i = 0 ... 5: steps and error of each run (a controller whose
 * decisions are robust gives the same steps). */
static int Perturb(double tol, const LGNRefHeavyTop *ref)
{
  SUNContext ctx;
  int f, k, i;
  SUNContext_Create(NULL, &ctx);
  printf("tol %g (1 + i 1e-13), i = 0 ... 5: steps / error at t = 1, modified Newton\n", tol);
  for (f = 0; f < 2; f++)
    for (k = 4; k <= 5; k++) {
      printf("%-3s maxord %d:", f ? "FLC" : "VC", k);
      for (i = 0; i < 6; i++) {
        const Result r = HeavyTop(ctx, f ? LGN_BDF_FIXED_LEADING : LGN_BDF_VARIABLE_COEFF, k,
                                  LGN_NEWTON_MODIFIED, tol * (1.0 + 1e-13 * i), ref);
        printf(" %ld/%.3e", r.nst, r.err);
      }
      printf("\n");
    }
  SUNContext_Free(&ctx);
  return 0;
}

/* --series: one form and maxord at n tolerances per decade, 1e-6 ... 1e-10
 * (modified Newton). The regularity is the largest ratio, either way, of an
 * error to the geometric mean of its two neighbours' (at n = 2: every half
 * decade and every decade, not only the half decades as in the table). */
static int Series(const char *fname, int maxord, int per_decade, const LGNRefHeavyTop *ref)
{
  const int form = !strcmp(fname, "FLC") ? LGN_BDF_FIXED_LEADING : LGN_BDF_VARIABLE_COEFF;
  const int n = 4 * per_decade + 1;
  double err[4 * 20 + 1], tol[4 * 20 + 1], sx = 0, sy = 0, sxx = 0, sxy = 0, worst = 0;
  long int steps = 0;
  SUNContext ctx;
  int i, failed = 0;
  if (per_decade < 1 || per_decade > 20) return 1;
  SUNContext_Create(NULL, &ctx);
  printf("%s maxord %d, modified Newton\n%10s %10s %6s %4s  %s\n", fname, maxord, "tol",
         "error", "steps", "etf", "orders 1-5");
  for (i = 0; i < n; i++) {
    Result r;
    tol[i] = pow(10.0, -6.0 - (double)i / per_decade);
    r      = HeavyTop(ctx, form, maxord, LGN_NEWTON_MODIFIED, tol[i], ref);
    err[i] = r.err;
    steps += r.nst;
    failed |= r.flag != 0;
    printf("%10.4g %10.3e %6ld %4ld  %ld %ld %ld %ld %ld%s\n", tol[i], r.err, r.nst, r.netf,
           r.nord[1], r.nord[2], r.nord[3], r.nord[4], r.nord[5], r.flag ? "  (failed)" : "");
    sx += log(tol[i]);
    sy += log(r.err);
    sxx += log(tol[i]) * log(tol[i]);
    sxy += log(tol[i]) * log(r.err);
  }
  for (i = 1; i + 1 < n; i++) {
    const double gm = sqrt(err[i - 1] * err[i + 1]);
    worst = fmax(worst, fmax(err[i] / gm, gm / err[i]));
  }
  printf("error ~ tol^%.3f; off the neighbours' geometric mean by up to %.2f; %ld steps in all\n",
         (n * sxy - sx * sy) / (n * sxx - sx * sx), worst, steps);
  SUNContext_Free(&ctx);
  return failed;
}

int main(int argc, char **argv)
{
  const char *csv_name = argc > 1 ? argv[1] : "bdf_forms.csv";
  const double t_end = 1.0;
  double tols[NTOL];
  LGNRefHeavyTop ref;
  SUNContext ctx;
  FILE *csv;
  int f, k, nm, i;
  for (i = 0; i < NTOL; i++) tols[i] = pow(10.0, -6.0 - 0.5 * i);
  if (lgnref_heavy_top(&t_end, 1, &ref, LGNREF_FEHLBERG_8) != 0) return 1;
  if (argc == 3 && !strcmp(argv[1], "--perturb")) return Perturb(atof(argv[2]), &ref);
  if ((argc == 4 || argc == 5) && !strcmp(argv[1], "--series"))
    return Series(argv[2], atoi(argv[3]), argc == 5 ? atoi(argv[4]) : 2, &ref);
  if (argc == 5 && !strcmp(argv[1], "--run")) { /* one run, e.g. under callgrind */
    const int form = !strcmp(argv[2], "FLC") ? LGN_BDF_FIXED_LEADING : LGN_BDF_VARIABLE_COEFF;
    Result r;
    SUNContext_Create(NULL, &ctx);
    r = HeavyTop(ctx, form, atoi(argv[3]), LGN_NEWTON_MODIFIED, atof(argv[4]), &ref);
    printf("%s maxord %s tol %s: error %.3e, %ld steps, %ld Newton, %ld Jacobians, %ld etf\n",
           argv[2], argv[3], argv[4], r.err, r.nst, r.nni, r.nje, r.netf);
    SUNContext_Free(&ctx);
    return r.flag != 0;
  }
  csv = fopen(csv_name, "w");
  if (csv == NULL) {
    fprintf(stderr, "bdf_forms: cannot write %s\n", csv_name);
    return 1;
  }
  SUNContext_Create(NULL, &ctx);
  fprintf(csv, "form,maxord,newton,tol,error,steps,newton_iters,jac_evals,etf,"
               "ord1,ord2,ord3,ord4,ord5\n");
  printf("heavy top to t = 1: error of the centre of mass, steps, Newton iterations,\n"
         "Jacobian evaluations, error test failures, steps at orders 1-5\n");
  for (nm = 0; nm < 2; nm++) {
    const int newton = nm == 0 ? LGN_NEWTON_MODIFIED : LGN_NEWTON_FULL;
    for (k = 4; k <= 5; k++) {
      for (f = 0; f < 2; f++) {
        const int form = f == 0 ? LGN_BDF_VARIABLE_COEFF : LGN_BDF_FIXED_LEADING;
        const char *fname = f == 0 ? "VC" : "FLC", *nname = nm == 0 ? "modified" : "full";
        double err[NTOL], sx = 0, sy = 0, sxx = 0, sxy = 0, worst = 0;
        printf("\n%s, maxord %d, %s Newton\n%9s %10s %6s %7s %6s %4s  %s\n", fname, k, nname,
               "tol", "error", "steps", "newton", "jac", "etf", "orders 1-5");
        for (i = 0; i < NTOL; i++) {
          const Result r = HeavyTop(ctx, form, k, newton, tols[i], &ref);
          err[i] = r.err;
          printf("%9.3g %10.3e %6ld %7ld %6ld %4ld  %ld %ld %ld %ld %ld%s\n", tols[i], r.err,
                 r.nst, r.nni, r.nje, r.netf, r.nord[1], r.nord[2], r.nord[3], r.nord[4],
                 r.nord[5], r.flag ? "  (failed)" : "");
          fprintf(csv, "%s,%d,%s,%.6g,%.6e,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld\n", fname, k,
                  nname, tols[i], r.err, r.nst, r.nni, r.nje, r.netf, r.nord[1], r.nord[2],
                  r.nord[3], r.nord[4], r.nord[5]);
          sx += log(tols[i]);
          sy += log(r.err);
          sxx += log(tols[i]) * log(tols[i]);
          sxy += log(tols[i]) * log(r.err);
        }
        for (i = 1; i < NTOL; i += 2) {
          const double gm = sqrt(err[i - 1] * err[i + 1]);
          worst = fmax(worst, fmax(err[i] / gm, gm / err[i]));
        }
        printf("error ~ tol^%.3f; half decades off the neighbours' geometric mean by "
               "up to a factor %.2f\n",
               (NTOL * sxy - sx * sy) / (NTOL * sxx - sx * sx), worst);
      }
    }
  }
  fclose(csv);
  SUNContext_Free(&ctx);
  printf("\nCSV: %s\n", csv_name);
  return 0;
}
