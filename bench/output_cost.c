/* -----------------------------------------------------------------------------
 * The cost of consistent and projected outputs (LGNSetConsistentOutputs,
 * LGNSetProjectOutputs; doc/user-guide.md §8.5): the motor-driven
 * slider-crank of test/core/test_output_multipliers.c over t in [0, 10]
 * under error control (tol 1e-8, index 3), generalized-alpha (rho_inf 0.9)
 * and BDF (maxord 5), outputs every dt_out = 0.1, 0.01 and 0.001 s
 * (LGN_NORMAL, interpolated), each with the four settings off/off,
 * consistent, projected, both (the default). Prints a table and writes
 * output_cost.csv: CPU seconds (best of 3), steps, linear solver setups,
 * output solves, and the CPU relative to off/off.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#define R_CRANK 0.2
#define L_ROD   0.6
#define PI      3.14159265358979323846

enum { ROTOR = 0, SLIDER_CRANK = 1 };

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
  int model;
} Model;

/* ---- the two mechanisms --------------------------------------------------- */

static int RotorLaw(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 0.5 * sin(3.0 * t);
  f[1] = 1.5 * cos(3.0 * t);
  f[2] = -4.5 * sin(3.0 * t);
  return 0;
}

static int CrankLaw(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 2.0 * PI * t;
  f[1] = 2.0 * PI;
  f[2] = 0.0;
  return 0;
}

/* Inertias of the slider-crank (test_driven.c). */
static const double Jc[3] = {0.01, 0.01, 0.01}, Jr[3] = {0.001, 0.03, 0.03};



static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Model *)ud)->bodies);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Model *)ud)->bodies);
}
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->joints, t, q, phi) ? -1 : 0;
}
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->joints, t, q, B) ? -1 : 0;
}
static int ConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  return LGNJoints_TimeDerivative(((Model *)ud)->joints, t, q, phit) ? -1 : 0;
}
static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->joints, t, q, v, z) ? -1 : 0;
}

/* The model's group, bodies, joints and start (q, v made here). */
static LGNGroup Build(SUNContext ctx, int model, Model *md, LGNGroup body, N_Vector *q,
                      N_Vector *v)
{
  const double ez[3] = {0, 0, 1}, ex[3] = {1, 0, 0}, o[3] = {0, 0, 0};
  LGNGroup f3[3], G;
  double *qd;
  int b, nb = model == ROTOR ? 1 : 3;
  for (b = 0; b < nb; b++) f3[b] = body;
  G = nb == 1 ? body : LGNGroup_Product(nb, f3);
  md->model  = model;
  md->bodies = LGNBodies_Create(G);
  md->joints = LGNJoints_Create(G);
  if (model == ROTOR) {
    const double J[3] = {1.0, 1.0, 2.0};
    LGNBodies_SetPrincipalInertia(md->bodies, 0, 1.0, J);
    LGNJoints_AddRevolute(md->joints, LGN_GROUND, o, ez, 0, o, ez);
    LGNJoints_AddRotationDriver(md->joints, LGN_GROUND, ez, ex, 0, ex, RotorLaw, NULL);
  } else {
    const double pin[3] = {R_CRANK, 0, 0}, rod_a[3] = {-L_ROD / 2, 0, 0};
    const double rod_b[3] = {L_ROD / 2, 0, 0};
    LGNBodies_SetPrincipalInertia(md->bodies, 0, 1.0, Jc);
    LGNBodies_SetPrincipalInertia(md->bodies, 1, 1.0, Jr);
    LGNBodies_SetPrincipalInertia(md->bodies, 2, 1.0, Jc);
    LGNJoints_AddRevolute(md->joints, LGN_GROUND, o, ez, 0, o, ez);
    LGNJoints_AddRotationDriver(md->joints, LGN_GROUND, ez, ex, 0, ex, CrankLaw, NULL);
    LGNJoints_AddSpherical(md->joints, 0, pin, 1, rod_a);
    LGNJoints_AddSpherical(md->joints, 1, rod_b, 2, o);
    LGNJoints_AddPrismatic(md->joints, LGN_GROUND, o, ex, 2, o, ex);
  }
  *q = N_VNew_Serial(G->nq, ctx);
  *v = N_VNew_Serial(G->nv, ctx);
  qd = N_VGetArrayPointer(*q);
  LGNGroup_Identity(G, qd);
  if (model == SLIDER_CRANK) {
    qd[7]  = R_CRANK + L_ROD / 2;
    qd[14] = R_CRANK + L_ROD;
  }
  N_VConst(0.0, *v);
  return G;
}

/* One run: CPU seconds, steps, setups, output solves. */
static double Run(SUNContext ctx, int bdf, double dt_out, sunbooleantype consistent,
                  sunbooleantype project, long int *nst, long int *nls, long int *nout)
{
  LGNGroup body = LGNGroup_R3xSO3(), G;
  Model md;
  N_Vector q, v, y;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  sunrealtype t = 0.0;
  sunindextype m, n;
  clock_t c0;
  double cpu;
  int flag, k, nk = (int)floor(10.0 / dt_out + 0.5);

  G    = Build(ctx, SLIDER_CRANK, &md, body, &q, &v);
  m    = LGNJoints_NumConstraints(md.joints);
  n    = G->nv + m;
  y    = N_VNew_Serial(n, ctx);
  A    = SUNDenseMatrix(n, n, ctx);
  LS   = LGNLinSol_Dense(y, A, ctx);
  mem  = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetConstraintTimeFn(mem, ConstrTime);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = bdf ? LGNSetBDF(mem, 5) : LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, 1e-8, 1e-8);
  if (!flag) flag = LGNSetConsistentOutputs(mem, consistent);
  if (!flag) flag = LGNSetProjectOutputs(mem, project ? LGN_PROJECT_ALL : LGN_PROJECT_NONE);
  if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_V);
  c0 = clock();
  for (k = 1; k <= nk && !flag; k++) flag = LGNSolve(mem, k * dt_out, &t, q, v, LGN_NORMAL);
  cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
  if (flag) {
    fprintf(stderr, "output_cost: flag %d at t = %g\n", flag, t);
    exit(1);
  }
  LGNGetNumSteps(mem, nst);
  LGNGetNumLinSolvSetups(mem, nls);
  LGNGetNumOutputSolves(mem, nout);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  return cpu;
}

int main(void)
{
  static const char *setting[4] = {"off/off", "consistent", "projected", "both (default)"};
  const double dts[3] = {0.1, 0.01, 0.001};
  SUNContext ctx;
  FILE *csv = fopen("output_cost.csv", "w");
  int bdf, d, s, rep;
  SUNContext_Create(NULL, &ctx);
  if (csv != NULL)
    fprintf(csv, "method,dt_out,setting,cpu_s,steps,setups,output_solves,cpu_ratio\n");
  printf("| method | dt_out | setting | CPU s | steps | LS setups | output solves | CPU / off |\n");
  printf("|---|---|---|---|---|---|---|---|\n");
  for (bdf = 0; bdf < 2; bdf++)
    for (d = 0; d < 3; d++) {
      double base = 0.0;
      for (s = 0; s < 4; s++) {
        double best = HUGE_VAL;
        long int nst = 0, nls = 0, nout = 0;
        for (rep = 0; rep < 3; rep++)
          best = fmin(best, Run(ctx, bdf, dts[d], (sunbooleantype)(s & 1),
                                (sunbooleantype)((s >> 1) & 1), &nst, &nls, &nout));
        if (s == 0) base = best;
        printf("| %s | %g | %s | %.3f | %ld | %ld | %ld | %.2f |\n", bdf ? "BDF5" : "gen-alpha",
               dts[d], setting[s], best, nst, nls, nout, best / base);
        if (csv != NULL)
          fprintf(csv, "%s,%g,%s,%.4f,%ld,%ld,%ld,%.3f\n", bdf ? "BDF5" : "gen-alpha", dts[d],
                  setting[s], best, nst, nls, nout, best / base);
      }
    }
  if (csv != NULL) fclose(csv);
  SUNContext_Free(&ctx);
  return 0;
}
