/* -----------------------------------------------------------------------------
 * Lignum test: two integrator objects used from two threads at once.
 *
 * Each thread has its own SUNContext, Lie group, joint set, integrator
 * memory, iteration matrix and linear solver (thread 0 dense, thread 1 KLU
 * CSC, or dense without KLU) and integrates a two-body chain on
 * (R^3 x SO(3))^2 (a spherical joint to the ground, a revolute joint between
 * the bodies; error control on thread 1) for STEPS steps. Every result must
 * equal, bit for bit, the same run done serially before the threads start.
 * Built and run in the normal suite, and under ThreadSanitizer by .ci/run
 * (LGN_ENABLE_TSAN: any report is fatal with TSAN_OPTIONS=halt_on_error=1).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

#define STEPS 400
#define NQ 14
#define NV 12

static const double MASS = 2.0, JB[3] = {0.3, 0.5, 0.7};

typedef struct {
  int id;          /* 0: dense, fixed steps; 1: KLU CSC, error control */
  LGNJoints J;     /* this run's own joint set */
  double q[NQ], v[NV], t;
  long nsteps;
  int flag;
  char where[96];
} Run;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  sunindextype i;
  (void)t; (void)q; (void)ud;
  if (SUNMatGetID(M) == SUNMATRIX_DENSE) {
    for (i = 0; i < NV; i++) SM_ELEMENT_D(M, i, i) = (i % 6) < 3 ? MASS : JB[i % 6 - 3];
    return 0;
  }
  {
    sunindextype *ptr, *ind;
    double *val;
    if (SUNSparseMatrix_NNZ(M) < NV && SUNSparseMatrix_Reallocate(M, NV) != 0) return -1;
    ptr = SUNSparseMatrix_IndexPointers(M);
    ind = SUNSparseMatrix_IndexValues(M);
    val = SUNSparseMatrix_Data(M);
    for (i = 0; i < NV; i++) {
      ptr[i] = i;
      ind[i] = i;
      val[i] = (i % 6) < 3 ? MASS : JB[i % 6 - 3];
    }
    ptr[NV] = NV;
  }
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const double *u = N_VGetArrayPointer(v);
  double *gg      = N_VGetArrayPointer(g);
  int b;
  (void)t; (void)q; (void)ud;
  for (b = 0; b < 2; b++) {
    const double *W = u + 6 * b + 3;
    double *f       = gg + 6 * b;
    f[0] = f[1] = 0.0;
    f[2] = MASS * 9.81;
    f[3] = W[1] * JB[2] * W[2] - W[2] * JB[1] * W[1];
    f[4] = W[2] * JB[0] * W[0] - W[0] * JB[2] * W[2];
    f[5] = W[0] * JB[1] * W[1] - W[1] * JB[0] * W[0];
  }
  return 0;
}

static int Phi(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Run *)ud)->J, t, q, phi) == 0 ? 0 : -1;
}

static int Jac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Run *)ud)->J, t, q, B) == 0 ? 0 : -1;
}

static int Curv(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Run *)ud)->J, t, q, v, z) == 0 ? 0 : -1;
}

#define FAIL(r, ...)                                                           \
  do {                                                                         \
    snprintf((r)->where, sizeof (r)->where, __VA_ARGS__);                      \
    goto done;                                                                 \
  } while (0)

/* One complete run: everything created, used and freed in this call. */
static void *Integrate(void *arg)
{
  Run *r = arg;
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL;
  N_Vector q = NULL, v = NULL, tmp = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunindextype m, n;
  const double s0[3] = {0, 0, 0}, s1[3] = {0, 0, 0.5}, s2[3] = {0, 0, -0.5}, ax[3] = {0, 0, 1};
  int k, flag = -1;

  r->J = NULL;
  if (SUNContext_Create(NULL, &ctx) != 0) FAIL(r, "SUNContext_Create");
  body = LGNGroup_R3xSO3();
  {
    LGNGroup f[2] = {body, body};
    G = LGNGroup_Product(2, f);
  }
  r->J = LGNJoints_Create(G);
  if (!r->J || LGNJoints_AddSpherical(r->J, LGN_GROUND, s0, 0, s1) ||
      LGNJoints_AddRevolute(r->J, 0, s2, ax, 1, s1, ax))
    FAIL(r, "joints");
  m   = LGNJoints_NumConstraints(r->J);
  n   = NV + m;
  q   = N_VNew_Serial(NQ, ctx);
  v   = N_VNew_Serial(NV, ctx);
  tmp = N_VNew_Serial(n, ctx);
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  {
    double *x = N_VGetArrayPointer(q), *u = N_VGetArrayPointer(v);
    /* a vertical chain spinning about its axis, tipped over by a sideways
     * velocity of the joint between the bodies */
    x[2] = -0.5; x[3] = 1.0; x[9] = -1.5; x[10] = 1.0;
    u[0] = 0.3; u[4] = -0.6; u[5] = 3.0; u[6] = 0.6; u[10] = -0.6; u[11] = 3.0;
  }
#if defined(LGN_HAVE_KLU)
  if (r->id == 1) {
    A  = SUNSparseMatrix(n, n, n * n, CSC_MAT, ctx);
    LS = SUNLinSol_KLU(tmp, A, ctx);
  } else
#endif
  {
    A  = SUNDenseMatrix(n, n, ctx);
    LS = SUNLinSol_Dense(tmp, A, ctx);
  }
  mem  = LGNCreate(ctx);
  flag = mem ? LGNSetErrFile(mem, stderr) : -1;
  if (!flag) flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, r);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Phi, Jac);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curv);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.8);
  if (!flag) flag = LGNSetStepSize(mem, 1e-3);
  if (!flag && r->id == 1) {
    flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSStolerances(mem, 1e-6, 1e-6);
  }
  if (flag) FAIL(r, "set-up: %s", LGNGetReturnFlagName(flag));
  for (k = 0; k < STEPS && !flag; k++) flag = LGNSolve(mem, 10.0, &r->t, q, v, LGN_ONE_STEP);
  if (flag) FAIL(r, "LGNSolve at step %d: %s", k, LGNGetReturnFlagName(flag));
  LGNGetNumSteps(mem, &r->nsteps);
  memcpy(r->q, N_VGetArrayPointer(q), sizeof r->q);
  memcpy(r->v, N_VGetArrayPointer(v), sizeof r->v);
done:
  r->flag = flag;
  LGNFree(&mem);
  if (LS) SUNLinSolFree(LS);
  if (A) SUNMatDestroy(A);
  if (q) N_VDestroy(q);
  if (v) N_VDestroy(v);
  if (tmp) N_VDestroy(tmp);
  LGNJoints_Destroy(&r->J);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  if (ctx) SUNContext_Free(&ctx);
  return NULL;
}

int main(void)
{
  Run serial[2], conc[2];
  pthread_t th[2];
  int i, round, fails = 0;
  for (i = 0; i < 2; i++) {
    memset(&serial[i], 0, sizeof serial[i]);
    serial[i].id = i;
    Integrate(&serial[i]);
    if (serial[i].flag) {
      fprintf(stderr, "FAIL: serial run %d: %s\n", i, serial[i].where);
      return 1;
    }
    printf("serial run %d (%s): %ld steps to t = %.6f, z of body 1 = %.12g\n", i,
           i == 0 ? "dense, fixed h" : "KLU CSC, error control", serial[i].nsteps, serial[i].t,
           serial[i].q[2]);
  }
  for (round = 0; round < 3; round++) {
    for (i = 0; i < 2; i++) {
      memset(&conc[i], 0, sizeof conc[i]);
      conc[i].id = i;
      if (pthread_create(&th[i], NULL, Integrate, &conc[i]) != 0) {
        fprintf(stderr, "FAIL: pthread_create\n");
        return 1;
      }
    }
    for (i = 0; i < 2; i++) pthread_join(th[i], NULL);
    for (i = 0; i < 2; i++) {
      if (conc[i].flag) {
        fprintf(stderr, "FAIL: round %d, thread %d: %s\n", round, i, conc[i].where);
        fails++;
      } else if (conc[i].t != serial[i].t || conc[i].nsteps != serial[i].nsteps ||
                 memcmp(conc[i].q, serial[i].q, sizeof conc[i].q) != 0 ||
                 memcmp(conc[i].v, serial[i].v, sizeof conc[i].v) != 0) {
        fprintf(stderr, "FAIL: round %d, thread %d: differs from the serial run\n", round, i);
        fails++;
      }
    }
  }
  if (fails) return 1;
  printf("two threads, 3 rounds: both results equal the serial runs bit for bit\n");
  return 0;
}
