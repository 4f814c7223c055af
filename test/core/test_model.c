/* -----------------------------------------------------------------------------
 * The multibody model object (lignum_model.h) against hand-written
 * callbacks, bit for bit, and the helpers' one rule for dense and sparse
 * matrices.
 *
 * Model: three rods (length 1) on R^3 x SO(3) x SE(3) x R^3 x SO(3) under
 * gravity: rod 0 on a revolute joint to the ground about z, turned by a
 * rotation driver theta = 2 t; rod 1 on a spherical joint to rod 0; rod 2
 * on a universal joint to rod 1; a translational spring-damper from the
 * ground to rod 2 and a rotational one between rods 1 and 2. Variant with a
 * user force: a linear spring k_u (x_2 - c) on rod 2 and a damper c_u Omega_1
 * on rod 1, with their K and C.
 *
 * Asserted:
 *  1. dense and sparse (CSC, CSR) K_t = d g/dq + d(B^T lambda)/dq and C_t of
 *     the body and joint helpers summed into one matrix agree exactly (the
 *     sparse sum was wrong before the helpers added into sparse matrices);
 *     a sparse matrix zeroed with SUNMatZero and summed again agrees too;
 *  2. runs with LGNModel_Attach equal runs with hand-written callbacks bit
 *     for bit (q, v, lambda, steps, Newton iterations): dense at index 3 and
 *     2 (Phi_t of the driver), with and without the user force, and KLU
 *     (CSC) at index 3;
 *  3. bad input is refused with a flag and a message naming the argument,
 *     and a refused LGNModel_Attach changes nothing.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_model.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#ifdef LGN_HAVE_KLU
#include <sunlinsol/sunlinsol_klu.h>
#endif

#include "test_util.h"

#define NB 3
#define K_USER 40.0
#define C_USER 0.3

static const sunrealtype user_anchor[3] = {2.5, 0.2, -0.1};

typedef struct {
  LGNGroup leaf[2], G;
  LGNBodies bodies;
  LGNJoints joints;
  int user_force;
  SUNMatrix Ktmp; /* hand-written sparse sums */
} Sys;

static int Drive(sunrealtype t, sunrealtype f[3], void *data)
{
  (void)data;
  f[0] = 2.0 * t;
  f[1] = 2.0;
  f[2] = 0.0;
  return 0;
}

/* ---- the user force: g_u = k_u (x_2 - c) on rod 2, c_u Omega_1 on rod 1 -- */
static int UserForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const sunrealtype *qd = N_VGetArrayPointer(q), *vd = N_VGetArrayPointer(v);
  sunrealtype *gd = N_VGetArrayPointer(g);
  int i;
  (void)t;
  (void)ud;
  for (i = 0; i < 3; i++) {
    gd[12 + i] += K_USER * (qd[14 + i] - user_anchor[i]); /* x_2: q[14..16], v[12..14] */
    gd[9 + i] += C_USER * vd[9 + i];                      /* Omega_1: v[9..11]        */
  }
  return 0;
}

/* a diagonal block d I at rows and columns o..o+2, dense or sparse (empty) */
static int DiagBlock(SUNMatrix A, sunindextype o, sunrealtype d)
{
  int i;
  if (SUNMatGetID(A) == SUNMATRIX_DENSE) {
    for (i = 0; i < 3; i++) SM_ELEMENT_D(A, o + i, o + i) += d;
    return 0;
  }
  {
    const sunindextype np = SUNSparseMatrix_NP(A);
    sunindextype *ptr, *ind, j;
    sunrealtype *val;
    if (SUNSparseMatrix_NNZ(A) < 3 && SUNSparseMatrix_Reallocate(A, 3) != 0) return -1;
    ptr = SUNSparseMatrix_IndexPointers(A);
    ind = SUNSparseMatrix_IndexValues(A);
    val = SUNSparseMatrix_Data(A);
    for (j = 0; j <= np; j++) ptr[j] = j <= o ? 0 : (j >= o + 3 ? 3 : j - o);
    for (i = 0; i < 3; i++) {
      ind[i] = o + i;
      val[i] = d;
    }
  }
  return 0;
}

static int UserStiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                         SUNMatrix K, void *ud)
{
  (void)t, (void)q, (void)v, (void)vdot, (void)lambda, (void)ud;
  return DiagBlock(K, 12, K_USER);
}

static int UserDamping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  (void)t, (void)q, (void)v, (void)ud;
  return DiagBlock(C, 9, C_USER);
}

/* ---- hand-written callbacks, as a user wrote them before the model ------ */
static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Sys *)ud)->bodies);
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  Sys *s  = (Sys *)ud;
  int flg = LGNBodies_ForceFn(t, q, v, g, s->bodies);
  if (flg == 0 && s->user_force) {
    N_Vector gu = N_VClone(g);
    N_VConst(0.0, gu);
    UserForce(t, q, v, gu, NULL);
    N_VLinearSum(1.0, g, 1.0, gu, g);
    N_VDestroy(gu);
  }
  return flg;
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Sys *)ud)->joints, t, q, phi) ? -1 : 0;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Sys *)ud)->joints, t, q, B) ? -1 : 0;
}

static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Sys *)ud)->joints, t, q, v, z) ? -1 : 0;
}

static int ConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  return LGNJoints_TimeDerivative(((Sys *)ud)->joints, t, q, phit) ? -1 : 0;
}

/* K += T, T written by fn into a fresh matrix like K (the old recipe for
 * sparse sums: SUNMatScaleAdd) */
static int AddTerm(Sys *s, SUNMatrix K, int (*fn)(Sys *, SUNMatrix, void *), void *arg)
{
  int flg;
  if (SUNMatGetID(K) == SUNMATRIX_DENSE) return fn(s, K, arg);
  if (s->Ktmp != NULL) SUNMatDestroy(s->Ktmp);
  s->Ktmp = SUNSparseMatrix(SUNSparseMatrix_Rows(K), SUNSparseMatrix_Columns(K), 1,
                            SUNSparseMatrix_SparseType(K), K->sunctx);
  flg = fn(s, s->Ktmp, arg);
  if (flg == 0) flg = SUNMatScaleAdd(1.0, K, s->Ktmp);
  return flg;
}

typedef struct {
  sunrealtype t;
  N_Vector q, v, lambda;
} KArgs;

static int JointsK(Sys *s, SUNMatrix K, void *arg)
{
  KArgs *a = (KArgs *)arg;
  return LGNJoints_Stiffness(s->joints, a->t, a->q, a->lambda, K) ? -1 : 0;
}

static int UserK(Sys *s, SUNMatrix K, void *arg)
{
  (void)s, (void)arg;
  return DiagBlock(K, 12, K_USER);
}

static int UserC(Sys *s, SUNMatrix C, void *arg)
{
  (void)s, (void)arg;
  return DiagBlock(C, 9, C_USER);
}

static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  Sys *s  = (Sys *)ud;
  KArgs a = {t, q, v, lambda};
  int flg = LGNBodies_Stiffness(s->bodies, q, v, K) ? -1 : 0;
  (void)vdot;
  if (flg == 0) flg = AddTerm(s, K, JointsK, &a);
  if (flg == 0 && s->user_force) flg = AddTerm(s, K, UserK, NULL);
  return flg;
}

static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  Sys *s  = (Sys *)ud;
  int flg = LGNBodies_DampingFn(t, q, v, C, s->bodies);
  if (flg == 0 && s->user_force) flg = AddTerm(s, C, UserC, NULL);
  return flg;
}

/* ---- the system -------------------------------------------------------- */
static int BuildSys(Sys *s)
{
  const sunrealtype J[3] = {0.01, 0.1, 0.1}, grav[3] = {0.0, 0.0, -9.81};
  const sunrealtype o[3] = {0.0, 0.0, 0.0}, ea[3] = {-0.5, 0.0, 0.0}, eb[3] = {0.5, 0.0, 0.0};
  const sunrealtype ez[3] = {0.0, 0.0, 1.0}, ey[3] = {0.0, 1.0, 0.0}, ex[3] = {1.0, 0.0, 0.0};
  const sunrealtype anchor[3] = {3.0, 0.3, -0.8};
  LGNGroup f[NB];
  int k, flg = 0;
  memset(s, 0, sizeof *s);
  s->leaf[0] = LGNGroup_R3xSO3();
  s->leaf[1] = LGNGroup_SE3();
  f[0] = f[2] = s->leaf[0];
  f[1]        = s->leaf[1];
  s->G        = LGNGroup_Product(NB, f); /* nq = 21, nv = 18 */
  s->bodies   = LGNBodies_Create(s->G);
  s->joints   = LGNJoints_Create(s->G);
  if (s->bodies == NULL || s->joints == NULL) return -1;
  for (k = 0; k < NB && !flg; k++) flg = LGNBodies_SetPrincipalInertia(s->bodies, k, 1.0 + k, J);
  if (!flg) flg = LGNBodies_SetGravity(s->bodies, grav);
  if (!flg) flg = LGNBodies_AddSpringDamper(s->bodies, LGN_GROUND, anchor, 2, eb, 50.0, 2.0, 1.0);
  if (!flg) flg = LGNBodies_AddRotationalSpringDamper(s->bodies, 1, 2, 5.0, 0.5, NULL);
  if (!flg) flg = LGNJoints_AddRevolute(s->joints, LGN_GROUND, o, ez, 0, ea, ez);
  if (!flg) flg = LGNJoints_AddRotationDriver(s->joints, LGN_GROUND, ez, ex, 0, ex, Drive, NULL);
  if (!flg) flg = LGNJoints_AddSpherical(s->joints, 0, eb, 1, ea);
  if (!flg) flg = LGNJoints_AddUniversal(s->joints, 1, eb, ey, 2, ea, ez);
  return flg;
}

static void FreeSys(Sys *s)
{
  if (s->Ktmp != NULL) SUNMatDestroy(s->Ktmp);
  LGNJoints_Destroy(&s->joints);
  LGNBodies_Destroy(&s->bodies);
  LGNGroup_Destroy(s->G);
  LGNGroup_Destroy(s->leaf[0]);
  LGNGroup_Destroy(s->leaf[1]);
}

/* rods along x, identity rotations, at rest; a slight tilt of rod 2 */
static void InitialState(N_Vector q, N_Vector v)
{
  sunrealtype *qd = N_VGetArrayPointer(q);
  int k;
  for (k = 0; k < NB; k++) {
    qd[7 * k + 0] = 0.5 + k;
    qd[7 * k + 1] = qd[7 * k + 2] = 0.0;
    qd[7 * k + 3]                 = 1.0;
    qd[7 * k + 4] = qd[7 * k + 5] = qd[7 * k + 6] = 0.0;
  }
  N_VConst(0.0, v);
}

/* ---- 1. dense and sparse sums of the helpers --------------------------- */
static void ToDense(SUNMatrix S, SUNMatrix D)
{
  const int csc = SUNSparseMatrix_SparseType(S) == CSC_MAT;
  const sunindextype np = SUNSparseMatrix_NP(S);
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(S), *ind = SUNSparseMatrix_IndexValues(S);
  const sunrealtype *val = SUNSparseMatrix_Data(S);
  sunindextype j, p;
  SUNMatZero(D);
  for (j = 0; j < np; j++)
    for (p = ptr[j]; p < ptr[j + 1]; p++) {
      if (csc) SM_ELEMENT_D(D, ind[p], j) += val[p];
      else SM_ELEMENT_D(D, j, ind[p]) += val[p];
    }
}

static sunrealtype MaxDiff(SUNMatrix A, SUNMatrix B)
{
  const sunindextype n = SM_LDATA_D(A);
  sunindextype i;
  sunrealtype d = 0.0;
  for (i = 0; i < n; i++) d = fmax(d, fabs(SM_DATA_D(A)[i] - SM_DATA_D(B)[i]));
  return d;
}

static sunrealtype MaxAbs(SUNMatrix A)
{
  const sunindextype n = SM_LDATA_D(A);
  sunindextype i;
  sunrealtype d = 0.0;
  for (i = 0; i < n; i++) d = fmax(d, fabs(SM_DATA_D(A)[i]));
  return d;
}

static void CheckDenseSparseSums(Sys *s, SUNContext ctx)
{
  const sunindextype nv = s->G->nv, m = LGNJoints_NumConstraints(s->joints);
  N_Vector q = N_VNew_Serial(s->G->nq, ctx), v = N_VNew_Serial(nv, ctx),
           lam = N_VNew_Serial(m, ctx);
  SUNMatrix Kd = SUNDenseMatrix(nv, nv, ctx), Cd = SUNDenseMatrix(nv, nv, ctx),
            W = SUNDenseMatrix(nv, nv, ctx);
  sunrealtype *vd = N_VGetArrayPointer(v), *ld = N_VGetArrayPointer(lam);
  sunrealtype *qd = N_VGetArrayPointer(q);
  sunindextype i;
  int type, pass;
  InitialState(q, v);
  /* a generic state: rotated rods, velocities and multipliers */
  for (i = 0; i < NB; i++) {
    const sunrealtype phi[3] = {0.3 + 0.1 * (double)i, -0.2, 0.4 - 0.2 * (double)i};
    LGNQuaternionFromRotationVector(phi, qd + 7 * i + 3);
    qd[7 * i + 1] = 0.1 * i;
  }
  for (i = 0; i < nv; i++) vd[i] = 0.3 * sin(1.0 + i);
  for (i = 0; i < m; i++) ld[i] = cos(2.0 + i);
  SUNMatZero(Kd);
  SUNMatZero(Cd);
  CHECK(LGNBodies_Stiffness(s->bodies, q, v, Kd) == 0 &&
            LGNJoints_Stiffness(s->joints, 0.1, q, lam, Kd) == 0 &&
            LGNBodies_Damping(s->bodies, q, v, Cd) == 0,
        "dense K_t, C_t evaluated");
  for (type = CSC_MAT; type <= CSR_MAT; type++) {
    SUNMatrix Ks = SUNSparseMatrix(nv, nv, 1, type, ctx), Cs = SUNSparseMatrix(nv, nv, 1, type, ctx);
    for (pass = 0; pass < 2; pass++) {
      /* pass 1: the matrices hold last pass's entries, zeroed (SUNMatZero) */
      if (pass == 1) {
        SUNMatZero(Ks);
        SUNMatZero(Cs);
      }
      CHECK(LGNBodies_Stiffness(s->bodies, q, v, Ks) == 0 &&
                LGNJoints_Stiffness(s->joints, 0.1, q, lam, Ks) == 0 &&
                LGNBodies_Damping(s->bodies, q, v, Cs) == 0,
            "sparse K_t, C_t evaluated");
      ToDense(Ks, W);
      CHECK(MaxDiff(W, Kd) == 0.0, "%s K_t (bodies + joints, pass %d) = dense K_t: max diff %.3g",
            type == CSC_MAT ? "CSC" : "CSR", pass, MaxDiff(W, Kd));
      ToDense(Cs, W);
      CHECK(MaxDiff(W, Cd) == 0.0, "%s C_t (pass %d) = dense C_t: max diff %.3g",
            type == CSC_MAT ? "CSC" : "CSR", pass, MaxDiff(W, Cd));
    }
    /* the joints first, then the bodies: the same sum */
    SUNMatDestroy(Ks);
    Ks = SUNSparseMatrix(nv, nv, 1, type, ctx);
    CHECK(LGNJoints_Stiffness(s->joints, 0.1, q, lam, Ks) == 0 &&
              LGNBodies_Stiffness(s->bodies, q, v, Ks) == 0,
          "sparse K_t, joints first");
    ToDense(Ks, W);
    CHECK(MaxDiff(W, Kd) <= 1e-13 * MaxAbs(Kd),
          "%s K_t (joints + bodies) = dense K_t to round-off: max diff %.3g",
          type == CSC_MAT ? "CSC" : "CSR", MaxDiff(W, Kd));
    SUNMatDestroy(Ks);
    SUNMatDestroy(Cs);
  }
  /* the sum must hold both terms: neither alone equals it */
  SUNMatZero(W);
  LGNJoints_Stiffness(s->joints, 0.1, q, lam, W);
  CHECK(MaxDiff(W, Kd) > 1e-3, "the joints' K_t alone differs from the sum (%.3g)",
        MaxDiff(W, Kd));
  SUNMatZero(W);
  LGNBodies_Stiffness(s->bodies, q, v, W);
  CHECK(MaxDiff(W, Kd) > 1e-3, "the bodies' K_t alone differs from the sum (%.3g)",
        MaxDiff(W, Kd));
  SUNMatDestroy(W);
  SUNMatDestroy(Kd);
  SUNMatDestroy(Cd);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(lam);
}

/* ---- 2. runs: the model against the hand-written callbacks -------------- */
typedef struct {
  N_Vector q, v, lambda;
  long nsteps, nni;
  int flag;
} Result;

static void FreeResult(Result *r)
{
  N_VDestroy(r->q);
  N_VDestroy(r->v);
  N_VDestroy(r->lambda);
}

/* use_model: LGNModel_Attach, else the callbacks above. sparse: KLU (CSC). */
static Result Run(Sys *s, int use_model, int sparse, int index, SUNContext ctx)
{
  const sunindextype nv = s->G->nv, m = LGNJoints_NumConstraints(s->joints);
  const sunindextype n = nv + (index == LGN_CONSTR_INDEX3 || index == LGN_CONSTR_INDEX2 ? m : 2 * m);
  Result r;
  LGNModel model = NULL;
  N_Vector tmpl = N_VNew_Serial(n, ctx);
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  sunrealtype t = 0.0;
  void *mem = LGNCreate(ctx);
  int flag = 0, k;
  memset(&r, 0, sizeof r);
  r.q      = N_VNew_Serial(s->G->nq, ctx);
  r.v      = N_VNew_Serial(nv, ctx);
  r.lambda = N_VNew_Serial(m, ctx);
  InitialState(r.q, r.v);
  if (use_model) {
    model = LGNModel_Create(s->bodies, s->joints);
    if (s->user_force) {
      flag = LGNModel_SetUserForce(model, UserForce, UserStiffness, UserDamping);
    }
    if (!flag) flag = LGNModel_Attach(model, mem);
  } else {
    flag = LGNSetGroup(mem, s->G);
    if (!flag) flag = LGNSetUserData(mem, s);
    if (!flag) flag = LGNSetMassFn(mem, Mass);
    if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
    if (!flag) flag = LGNSetForceFn(mem, Force);
    if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
    if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
    if (!flag) flag = LGNSetConstraintTimeFn(mem, ConstrTime);
    if (!flag) flag = LGNSetStiffnessFn(mem, Stiffness);
    if (!flag) flag = LGNSetDampingFn(mem, Damping);
  }
  if (!flag) flag = LGNInit(mem, 0.0, r.q, r.v);
  if (sparse) {
#ifdef LGN_HAVE_KLU
    A  = SUNSparseMatrix(n, n, 1, CSC_MAT, ctx);
    LS = SUNLinSol_KLU(tmpl, A, ctx);
#endif
  } else {
    A  = SUNDenseMatrix(n, n, ctx);
    LS = LGNLinSol_Dense(tmpl, A, ctx);
  }
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetConstraintIndex(mem, index);
  if (!flag) flag = LGNSetStepSize(mem, 2e-3);
  if (!flag) flag = LGNSStolerances(mem, 1e-8, 1e-8);
  if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_QV);
  for (k = 1; k <= 4 && !flag; k++) flag = LGNSolve(mem, 0.1 * k, &t, r.q, r.v, LGN_NORMAL);
  if (!flag) flag = LGNGetMultipliers(mem, r.lambda);
  if (!flag) flag = LGNGetNumSteps(mem, &r.nsteps);
  if (!flag) flag = LGNGetNumNewtonIters(mem, &r.nni);
  r.flag = flag;
  LGNFree(&mem);
  LGNModel_Destroy(&model); /* after LGNFree */
  if (LS != NULL) SUNLinSolFree(LS);
  if (A != NULL) SUNMatDestroy(A);
  N_VDestroy(tmpl);
  return r;
}

static int SameVec(N_Vector a, N_Vector b)
{
  return N_VGetLength(a) == N_VGetLength(b) &&
         memcmp(N_VGetArrayPointer(a), N_VGetArrayPointer(b),
                (size_t)N_VGetLength(a) * sizeof(sunrealtype)) == 0;
}

static void CompareRuns(Sys *s, int sparse, int index, SUNContext ctx, const char *what)
{
  Result hand = Run(s, 0, sparse, index, ctx), mod = Run(s, 1, sparse, index, ctx);
  CHECK(hand.flag == 0 && mod.flag == 0, "%s: both runs succeed (flags %d, %d)", what, hand.flag,
        mod.flag);
  CHECK(hand.nsteps == 200 && mod.nsteps == hand.nsteps && mod.nni == hand.nni,
        "%s: same steps (%ld, %ld) and Newton iterations (%ld, %ld)", what, hand.nsteps,
        mod.nsteps, hand.nni, mod.nni);
  CHECK(SameVec(hand.q, mod.q) && SameVec(hand.v, mod.v) && SameVec(hand.lambda, mod.lambda),
        "%s: q, v, lambda bit for bit", what);
  /* the motion is not trivial: the driver turned rod 0 by 0.8 rad */
  CHECK(fabs(N_VGetArrayPointer(mod.q)[1] - 0.5 * sin(0.8)) < 1e-6,
        "%s: rod 0 follows the driver (y_0 = %.9f)", what, N_VGetArrayPointer(mod.q)[1]);
  FreeResult(&hand);
  FreeResult(&mod);
}

/* ---- 3. bad input --------------------------------------------------------- */
static char last_msg[512];
static int last_code;
static void Capture(int code, const char *module, const char *function, const char *msg,
                    void *data)
{
  (void)module, (void)data;
  last_code = code;
  snprintf(last_msg, sizeof last_msg, "%s: %s", function, msg);
}

static void CheckBadInput(Sys *s, SUNContext ctx)
{
  LGNGroup other = LGNGroup_Product(NB, (LGNGroup[]){s->leaf[0], s->leaf[1], s->leaf[0]});
  LGNJoints J2   = LGNJoints_Create(other);
  LGNModel model;
  N_Vector q = N_VNew_Serial(14, ctx), v = N_VNew_Serial(12, ctx);
  LGNGroup pair = LGNGroup_Product(2, s->leaf);
  void *mem;
  int flag;

  CHECK(LGNModel_Create(NULL, s->joints) == NULL, "Create(NULL bodies) refused");
  CHECK(LGNModel_Create(s->bodies, J2) == NULL, "Create with sets on different groups refused");
  model = LGNModel_Create(s->bodies, NULL);
  CHECK(model != NULL && LGNModel_NumConstraints(model) == 0 && LGNModel_GetJoints(model) == NULL,
        "a model without joints: m = 0");
  LGNModel_Destroy(&model);
  CHECK(model == NULL, "Destroy sets the handle to NULL");
  LGNModel_Destroy(&model); /* NULL allowed */

  model = LGNModel_Create(s->bodies, s->joints);
  CHECK(LGNModel_NumConstraints(model) == 5 + 1 + 3 + 4, "m = %lld",
        (long long)LGNModel_NumConstraints(model));
  CHECK(LGNModel_GetBodies(model) == s->bodies && LGNModel_GetJoints(model) == s->joints,
        "the sets are the model's");
  LGNModel_SetErrHandlerFn(model, Capture, NULL);
  CHECK(LGNModel_Attach(NULL, NULL) == LGN_ILL_INPUT, "Attach(NULL model) refused");
  CHECK(LGNModel_Attach(model, NULL) == LGN_MEM_NULL && strstr(last_msg, "lgn_mem") != NULL,
        "Attach(NULL memory) refused, naming lgn_mem: %s", last_msg);
  last_msg[0] = '\0';
  CHECK(LGNModel_SetUserForce(model, NULL, UserStiffness, NULL) == LGN_ILL_INPUT &&
            strstr(last_msg, "K") != NULL,
        "K without a force refused: %s", last_msg);
  CHECK(LGNModel_SetUserForce(NULL, UserForce, NULL, NULL) == LGN_ILL_INPUT,
        "SetUserForce(NULL model) refused");
  CHECK(LGNModel_SetUserData(NULL, NULL) == LGN_ILL_INPUT && LGNModel_GetUserData(NULL) == NULL,
        "SetUserData(NULL) refused");
  CHECK(LGNModel_SetUserData(model, s) == LGN_SUCCESS && LGNModel_GetUserData(model) == s,
        "user data kept");
  CHECK(LGNModel_SetErrHandlerFn(NULL, NULL, NULL) == LGN_ILL_INPUT &&
            LGNModel_SetErrFile(NULL, NULL) == LGN_ILL_INPUT,
        "error settings of a NULL model refused");

  /* an integrator initialised on two bodies (nq = 14): the model's group
   * (nq = 21) is refused and nothing changes: the run continues with its
   * own callbacks */
  mem  = LGNCreate(ctx);
  LGNSetErrFile(mem, NULL);
  flag = LGNSetGroup(mem, pair);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetUserData(mem, s);
  {
    sunrealtype *qd = N_VGetArrayPointer(q);
    LGNGroup_Identity(pair, qd);
  }
  N_VConst(0.0, v);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  CHECK(flag == 0, "two-body integrator set up");
  last_msg[0] = '\0';
  CHECK(LGNModel_Attach(model, mem) == LGN_ILL_INPUT && strstr(last_msg, "lgn_mem") != NULL &&
            strstr(last_msg, "nq = 21") != NULL,
        "Attach to an integrator of other sizes refused: %s", last_msg);
  LGNFree(&mem);
  LGNModel_Destroy(&model);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNJoints_Destroy(&J2);
  LGNGroup_Destroy(other);
  LGNGroup_Destroy(pair);
}

int main(void)
{
  SUNContext ctx;
  Sys s;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  CHECK(BuildSys(&s) == 0, "model built");
  CheckDenseSparseSums(&s, ctx);
  CompareRuns(&s, 0, LGN_CONSTR_INDEX3, ctx, "dense, index 3");
  CompareRuns(&s, 0, LGN_CONSTR_INDEX2, ctx, "dense, index 2");
  s.user_force = 1;
  CompareRuns(&s, 0, LGN_CONSTR_INDEX3, ctx, "dense, index 3, user force");
#ifdef LGN_HAVE_KLU
  CompareRuns(&s, 1, LGN_CONSTR_INDEX3, ctx, "KLU, index 3, user force");
  s.user_force = 0;
  CompareRuns(&s, 1, LGN_CONSTR_INDEX3, ctx, "KLU, index 3");
#endif
  s.user_force = 0;
  CheckBadInput(&s, ctx);
  FreeSys(&s);
  SUNContext_Free(&ctx);
  return test_summary("test_model");
}
