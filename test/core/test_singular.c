/* -----------------------------------------------------------------------------
 * Lignum test: singular mechanisms are diagnosed in words (redundant
 * constraints with LGN_REDUNDANT_REFUSE; by default they are left out and
 * the mechanism runs: test_redundant).
 *
 *  (a) two identical sets of constraints (a body pinned twice at the same
 *      point): LGN_IC_FAIL, and exactly one of each pair of identical rows
 *      is named redundant (LGNGetRedundantConstraints and the message);
 *  (b) an all-revolute spatial four-bar built with the joint helpers
 *      (20 constraints on 18 velocities, one degree of freedom: 3 redundant
 *      constraints): three redundant rows, named by joint with
 *      LGNJoints_DescribeConstraint; dense and KLU;
 *  (c) a body without mass in one direction: the zero pivot is named
 *      (body and direction) and no constraint is called redundant.
 * The dense cases run with SUNLinSol_Dense and again with Lignum's dense
 * LU (LGNLinSol_Dense), whose last flag names the zero pivot the same way.
 * The messages are printed, as a user would read them.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

#include "test_util.h"

static char last_msg[1024];
static void Capture(int code, const char *module, const char *fn, const char *msg, void *d)
{
  (void)code; (void)module; (void)d;
  snprintf(last_msg, sizeof last_msg, "%s: %s", fn, msg);
}

/* n bodies on R^3 x SO(3): unit masses and inertias (diagonal), gravity -y;
 * the joints' constraints. */
typedef struct {
  int n;
  double mass_x0; /* mass of body 0 in x (0: singular) */
  LGNJoints J;
  int twice;      /* pinned twice (a) */
} Model;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  const Model *md = (const Model *)ud;
  sunindextype i, nv = 6 * md->n;
  (void)t; (void)q;
  if (SUNMatGetID(M) == SUNMATRIX_DENSE) {
    for (i = 0; i < nv; i++) SM_ELEMENT_D(M, i, i) = (i == 0) ? md->mass_x0 : 1.0;
  } else {
    sunindextype *ptr = SUNSparseMatrix_IndexPointers(M), *ind = SUNSparseMatrix_IndexValues(M);
    sunrealtype *val = SUNSparseMatrix_Data(M);
    for (i = 0; i < nv; i++) {
      ptr[i] = i;
      ind[i] = i;
      val[i] = (i == 0) ? md->mass_x0 : 1.0;
    }
    ptr[nv] = nv;
  }
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const Model *md = (const Model *)ud;
  int k;
  (void)t; (void)q; (void)v;
  for (k = 0; k < md->n; k++) N_VGetArrayPointer(g)[6 * k + 1] = 9.81; /* m g, unit J: no gyro */
  return 0;
}

static int Phi(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const Model *md = (const Model *)ud;
  if (md->twice) {
    /* the pin Phi = x - 0, twice */
    int i;
    for (i = 0; i < 6; i++) N_VGetArrayPointer(phi)[i] = N_VGetArrayPointer(q)[i % 3];
    return 0;
  }
  return LGNJoints_Residual(md->J, t, q, phi);
}

static int Jac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  const Model *md = (const Model *)ud;
  if (md->twice) {
    int i;
    for (i = 0; i < 6; i++) SM_ELEMENT_D(B, i, i % 3) = 1.0;
    return 0;
  }
  return LGNJoints_Jacobian(md->J, t, q, B);
}

/* the dense solver of Run: SUNLinSol_Dense, or LGNLinSol_Dense when set */
static int use_lgn_lu = 0;

static int Run(Model *md, LGNGroup G, N_Vector q0, int sparse, sunindextype m,
               sunindextype *nred, sunindextype *rows, sunindextype *pivot)
{
  SUNContext ctx = NULL;
  const sunindextype nv = 6 * md->n, n = nv + m;
  N_Vector v0, tmp, qo, vo;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem;
  double t;
  int flag;
  SUNContext_Create(NULL, &ctx);
  v0  = N_VNew_Serial(nv, ctx);
  vo  = N_VNew_Serial(nv, ctx);
  qo  = N_VClone(q0);
  tmp = N_VNew_Serial(n, ctx);
  N_VConst(0.0, v0);
  if (!sparse) {
    A  = SUNDenseMatrix(n, n, ctx);
    LS = use_lgn_lu ? LGNLinSol_Dense(tmp, A, ctx) : SUNLinSol_Dense(tmp, A, ctx);
  } else {
#if defined(LGN_HAVE_KLU)
    A  = SUNSparseMatrix(n, n, n * n, CSC_MAT, ctx);
    LS = SUNLinSol_KLU(tmp, A, ctx);
#endif
  }
  mem  = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetErrHandlerFn(mem, Capture, NULL);
  if (!flag) flag = LGNSetUserData(mem, md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag && m > 0) flag = LGNSetConstraints(mem, m, Phi, Jac);
  if (!flag) flag = LGNInit(mem, 0.0, q0, v0);
  /* the refusal (the default leaves redundant rows out: test_redundant) */
  if (!flag) flag = LGNSetRedundantConstraints(mem, LGN_REDUNDANT_REFUSE);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetStepSize(mem, 1e-3);
  last_msg[0] = '\0';
  if (!flag) flag = LGNSolve(mem, 0.01, &t, qo, vo, LGN_NORMAL);
  LGNGetRedundantConstraints(mem, nred, rows);
  LGNGetZeroPivot(mem, pivot);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(v0);
  N_VDestroy(vo);
  N_VDestroy(qo);
  N_VDestroy(tmp);
  SUNContext_Free(&ctx);
  return flag;
}

static void PinnedTwice(void)
{
  SUNContext ctx;
  LGNGroup G = LGNGroup_R3xSO3();
  Model md = {1, 1.0, NULL, 1};
  N_Vector q;
  sunindextype nred = 0, rows[6], pivot = -1, i;
  int flag, pairs_ok = 1;
  SUNContext_Create(NULL, &ctx);
  q = N_VNew_Serial(7, ctx);
  N_VConst(0.0, q);
  N_VGetArrayPointer(q)[3] = 1.0;
  flag = Run(&md, G, q, 0, 6, &nred, rows, &pivot);
  printf("(a) pinned twice: %s\n    %s\n", LGNGetReturnFlagName(flag), last_msg);
  CHECK(flag == LGN_IC_FAIL || flag == LGN_LSETUP_FAIL, "pinned twice: %s",
        LGNGetReturnFlagName(flag));
  CHECK(nred == 3, "three redundant constraints, found %lld", (long long)nred);
  /* one of each identical pair */
  for (i = 0; i < 3 && nred == 3; i++) {
    int count = 0, k;
    for (k = 0; k < 3; k++) count += rows[k] == i || rows[k] == i + 3;
    pairs_ok = pairs_ok && count == 1;
  }
  CHECK(pairs_ok, "one of each pair of identical rows");
  CHECK(strstr(last_msg, "Redundant constraints") != NULL && strstr(last_msg, "rank 3 of 6"),
        "the message names them: %s", last_msg);
  N_VDestroy(q);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
}

/* An all-revolute spatial four-bar in the x-y plane, axes z: bodies with
 * R = I at the link midpoints, joint points as offsets from them. */
static void FourBar(int sparse)
{
  SUNContext ctx;
  LGNGroup body = LGNGroup_R3xSO3(), G;
  LGNGroup f[3];
  Model md = {3, 1.0, NULL, 0};
  const double pi = acos(-1.0), L1 = 0.3, L2 = 1.0, L3 = 0.8;
  const double A[3] = {0, 0, 0}, D[3] = {1, 0, 0}, z[3] = {0, 0, 1};
  double B[3], C[3], d, a, hh, mid[3], x[3][3], *qd;
  const double *P[3][2];
  sunindextype nred = 0, rows[20], pivot = -1, m, i;
  N_Vector q;
  int k, flag, joints_named = 1;
  char what[160];

  SUNContext_Create(NULL, &ctx);
  f[0] = f[1] = f[2] = body;
  G    = LGNGroup_Product(3, f);
  md.J = LGNJoints_Create(G);
  B[0] = L1 * cos(pi / 3); B[1] = L1 * sin(pi / 3); B[2] = 0.0;
  d  = sqrt((D[0] - B[0]) * (D[0] - B[0]) + (D[1] - B[1]) * (D[1] - B[1]));
  a  = (L2 * L2 - L3 * L3 + d * d) / (2 * d);
  hh = sqrt(L2 * L2 - a * a);
  for (i = 0; i < 3; i++) mid[i] = B[i] + a * (D[i] - B[i]) / d;
  C[0] = mid[0] - hh * (D[1] - B[1]) / d;
  C[1] = mid[1] + hh * (D[0] - B[0]) / d;
  C[2] = 0.0;
  P[0][0] = A; P[0][1] = B;
  P[1][0] = B; P[1][1] = C;
  P[2][0] = D; P[2][1] = C;
  q  = N_VNew_Serial(21, ctx);
  qd = N_VGetArrayPointer(q);
  for (k = 0; k < 3; k++) {
    for (i = 0; i < 3; i++) x[k][i] = 0.5 * (P[k][0][i] + P[k][1][i]);
    qd[7 * k] = x[k][0]; qd[7 * k + 1] = x[k][1]; qd[7 * k + 2] = x[k][2];
    qd[7 * k + 3] = 1.0; qd[7 * k + 4] = qd[7 * k + 5] = qd[7 * k + 6] = 0.0;
  }
  {
    double s0[3], s1[3];
    for (i = 0; i < 3; i++) s0[i] = A[i] - x[0][i];
    LGNJoints_AddRevolute(md.J, LGN_GROUND, A, z, 0, s0, z);
    for (i = 0; i < 3; i++) { s0[i] = B[i] - x[0][i]; s1[i] = B[i] - x[1][i]; }
    LGNJoints_AddRevolute(md.J, 0, s0, z, 1, s1, z);
    for (i = 0; i < 3; i++) { s0[i] = C[i] - x[1][i]; s1[i] = C[i] - x[2][i]; }
    LGNJoints_AddRevolute(md.J, 1, s0, z, 2, s1, z);
    for (i = 0; i < 3; i++) s0[i] = D[i] - x[2][i];
    LGNJoints_AddRevolute(md.J, 2, s0, z, LGN_GROUND, D, z);
  }
  m = LGNJoints_NumConstraints(md.J);
  CHECK(m == 20, "20 constraints, got %lld", (long long)m);
  flag = Run(&md, G, q, sparse, m, &nred, rows, &pivot);
  printf("(b) all-revolute four-bar (%s): %s\n    %s\n", sparse ? "KLU" : "dense",
         LGNGetReturnFlagName(flag), last_msg);
  CHECK(flag == LGN_IC_FAIL || flag == LGN_LSETUP_FAIL, "four-bar: %s",
        LGNGetReturnFlagName(flag));
  CHECK(nred == 3, "three redundant constraints, found %lld", (long long)nred);
  for (i = 0; i < nred && i < 20; i++) {
    flag = LGNJoints_DescribeConstraint(md.J, rows[i], what, sizeof what);
    printf("    redundant constraint %lld: %s\n", (long long)rows[i], what);
    joints_named = joints_named && flag == LGN_SUCCESS && strstr(what, "revolute joint") != NULL;
  }
  CHECK(joints_named, "the redundant constraints are named by joint");
  CHECK(strstr(last_msg, "rank 17 of 20") != NULL, "rank 17 of 20 in the message: %s", last_msg);
  LGNJoints_SetErrFile(md.J, NULL); /* the expected complaint */
  CHECK(LGNJoints_DescribeConstraint(md.J, 20, what, sizeof what) == LGN_ILL_INPUT,
        "row 20 is out of range");
  LGNJoints_Destroy(&md.J);
  N_VDestroy(q);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
}

static void MasslessDirection(void)
{
  SUNContext ctx;
  LGNGroup G = LGNGroup_R3xSO3();
  Model md = {1, 0.0, NULL, 0};
  N_Vector q;
  sunindextype nred = 0, pivot = -1;
  int flag;
  SUNContext_Create(NULL, &ctx);
  q = N_VNew_Serial(7, ctx);
  N_VConst(0.0, q);
  N_VGetArrayPointer(q)[3] = 1.0;
  flag = Run(&md, G, q, 0, 0, &nred, NULL, &pivot);
  printf("(c) no mass along x: %s\n    %s\n", LGNGetReturnFlagName(flag), last_msg);
  CHECK(flag == LGN_IC_FAIL || flag == LGN_LSETUP_FAIL, "massless: %s",
        LGNGetReturnFlagName(flag));
  CHECK(pivot == 0 && nred == 0, "zero pivot at unknown 0 (got %lld), nothing redundant",
        (long long)pivot);
  CHECK(strstr(last_msg, "body 0, translation x") != NULL, "named in words: %s", last_msg);
  N_VDestroy(q);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
}

int main(void)
{
  PinnedTwice();
  FourBar(0);
#if defined(LGN_HAVE_KLU)
  FourBar(1);
#endif
  MasslessDirection();
  printf("The dense cases again with LGNLinSol_Dense:\n");
  use_lgn_lu = 1;
  PinnedTwice();
  FourBar(0);
  MasslessDirection();
  return test_summary("test_singular");
}
