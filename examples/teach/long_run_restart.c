/* -----------------------------------------------------------------------------
 * Lignum teaching example: a long run interrupted and resumed from a
 * restart file.
 *
 * Shows: LGNWriteRestart and LGNReadRestart. A run on a cluster ends at the
 * job's time limit; the next job makes the integrator exactly as the first
 * did (the model, LGNModel_Attach, linear solver, root functions, the
 * same settings), calls LGNInit with any q0, v0 of the right sizes, reads
 * the restart file and goes on. The continued run then equals the
 * uninterrupted one bit for bit: the file holds the state, the last step,
 * the error control's history and all counters, and LGNReadRestart checks
 * that the settings which decide the steps are the writer's.
 *
 * The user's own state is not in Lignum's file: here the callbacks count
 * the top's revolutions (a root function, LGNRootInit, and a counter the
 * program keeps), and that counter is saved next to the restart file by
 * the program itself (SaveUserState, LoadUserState).
 *
 * Model: the heavy top of heavy_top.c (R^3 x SO(3), spherical joint),
 * generalized-alpha with error control. Job 1 integrates to t = 0.5 and
 * writes the files, job 2 reads them and integrates to t = 1; a third run
 * goes from 0 to 1 without a break, and the two are compared.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_model.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#define RESTART_FILE "long_run_restart.lgr"
#define USER_FILE    "long_run_restart.user"

/* The user's own state (the callbacks change it). */
typedef struct {
  long int crossings; /* the centre of mass crossing the x-z plane */
} UserState;

/* An event: the centre of mass crosses the plane y = 0 (the top precesses
 * about the z axis). */
static int Crossing(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *g, void *ud)
{
  (void)t;
  (void)v;
  (void)ud;
  g[0] = NV_Ith_S(q, 1);
  return 0;
}

/* Everything a job makes: the same in every job. */
typedef struct {
  SUNContext ctx;
  LGNGroup G;
  LGNBodies bodies;
  LGNJoints joints;
  LGNModel model; /* the bodies and joints: every model callback */
  UserState us;
  N_Vector q, v, y;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
} Job;

static int StartJob(Job *job)
{
  const sunrealtype X[3] = {0.0, 1.0, 0.0}, mX[3] = {0.0, -1.0, 0.0};
  const sunrealtype J[3] = {0.234375, 0.46875, 0.234375}, gvec[3] = {0.0, 0.0, -9.81};
  const sunrealtype origin[3] = {0.0, 0.0, 0.0}, omega0[3] = {0.0, 150.0, -4.61538};
  sunrealtype *qd, *vd;
  sunindextype m;
  int flag;

  memset(job, 0, sizeof *job);
  if (SUNContext_Create(NULL, &job->ctx) != 0) return -1;
  job->G = LGNGroup_R3xSO3();
  job->bodies = LGNBodies_Create(job->G);
  job->joints = LGNJoints_Create(job->G);
  job->model  = LGNModel_Create(job->bodies, job->joints);
  flag = LGNBodies_SetPrincipalInertia(job->bodies, 0, 15.0, J);
  if (!flag) flag = LGNBodies_SetGravity(job->bodies, gvec);
  if (!flag) flag = LGNJoints_AddSpherical(job->joints, LGN_GROUND, origin, 0, mX);
  m = LGNJoints_NumConstraints(job->joints);

  /* the initial state (a job that reads a restart file may give any q0,
   * v0 of these sizes: LGNReadRestart replaces them) */
  job->q = N_VNew_Serial(job->G->nq, job->ctx);
  job->v = N_VNew_Serial(job->G->nv, job->ctx);
  qd = N_VGetArrayPointer(job->q);
  vd = N_VGetArrayPointer(job->v);
  N_VConst(0.0, job->q);
  qd[0] = X[0]; qd[1] = X[1]; qd[2] = X[2];
  qd[3] = 1.0;
  vd[0] = omega0[1] * X[2] - omega0[2] * X[1];
  vd[1] = omega0[2] * X[0] - omega0[0] * X[2];
  vd[2] = omega0[0] * X[1] - omega0[1] * X[0];
  vd[3] = omega0[0]; vd[4] = omega0[1]; vd[5] = omega0[2];

  job->mem = LGNCreate(job->ctx);
  if (!flag) flag = LGNModel_Attach(job->model, job->mem);
  if (!flag) flag = LGNInit(job->mem, 0.0, job->q, job->v);
  if (!flag) flag = LGNRootInit(job->mem, 1, Crossing);
  job->y  = N_VNew_Serial(job->G->nv + m, job->ctx);
  job->A  = SUNDenseMatrix(job->G->nv + m, job->G->nv + m, job->ctx);
  job->LS = LGNLinSol_Dense(job->y, job->A, job->ctx);
  if (!flag) flag = LGNSetLinearSolver(job->mem, job->LS, job->A);
  if (!flag) flag = LGNSetGenAlpha(job->mem, 0.9);
  if (!flag) flag = LGNSetStepControl(job->mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(job->mem, 1e-6, 1e-6);
  if (!flag) flag = LGNSetStepSize(job->mem, 1e-3);
  if (!flag) flag = LGNSetMaxNumSteps(job->mem, 100000);
  return flag;
}

static void EndJob(Job *job)
{
  LGNFree(&job->mem);
  SUNLinSolFree(job->LS);
  SUNMatDestroy(job->A);
  N_VDestroy(job->y);
  N_VDestroy(job->q);
  N_VDestroy(job->v);
  LGNModel_Destroy(&job->model);
  LGNJoints_Destroy(&job->joints);
  LGNBodies_Destroy(&job->bodies);
  LGNGroup_Destroy(job->G);
  SUNContext_Free(&job->ctx);
}

/* The user's state, saved and read by the user (here one number). */
static int SaveUserState(const UserState *us)
{
  FILE *fp = fopen(USER_FILE, "w");
  if (fp == NULL) return -1;
  fprintf(fp, "%ld\n", us->crossings);
  return fclose(fp) == 0 ? 0 : -1;
}

static int LoadUserState(UserState *us)
{
  FILE *fp = fopen(USER_FILE, "r");
  int ok;
  if (fp == NULL) return -1;
  ok = fscanf(fp, "%ld", &us->crossings) == 1;
  fclose(fp);
  return ok ? 0 : -1;
}

/* Integrate to tend, printing every 0.1 s and counting the crossings. */
static int Integrate(Job *job, sunrealtype tend, int jobno, sunbooleantype print)
{
  sunrealtype t = 0.0, tout;
  int flag = LGNGetCurrentTime(job->mem, &t);
  for (tout = floor(t * 10.0 + 0.5) / 10.0 + 0.1; !flag && tout <= tend + 0.05;) {
    flag = LGNSolve(job->mem, tout, &t, job->q, job->v, LGN_NORMAL);
    if (flag == LGN_ROOT_RETURN) {
      job->us.crossings++;
      flag = 0;
      continue;
    }
    if (!flag && print)
      printf("%4d %5.2f %12.6f %12.6f %12.6f %10ld\n", jobno, t, NV_Ith_S(job->q, 0),
             NV_Ith_S(job->q, 1), NV_Ith_S(job->q, 2), job->us.crossings);
    tout += 0.1;
  }
  return flag;
}

int main(void)
{
  Job job1, job2, whole;
  sunrealtype q2[7], qw[7], v2[6], vw[6];
  long int nst2 = 0, nstw = 0;
  long size = 0;
  int flag;
  FILE *fp;

  printf("Heavy top, generalized-alpha(0.9), error control (1e-6): job 1 stops at\n");
  printf("t = 0.5 and writes a restart file, job 2 reads it and goes on to t = 1\n\n");
  printf("%4s %5s %12s %12s %12s %10s\n", "job", "t", "x", "y", "z", "crossings");

  /* job 1: to the time limit, then the restart file and the user's state */
  flag = StartJob(&job1);
  if (!flag) flag = Integrate(&job1, 0.5, 1, SUNTRUE);
  if (!flag) flag = LGNWriteRestart(job1.mem, RESTART_FILE);
  if (!flag) flag = SaveUserState(&job1.us);
  EndJob(&job1);

  /* job 2: the same integrator, the files read, the run continued */
  if (!flag) flag = StartJob(&job2);
  if (!flag) flag = LGNReadRestart(job2.mem, RESTART_FILE);
  if (!flag) flag = LoadUserState(&job2.us);
  if (!flag) flag = Integrate(&job2, 1.0, 2, SUNTRUE);

  /* the run without a break, for comparison */
  if (!flag) flag = StartJob(&whole);
  if (!flag) flag = Integrate(&whole, 1.0, 0, SUNFALSE);
  if (flag) {
    fprintf(stderr, "long_run_restart: %s\n", LGNGetReturnFlagName(flag));
    return 1;
  }
  memcpy(q2, N_VGetArrayPointer(job2.q), sizeof q2);
  memcpy(v2, N_VGetArrayPointer(job2.v), sizeof v2);
  memcpy(qw, N_VGetArrayPointer(whole.q), sizeof qw);
  memcpy(vw, N_VGetArrayPointer(whole.v), sizeof vw);
  LGNGetNumSteps(job2.mem, &nst2);
  LGNGetNumSteps(whole.mem, &nstw);
  fp = fopen(RESTART_FILE, "rb");
  if (fp != NULL && fseek(fp, 0, SEEK_END) == 0) size = ftell(fp);
  if (fp != NULL) fclose(fp);

  printf("\nrestart file: %ld bytes\n", size);
  printf("steps: %ld (resumed), %ld (without a break)\n", nst2, nstw);
  printf("crossings: %ld (resumed), %ld (without a break)\n", job2.us.crossings,
         whole.us.crossings);
  flag = memcmp(q2, qw, sizeof q2) != 0 || memcmp(v2, vw, sizeof v2) != 0 || nst2 != nstw ||
         job2.us.crossings != whole.us.crossings;
  printf("q, v at t = 1 equal bit for bit: %s\n", flag ? "NO" : "yes");
  EndJob(&job2);
  EndJob(&whole);
  remove(RESTART_FILE);
  remove(USER_FILE);
  return flag;
}
