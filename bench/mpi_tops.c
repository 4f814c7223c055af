/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * What a run across ranks costs: K heavy tops per rank (R^3 x SO(3) bodies on
 * spherical joints, spun at different rates; no joint between ranks), in
 * MPIPlusX vectors, generalized-alpha (modified kinematics) under error
 * control with modified Newton and KLU on each rank's block. Weak scaling:
 * start it with 1, 2, 4 ... ranks (bench/mpi-scaling does). Rank 0 prints
 * one row per K and appends it to the CSV:
 *
 *   ranks, K, bodies, steps, ms per step, us per step and body, reductions
 *   (MPI_Allreduce calls) per step, us per reduction (timed alone, 3 reals),
 *   the reductions' share of the step, the largest resident memory of a
 *   rank (MB) and per body (kB).
 *
 * The reductions are counted through MPI's profiling interface: this
 * program's MPI_Allreduce counts and calls PMPI_Allreduce.
 *   mpi_tops [--per-rank K1,K2,...] [--t-end T] [--repeat R] [--csv FILE]
 * Timings: the best of R runs (default 3; one run above 1e5 bodies per
 * rank), each the slowest rank's.
 * ---------------------------------------------------------------------------*/

#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <mpi.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_mpiplusx.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

static long int n_allreduce = 0;

/* MPI's profiling interface: count, then reduce */
int MPI_Allreduce(const void *sendbuf, void *recvbuf, int count, MPI_Datatype type, MPI_Op op,
                  MPI_Comm comm)
{
  n_allreduce++;
  return PMPI_Allreduce(sendbuf, recvbuf, count, type, op, comm);
}

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Tops;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Tops *)ud)->bodies);
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Tops *)ud)->bodies);
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Tops *)ud)->joints, t, q, phi);
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Tops *)ud)->joints, t, q, B);
}

static double Now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* resident memory of this process, MB (VmHWM: its peak) */
static double PeakMB(void)
{
  FILE *f = fopen("/proc/self/status", "r");
  char line[256];
  double kb = 0.0;
  if (f == NULL) return 0.0;
  while (fgets(line, sizeof line, f))
    if (sscanf(line, "VmHWM: %lf", &kb) == 1) break;
  fclose(f);
  return kb / 1024.0;
}

/* One run of K tops per rank; returns 0 and the timings on success. */
static int Run(MPI_Comm comm, int rank, int K, double t_end, SUNContext ctx, long int *nst,
               double *seconds, long int *nred)
{
  const sunrealtype J[3] = {0.234375, 0.46875, 0.234375}, gravity[3] = {0.0, 0.0, -9.81};
  const sunrealtype origin[3] = {0.0, 0.0, 0.0}, tip[3] = {0.0, -1.0, 0.0};
  LGNGroup body = LGNGroup_R3xSO3(), G;
  LGNGroup *factors = (LGNGroup *)malloc((size_t)K * sizeof(LGNGroup));
  Tops md = {NULL, NULL};
  N_Vector q, v, tmpl;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  sunindextype nv, m;
  sunrealtype *qd, *vd, t = 0.0;
  double t0;
  long int red0;
  int k, flag = 0;

  for (k = 0; k < K; k++) factors[k] = body;
  G         = LGNGroup_Product(K, factors);
  nv        = G->nv;
  md.bodies = LGNBodies_Create(G);
  md.joints = LGNJoints_Create(G);
  for (k = 0; k < K && !flag; k++) {
    flag = LGNBodies_SetPrincipalInertia(md.bodies, k, 15.0, J);
    if (!flag) flag = LGNJoints_AddSpherical(md.joints, LGN_GROUND, origin, k, tip);
  }
  if (!flag) flag = LGNBodies_SetGravity(md.bodies, gravity);
  m  = LGNJoints_NumConstraints(md.joints);
  q  = N_VMake_MPIPlusX(comm, N_VNew_Serial(G->nq, ctx), ctx);
  v  = N_VMake_MPIPlusX(comm, N_VNew_Serial(nv, ctx), ctx);
  qd = N_VGetArrayPointer(q);
  vd = N_VGetArrayPointer(v);
  LGNGroup_Identity(G, qd);
  N_VConst(0.0, v);
  for (k = 0; k < K; k++) {
    const double u = (double)(rank * K + k) / (double)K; /* spread of the spins */
    qd[7 * k + 1] = 1.0;
    vd[6 * k + 4] = 150.0 - 20.0 * u;
    vd[6 * k + 5] = -4.61538;
    vd[6 * k + 0] = -vd[6 * k + 5]; /* u = Omega x X */
  }
  tmpl = N_VNew_Serial(nv + m, ctx);
  A    = SUNSparseMatrix(nv + m, nv + m, 40 * (nv + m), CSC_MAT, ctx);
  LS   = SUNLinSol_KLU(tmpl, A, ctx);
  mem  = LGNCreate(ctx);
  if (!flag) flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetKinematics(mem, LGN_KINEMATICS_EXACT);
  if (!flag) flag = LGNSetNewtonMode(mem, LGN_NEWTON_MODIFIED);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, 1e-6, 1e-6);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  /* the first step (initial values, symbolic analysis) is not timed */
  if (!flag) flag = LGNSolve(mem, t_end, &t, q, v, LGN_ONE_STEP);
  MPI_Barrier(comm);
  t0   = Now();
  red0 = n_allreduce;
  if (!flag) flag = LGNSolve(mem, t_end, &t, q, v, LGN_NORMAL);
  *seconds = Now() - t0;
  *nred    = n_allreduce - red0;
  LGNGetNumSteps(mem, nst);
  *nst -= 1;

  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(tmpl);
  N_VDestroy(N_VGetLocalVector_MPIPlusX(q));
  N_VDestroy(N_VGetLocalVector_MPIPlusX(v));
  N_VDestroy(q);
  N_VDestroy(v);
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  free(factors);
  return flag;
}

/* us per MPI_Allreduce of 3 reals (the size of Lignum's), alone */
static double ReductionLatency(MPI_Comm comm)
{
  double x[3] = {1.0, 2.0, 3.0}, t0;
  int i;
  const int n = 2000;
  MPI_Barrier(comm);
  t0 = Now();
  for (i = 0; i < n; i++) PMPI_Allreduce(MPI_IN_PLACE, x, 3, MPI_DOUBLE, MPI_SUM, comm);
  return 1e6 * (Now() - t0) / n;
}

int main(int argc, char **argv)
{
  MPI_Comm comm = MPI_COMM_WORLD;
  SUNContext ctx;
  int rank, size, i, nk = 0, fails = 0;
  int per_rank[16] = {1000, 10000, 100000};
  double t_end = 0.03, lat;
  int repeat = 3;
  const char *csv = "mpi_tops.csv";
  FILE *out = NULL;

  MPI_Init(&argc, &argv);
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  for (i = 1; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "--per-rank")) {
      char *s = argv[i + 1], *end;
      nk = 0;
      while (*s && nk < 16) {
        per_rank[nk++] = (int)strtol(s, &end, 10);
        s = *end == ',' ? end + 1 : end;
        if (end == s && *s) break;
      }
    } else if (!strcmp(argv[i], "--repeat")) {
      repeat = atoi(argv[i + 1]) > 0 ? atoi(argv[i + 1]) : 1;
    } else if (!strcmp(argv[i], "--t-end")) {
      t_end = atof(argv[i + 1]);
    } else if (!strcmp(argv[i], "--csv")) {
      csv = argv[i + 1];
    }
  }
  if (nk == 0) nk = 3;
  SUNContext_Create(&comm, &ctx);
  lat = ReductionLatency(comm);
  if (rank == 0) {
    FILE *probe = fopen(csv, "r");
    int fresh   = probe == NULL;
    if (probe != NULL) fclose(probe);
    out = fopen(csv, "a");
    if (out != NULL && fresh)
      fprintf(out, "ranks,per_rank,bodies,steps,ms_per_step,us_per_step_body,"
                   "reductions_per_step,us_per_reduction,reduction_share,mb_per_rank,"
                   "kb_per_body\n");
    printf("%5s %8s %9s %6s %11s %13s %10s %9s %7s %9s %8s\n", "ranks", "K/rank", "bodies",
           "steps", "ms/step", "us/step/body", "red./step", "us/red.", "share", "MB/rank",
           "kB/body");
  }
  for (i = 0; i < nk; i++) {
    long int nst = 0, nred = 0;
    double sec = 0.0, sec_max = 0.0, sec_run, mb, mb_max;
    int flag = 0, r;
    /* the best of `repeat` runs (one above 1e5 bodies per rank): the
     * slowest rank's time of each */
    for (r = 0; r < (per_rank[i] >= 100000 ? 1 : repeat) && !flag; r++) {
      flag = Run(comm, rank, per_rank[i], t_end, ctx, &nst, &sec, &nred);
      MPI_Allreduce(&sec, &sec_run, 1, MPI_DOUBLE, MPI_MAX, comm);
      sec_max = r == 0 ? sec_run : fmin(sec_max, sec_run);
    }
    mb = PeakMB();
    MPI_Allreduce(&mb, &mb_max, 1, MPI_DOUBLE, MPI_MAX, comm);
    if (flag) fails++;
    if (rank == 0 && nst > 0) {
      const double bodies = (double)per_rank[i] * size, ms = 1e3 * sec_max / (double)nst;
      const double rps = (double)nred / (double)nst;
      printf("%5d %8d %9.0f %6ld %11.3f %13.3f %10.1f %9.2f %6.1f%% %9.1f %8.1f%s\n", size,
             per_rank[i], bodies, nst, ms, 1e3 * ms / per_rank[i], rps, lat,
             100.0 * rps * lat / (1e3 * ms), mb_max, 1024.0 * mb_max / per_rank[i],
             flag ? "  FAILED" : "");
      if (out != NULL)
        fprintf(out, "%d,%d,%.0f,%ld,%.6g,%.6g,%.4g,%.4g,%.4g,%.4g,%.4g\n", size, per_rank[i],
                bodies, nst, ms, 1e3 * ms / per_rank[i], rps, lat, rps * lat / (1e3 * ms),
                mb_max, 1024.0 * mb_max / per_rank[i]);
    }
  }
  if (out != NULL) fclose(out);
  SUNContext_Free(&ctx);
  MPI_Finalize();
  return fails ? 1 : 0;
}
