/* -----------------------------------------------------------------------------
 * Lignum benchmark: the size of restart files and the time to write and
 * read them (LGNWriteRestart, LGNReadRestart), and the time to write one
 * output of the trajectory writer for ParaView (lignum_vtk.h).
 *
 *   restart_io [--n 1,100,10000] [--repeat R] [--csv FILE] [--dir DIR]
 *
 * Models: the heavy top (one body on R^3 x SO(3), spherical joint; the
 * heavy_top_study's), and the spherical-joint chain of models/chain.c
 * with N rods (R^3 x SO(3), m = 3 N, KLU). Each integrator takes 5 fixed
 * steps of generalized-alpha at index 3 (h = 1e-3), then writes its
 * restart file R times and reads it R times into a fresh integrator made
 * the same way (the fastest of R is reported: the file is in the page
 * cache, so these are the costs of Lignum's serialisation, CRC-32 and one
 * copy, not of a disk), and the read run takes one more step to show it
 * goes on. VTK: one output with each rod a cylinder and one joint frame.
 * Table on stdout, CSV (model,n,nq,nv,m,bytes,write_s,read_s,vtk_bytes,vtk_s).
 * ---------------------------------------------------------------------------*/

#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_vtk.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_math.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif

#include "models/chain.h"

static RigidCallbacks cbs;

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((RigidSystem *)ud)->joints, t, q, phi) == 0 ? 0 : -1;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((RigidSystem *)ud)->joints, t, q, B) == 0 ? 0 : -1;
}

typedef struct {
  void *mem;
  SUNMatrix A;
  SUNLinearSolver LS;
  N_Vector y;
} Integrator;

static double Now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int Make(RigidSystem *sys, Integrator *I, SUNContext ctx)
{
  const sunindextype nv = sys->G->nv, m = LGNJoints_NumConstraints(sys->joints), n = nv + m;
  int flag;
  memset(I, 0, sizeof *I);
  I->mem = LGNCreate(ctx);
  I->y   = N_VNew_Serial(n, ctx);
#if defined(LGN_HAVE_KLU)
  if (sys->n > 20) {
    I->A  = SUNSparseMatrix(n, n, 40 * n, CSC_MAT, ctx);
    I->LS = SUNLinSol_KLU(I->y, I->A, ctx);
  } else
#endif
  {
    I->A  = SUNDenseMatrix(n, n, ctx);
    I->LS = SUNLinSol_Dense(I->y, I->A, ctx);
  }
  flag = LGNSetGroup(I->mem, sys->G);
  if (!flag) flag = LGNInit(I->mem, 0.0, sys->q0, sys->v0);
  if (!flag) flag = LGNSetUserData(I->mem, sys);
  if (!flag) flag = LGNSetMassFn(I->mem, cbs.mass);
  if (!flag) flag = LGNSetForceFn(I->mem, cbs.force);
  if (!flag) flag = LGNSetMassConstant(I->mem, SUNTRUE);
  if (!flag) flag = LGNSetConstraints(I->mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetLinearSolver(I->mem, I->LS, I->A);
  if (!flag) flag = LGNSetGenAlpha(I->mem, 0.9);
  if (!flag) flag = LGNSetStepSize(I->mem, 1e-3);
  return flag;
}

static void Free(Integrator *I)
{
  LGNFree(&I->mem);
  SUNLinSolFree(I->LS);
  SUNMatDestroy(I->A);
  N_VDestroy(I->y);
}

static long FileSize(const char *name)
{
  FILE *fp = fopen(name, "rb");
  long n = -1;
  if (fp != NULL && fseek(fp, 0, SEEK_END) == 0) n = ftell(fp);
  if (fp != NULL) fclose(fp);
  return n;
}

/* The heavy top as a one-rod "chain": the heavy top's own body and joint. */
static RigidSystem *HeavyTop(SUNContext ctx)
{
  const sunrealtype mX[3] = {0.0, -1.0, 0.0}, origin[3] = {0.0, 0.0, 0.0};
  const sunrealtype X[3] = {0.0, 1.0, 0.0}, omega[3] = {0.0, 150.0, -4.61538};
  RigidSystem *sys = rigid_create(1, RB_R3XSO3, ctx);
  sunrealtype *q = N_VGetArrayPointer(sys->q0), *v = N_VGetArrayPointer(sys->v0);
  sys->mass[0]    = 15.0;
  sys->inertia[0] = 0.234375;
  sys->inertia[1] = 0.46875;
  sys->inertia[2] = 0.234375;
  sys->gravity[2] = -9.81;
  LGNJoints_AddSpherical(sys->joints, LGN_GROUND, origin, 0, mX);
  N_VConst(0.0, sys->q0);
  q[0] = X[0]; q[1] = X[1]; q[2] = X[2]; q[3] = 1.0;
  v[0] = omega[1] * X[2] - omega[2] * X[1];
  v[1] = omega[2] * X[0] - omega[0] * X[2];
  v[2] = omega[0] * X[1] - omega[1] * X[0];
  v[3] = omega[0]; v[4] = omega[1]; v[5] = omega[2];
  return sys;
}

int main(int argc, char **argv)
{
  const char *nlist = "1,100,10000", *csvname = "restart_io.csv", *dir = ".";
  int repeat = 5, i;
  SUNContext ctx;
  FILE *csv;
  char *list, *tok;
  for (i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--n") && i + 1 < argc) nlist = argv[++i];
    else if (!strcmp(argv[i], "--repeat") && i + 1 < argc) repeat = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--csv") && i + 1 < argc) csvname = argv[++i];
    else if (!strcmp(argv[i], "--dir") && i + 1 < argc) dir = argv[++i];
    else {
      fprintf(stderr, "usage: restart_io [--n 1,100,10000] [--repeat R] [--csv FILE] [--dir DIR]\n"
                      "  (n = 1: the heavy top; n > 1: the chain of n rods)\n");
      return 2;
    }
  }
  if (repeat < 1 || SUNContext_Create(NULL, &ctx) != 0) return 2;
  rigid_get_callbacks(&cbs);
  csv = fopen(csvname, "w");
  if (csv != NULL) fprintf(csv, "model,n,nq,nv,m,bytes,write_s,read_s,vtk_bytes,vtk_s\n");
  printf("%-10s %6s %8s %8s %8s %12s %10s %10s %12s %10s\n", "model", "n", "nq", "nv", "m",
         "restart B", "write s", "read s", "vtp B", "vtk s");
  list = strdup(nlist);
  for (tok = strtok(list, ","); tok != NULL; tok = strtok(NULL, ",")) {
    const int n = atoi(tok);
    RigidSystem *sys = n == 1 ? HeavyTop(ctx) : chain_create(n, RB_R3XSO3, ctx);
    Integrator W, R;
    N_Vector q = N_VClone(sys->q0), v = N_VClone(sys->v0);
    char name[512], base[512];
    double tw = 1e30, tr = 1e30, tv, t0;
    sunrealtype t;
    long bytes, vbytes;
    int k, flag = Make(sys, &W, ctx);
    LGNVtk vtk;
    snprintf(name, sizeof name, "%s/restart_io_%d.lgr", dir, n);
    for (k = 0; k < 5 && !flag; k++) flag = LGNSolve(W.mem, 10.0, &t, q, v, LGN_ONE_STEP);
    for (k = 0; k < repeat && !flag; k++) {
      t0   = Now();
      flag = LGNWriteRestart(W.mem, name);
      tw   = SUNMIN(tw, Now() - t0);
    }
    for (k = 0; k < repeat && !flag; k++) {
      flag = Make(sys, &R, ctx);
      t0   = Now();
      if (!flag) flag = LGNReadRestart(R.mem, name);
      tr = SUNMIN(tr, Now() - t0);
      if (!flag && k == repeat - 1) flag = LGNSolve(R.mem, 10.0, &t, q, v, LGN_ONE_STEP);
      Free(&R);
    }
    bytes = FileSize(name);
    /* one output for ParaView: cylinders and a joint frame per rod */
    snprintf(base, sizeof base, "%s/restart_io_%d", dir, n);
    vtk = LGNVtk_Create(sys->G, base);
    for (k = 0; k < sys->n && !flag; k++) {
      const sunrealtype top[3] = {0.0, 0.0, 0.5};
      flag = LGNVtk_SetCylinder(vtk, k, 0.02, 1.0);
      if (!flag) flag = LGNVtk_AddFrame(vtk, k, top, NULL, 0.1);
    }
    t0 = Now();
    if (!flag) flag = LGNVtk_Write(vtk, t, q);
    tv = Now() - t0;
    LGNVtk_Destroy(&vtk);
    snprintf(base, sizeof base, "%s/restart_io_%d_000000.vtp", dir, n);
    vbytes = FileSize(base);
    if (flag) {
      fprintf(stderr, "restart_io: n = %d: %s\n", n, LGNGetReturnFlagName(flag));
      return 1;
    }
    printf("%-10s %6d %8lld %8lld %8lld %12ld %10.2e %10.2e %12ld %10.2e\n",
           n == 1 ? "heavy top" : "chain", n, (long long)sys->G->nq, (long long)sys->G->nv,
           (long long)LGNJoints_NumConstraints(sys->joints), bytes, tw, tr, vbytes, tv);
    if (csv != NULL)
      fprintf(csv, "%s,%d,%lld,%lld,%lld,%ld,%.3e,%.3e,%ld,%.3e\n",
              n == 1 ? "heavy_top" : "chain", n, (long long)sys->G->nq,
              (long long)sys->G->nv, (long long)LGNJoints_NumConstraints(sys->joints), bytes,
              tw, tr, vbytes, tv);
    remove(name);
    Free(&W);
    N_VDestroy(q);
    N_VDestroy(v);
    rigid_free(&sys);
  }
  free(list);
  if (csv != NULL) fclose(csv);
  SUNContext_Free(&ctx);
  return 0;
}
