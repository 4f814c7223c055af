/* -----------------------------------------------------------------------------
 * The heavy top of examples/teach/heavy_top.c as a reference for the Python
 * package: the same model and callbacks, outputs at t = k/10, k = 1..10,
 * printed exactly (C99 hexadecimal floats %a) so that test_python compares
 * the Python package's results bit for bit; and the C side of the timing
 * in bench/python/bench_heavy_top.py.
 *
 *   heavy_top_ref [adaptive|fixed|bdf] [--repeat N]
 *
 * adaptive: generalized-alpha(0.9), rtol = atol = 1e-6, first step 1e-3
 * (the example's settings); fixed: generalized-alpha(0.9), h = 1e-3; bdf:
 * BDF up to order 5 with rtol = atol = 1e-6. Prints for each output
 * "t q[0..6] v[0..5] lambda[0..2]"; with --repeat N, runs N times and
 * prints "wall_seconds_per_run steps min_cpu_seconds_per_run" instead.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Model;

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
static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->joints, t, q, v, z) ? -1 : 0;
}
static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                     N_Vector lambda, SUNMatrix K, void *ud)
{
  Model *md = (Model *)ud;
  (void)vdot;
  if (LGNJoints_Stiffness(md->joints, t, q, lambda, K)) return -1;
  return LGNBodies_Stiffness(md->bodies, q, v, K) ? -1 : 0;
}
static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  return LGNBodies_DampingFn(t, q, v, C, ((Model *)ud)->bodies);
}

/* One run over [0, 1]; prints the outputs when print != 0. Returns the
 * flag; *nsteps receives the number of steps. */
static int Run(const char *mode, int print, long int *nsteps)
{
  const sunrealtype X[3] = {0.0, 1.0, 0.0}, mX[3] = {0.0, -1.0, 0.0};
  const sunrealtype J[3] = {0.234375, 0.46875, 0.234375}, gvec[3] = {0.0, 0.0, -9.81};
  const sunrealtype origin[3] = {0.0, 0.0, 0.0}, omega0[3] = {0.0, 150.0, -4.61538};
  SUNContext ctx = NULL;
  LGNGroup G = LGNGroup_R3xSO3();
  Model md = {NULL, NULL};
  N_Vector q, v, y, lam;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  sunrealtype t = 0.0, *qd, *vd;
  sunindextype m;
  int flag, k, i;

  if (SUNContext_Create(NULL, &ctx) != 0 || !G) return -1;
  md.bodies = LGNBodies_Create(G);
  md.joints = LGNJoints_Create(G);
  flag = LGNBodies_SetPrincipalInertia(md.bodies, 0, 15.0, J);
  if (!flag) flag = LGNBodies_SetGravity(md.bodies, gvec);
  if (!flag) flag = LGNJoints_AddSpherical(md.joints, LGN_GROUND, origin, 0, mX);
  m = LGNJoints_NumConstraints(md.joints);
  q = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(G->nv, ctx);
  lam = N_VNew_Serial(m, ctx);
  qd = N_VGetArrayPointer(q);
  vd = N_VGetArrayPointer(v);
  N_VConst(0.0, q);
  qd[0] = X[0]; qd[1] = X[1]; qd[2] = X[2];
  qd[3] = 1.0;
  /* u = Omega x X (R = I), as numpy.cross computes it */
  vd[0] = omega0[1] * X[2] - omega0[2] * X[1];
  vd[1] = omega0[2] * X[0] - omega0[0] * X[2];
  vd[2] = omega0[0] * X[1] - omega0[1] * X[0];
  vd[3] = omega0[0]; vd[4] = omega0[1]; vd[5] = omega0[2];

  mem = LGNCreate(ctx);
  if (!flag) flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetStiffnessFn(mem, Stiffness);
  if (!flag) flag = LGNSetDampingFn(mem, Damping);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  y = N_VNew_Serial(G->nv + m, ctx);
  A = SUNDenseMatrix(G->nv + m, G->nv + m, ctx);
  LS = LGNLinSol_Dense(y, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (strcmp(mode, "bdf") == 0) {
    if (!flag) flag = LGNSetBDF(mem, 5);
  } else {
    if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  }
  if (strcmp(mode, "fixed") != 0) {
    if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSStolerances(mem, 1e-6, 1e-6);
  }
  if (!flag) flag = LGNSetStepSize(mem, 1e-3);
  if (!flag) flag = LGNSetMaxNumSteps(mem, 100000);
  for (k = 1; !flag && k <= 10; k++) {
    flag = LGNSolve(mem, 0.1 * k, &t, q, v, LGN_NORMAL);
    if (!flag) flag = LGNGetMultipliers(mem, lam);
    if (!flag && print) {
      printf("%a", t);
      for (i = 0; i < 7; i++) printf(" %a", qd[i]);
      for (i = 0; i < 6; i++) printf(" %a", vd[i]);
      for (i = 0; i < 3; i++) printf(" %a", N_VGetArrayPointer(lam)[i]);
      printf("\n");
    }
  }
  LGNGetNumSteps(mem, nsteps);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(lam);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return flag;
}

int main(int argc, char **argv)
{
  const char *mode = argc > 1 ? argv[1] : "adaptive";
  long int nsteps = 0, repeat = 0, r;
  struct timespec t0, t1, c0, c1;
  double cpu, cpu_min = 0.0;
  int flag = 0;

  if (strcmp(mode, "adaptive") && strcmp(mode, "fixed") && strcmp(mode, "bdf")) {
    fprintf(stderr, "usage: heavy_top_ref [adaptive|fixed|bdf] [--repeat N]\n");
    return 2;
  }
  if (argc > 3 && strcmp(argv[2], "--repeat") == 0) repeat = strtol(argv[3], NULL, 10);
  if (repeat < 1) return Run(mode, 1, &nsteps) ? 1 : 0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (r = 0; !flag && r < repeat; r++) { /* the fastest run's CPU time */
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
    flag = Run(mode, 0, &nsteps);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
    cpu = (c1.tv_sec - c0.tv_sec) + 1e-9 * (c1.tv_nsec - c0.tv_nsec);
    if (r == 0 || cpu < cpu_min) cpu_min = cpu;
  }
  clock_gettime(CLOCK_MONOTONIC, &t1);
  printf("%.9e %ld %.9e\n", ((t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec)) / repeat,
         nsteps, cpu_min);
  return flag ? 1 : 0;
}
