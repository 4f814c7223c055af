/* -----------------------------------------------------------------------------
 * Lignum test: one chain across MPI ranks, with joints and force elements
 * between bodies of different ranks (ghost bodies, LGNSetHalo). Run on 1,
 * 2 and 4 ranks (CTest mpi_chain_np*).
 *
 * The model: N bodies (R^3 x SO(3)) hanging from a spherical joint at the
 * origin, consecutive bodies joined by spherical joints and rotational
 * spring-dampers, under gravity; it starts horizontal and at rest, so it
 * swings and twists. Rank r owns a contiguous segment [lo, hi) of the
 * bodies; its ghost is body lo - 1 (r > 0). Each joint and spring between
 * k - 1 and k is declared on the rank owning k, so the segment boundaries
 * carry both. K_t and C_t come from Lignum's difference quotients, which
 * thus run over the ghosts' columns too.
 *
 * Every rank also integrates the whole chain on one process (serial
 * vectors, LGNLinSol_Dense) as the reference, and compares its own bodies:
 *  (a) fixed steps, generalized-alpha at index 3, SPGMR with the block
 *      preconditioner (one block per rank) and tight Newton and Krylov
 *      tolerances: the trajectory equals the direct one-process solve to
 *      1e-9 (Krylov's tolerance), at every output time;
 *  (b) error control (tol 1e-6), BDF with modified Newton: the same steps,
 *      failures and order counts on every rank, and the end state within
 *      1e-5 of the one-process BDF run with the same settings;
 *  (c) Phi(q) of every joint (including those at the boundaries) small at
 *      the end, and the ghosts' entries of the returned q equal to their
 *      owners';
 *  (d) a force callback failing on the last rank at t > 0.05: LGN_FORCE_FAIL
 *      on every rank at the same t, no hang;
 *  (e) misuse: a halo with a ghost no rank owns, or with a global number
 *      owned by every rank, is refused on every rank;
 *      a dense solver of the rank's matrix, and a Krylov template whose
 *      length counts the ghosts' unknowns, give LGN_LS_MISMATCH everywhere;
 *      ghosts left with a mass (LGNBodies_SetGhosts forgotten) give
 *      LGN_ILL_INPUT everywhere (their mass would be counted twice);
 *  (h) a joint and a spring between two ghosts (the next rank's first two
 *      bodies, declared on this rank): a constraint row with no owned
 *      column, in no block of the block preconditioner; (a) to 1e-9;
 *  (g) with PETSc: MUMPS on the sum of the ranks' subdomain matrices
 *      (LGNLinSol_PETScSubdomain, LGNGetGlobalIndices): (a) to 1e-10 (to
 *      t = 0.1 instead of 0.4 on more than one rank, for time);
 *  (f) index 2, exact kinematics, full Newton, from a start off the
 *      constraints projected by LGNCalcIC (q and v): the trajectory equals
 *      the one-process run's to 1e-9.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mpi.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_halo.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#if defined(LGN_HAVE_PETSC)
#include <lignum/lignum_petsc.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif
#include <nvector/nvector_mpiplusx.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sundials/sundials_math.h>
#include <sunmatrix/sunmatrix_dense.h>

#define NBODIES 12

static int rank = 0, nranks = 1, failures = 0;

#define CHECK(cond, ...)                                          \
  do {                                                            \
    if (!(cond)) {                                                \
      failures++;                                                 \
      printf("[rank %d] FAIL %s:%d: ", rank, __FILE__, __LINE__); \
      printf(__VA_ARGS__);                                        \
      printf("\n");                                               \
    }                                                             \
  } while (0)

typedef struct {
  LGNGroup body, G;
  LGNBodies bodies;
  LGNJoints joints;
  int lo, hi, nown, nghost;
  long int gid[NBODIES];
  int owner[NBODIES]; /* of each ghost */
  int fail_after;     /* (d): the force fails for t > 0.05 on this rank */
} Chain;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Chain *)ud)->bodies);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  Chain *c = (Chain *)ud;
  if (c->fail_after && t > 0.05) return -1;
  return LGNBodies_ForceFn(t, q, v, g, c->bodies);
}
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Chain *)ud)->joints, t, q, phi) ? -1 : 0;
}
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Chain *)ud)->joints, t, q, B) ? -1 : 0;
}
static int ConstrForce(sunrealtype t, N_Vector q, N_Vector lambda, N_Vector f, void *ud)
{
  return LGNJoints_ConstraintForce(((Chain *)ud)->joints, t, q, lambda, f) ? -1 : 0;
}

/* (e): a model that forgets LGNBodies_SetGhosts (its ghosts keep a mass) */
static int forget_ghosts = 0;

/* (h): the joint and spring between the next rank's first two bodies are
 * declared here, on two ghosts (and not there) */
static int ghost_pair = 0;

/* Rank r's first body of P ranks (r = P: the end). */
static int First(int r, int P) { return (int)(((long)r * NBODIES) / P); }

/* Does rank r (of P) hold the next rank's first two bodies as ghosts? */
static int TakesPair(int r, int P)
{
  return ghost_pair && r >= 0 && r + 1 < P && First(r + 2, P) - First(r + 1, P) >= 2;
}

/* Rank r's bodies [lo, hi) of P ranks (r < 0: the whole chain on one
 * process) and its ghosts, last: lo - 1 (r > 0), and with ghost_pair hi and
 * hi + 1. */
static int BuildChain(Chain *c, int r, int P)
{
  const int lo = r < 0 ? 0 : First(r, P), hi = r < 0 ? NBODIES : First(r + 1, P);
  const int pair = TakesPair(r, P), skip = r > 0 && TakesPair(r - 1, P);
  const sunrealtype L = 1.0, mass = 1.0, radius = 0.05;
  const sunrealtype J[3] = {0.5 * mass * radius * radius, mass * L * L / 12.0,
                            mass * L * L / 12.0};
  const sunrealtype gvec[3] = {0.0, 0.0, -9.81}, origin[3] = {0.0, 0.0, 0.0};
  const sunrealtype left[3] = {-0.5 * L, 0.0, 0.0}, right[3] = {0.5 * L, 0.0, 0.0};
  LGNGroup factors[NBODIES];
  int k, flag = 0;
  memset(c, 0, sizeof *c);
  c->lo     = lo;
  c->hi     = hi;
  c->nown   = hi - lo;
  c->nghost = (lo > 0 ? 1 : 0) + (pair ? 2 : 0);
  c->body   = LGNGroup_R3xSO3();
  for (k = 0; k < c->nown + c->nghost; k++) factors[k] = c->body;
  c->G = LGNGroup_Product(c->nown + c->nghost, factors);
  for (k = 0; k < c->nown; k++) c->gid[k] = lo + k;
  k = c->nown;
  if (lo > 0) {
    c->owner[k - c->nown] = r - 1;
    c->gid[k++]           = lo - 1;
  }
  if (pair) {
    c->owner[k - c->nown] = r + 1;
    c->gid[k++]           = hi;
    c->owner[k - c->nown] = r + 1;
    c->gid[k++]           = hi + 1;
  }
  c->bodies = LGNBodies_Create(c->G);
  c->joints = LGNJoints_Create(c->G);
  if (c->bodies == NULL || c->joints == NULL) return -1;
  flag = LGNBodies_SetGravity(c->bodies, gvec);
  for (k = 0; k < c->nown && !flag; k++)
    flag = LGNBodies_SetPrincipalInertia(c->bodies, k, mass * (1.0 + 0.1 * (lo + k)), J);
  if (!flag && c->nghost && !forget_ghosts) flag = LGNBodies_SetGhosts(c->bodies, c->nown);
  for (k = lo; k < hi && !flag; k++) {
    const int a = k == lo ? c->nown : k - 1 - lo; /* local number of body k - 1 */
    if (skip && k == lo + 1) continue; /* declared on rank r - 1 (h) */
    if (k == 0) {
      flag = LGNJoints_AddSpherical(c->joints, LGN_GROUND, origin, 0, left);
    } else {
      flag = LGNJoints_AddSpherical(c->joints, a, right, k - lo, left);
      if (!flag) flag = LGNBodies_AddRotationalSpringDamper(c->bodies, a, k - lo, 20.0, 0.5, NULL);
    }
  }
  if (pair && !flag) { /* (h) between the ghosts hi and hi + 1 */
    const int g0 = c->nown + (lo > 0 ? 1 : 0);
    flag = LGNJoints_AddSpherical(c->joints, g0, right, g0 + 1, left);
    if (!flag) flag = LGNBodies_AddRotationalSpringDamper(c->bodies, g0, g0 + 1, 20.0, 0.5, NULL);
  }
  return flag;
}

static void FreeChain(Chain *c)
{
  LGNJoints_Destroy(&c->joints);
  LGNBodies_Destroy(&c->bodies);
  LGNGroup_Destroy(c->G);
  LGNGroup_Destroy(c->body);
}

/* Horizontal along x, at rest; the ghost's entries garbage: with the halo
 * set before LGNInit (unread) not even a group element (zero quaternion),
 * after it (checked by LGNInit) one that normalises. */
static void InitialState(const Chain *c, sunrealtype *q, sunrealtype *v, int unread,
                         int inconsistent)
{
  int k, i;
  for (k = 0; k < c->nown + c->nghost; k++) {
    const long int g = c->gid[k];
    for (i = 0; i < 7; i++) q[7 * k + i] = 0.0;
    for (i = 0; i < 6; i++) v[6 * k + i] = 0.0;
    q[7 * k]     = (sunrealtype)g + 0.5;
    q[7 * k + 3] = 1.0;
    if (inconsistent) { /* (f): off the constraints, and moving */
      q[7 * k + 1] = 1e-3 * cos((double)g);
      v[6 * k + 2] = 0.1 * sin((double)g);
      v[6 * k + 4] = 0.2 * cos(2.0 * (double)g);
    }
    if (k >= c->nown) { /* the ghost: its owner's values must win */
      for (i = 0; i < 7; i++) q[7 * k + i] = 1e3;
      for (i = 0; i < 6; i++) v[6 * k + i] = -1e3;
      if (unread) q[7 * k + 3] = q[7 * k + 4] = q[7 * k + 5] = q[7 * k + 6] = 0.0;
    }
  }
}

#define NOUT 4
/* the outputs: t = out_dt, ..., NOUT out_dt */
static sunrealtype out_dt = 0.1;
typedef struct {
  sunrealtype q[NOUT][7 * NBODIES]; /* by global body */
  long int nst, netf, nncf, nord[6];
  int flag;
  sunrealtype tfail;
} Result;

enum { RUN_GA_FIXED = 0, RUN_BDF_ADAPTIVE = 1, RUN_INDEX2_CALCIC = 2 };
/* (e) misuse of the linear solver with a halo: none, a dense solver of the
 * rank's matrix, a Krylov template with the ghosts' unknowns too */
enum { SOLVER_RIGHT = 0, SOLVER_DENSE = 1, SOLVER_WRONG_LENGTH = 2, SOLVER_MUMPS = 3 };
static int misuse = SOLVER_RIGHT;

/* One integration of the chain c (with ghosts: across ranks on comm). */
static void Run(Chain *c, int kind, sunbooleantype across, MPI_Comm comm, SUNContext ctx,
                Result *res)
{
  const int nb = c->nown + c->nghost;
  const sunindextype nq = 7 * nb, nv = 6 * nb;
  N_Vector q = NULL, v = NULL, y = NULL, yloc = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  LGNHalo halo = NULL;
  void *mem = LGNCreate(ctx);
  sunindextype m;
  sunrealtype t = 0.0;
  int flag = 0, j, k;
  memset(res, 0, sizeof *res);
  if (across) {
    q = N_VMake_MPIPlusX(comm, N_VNew_Serial(nq, ctx), ctx);
    v = N_VMake_MPIPlusX(comm, N_VNew_Serial(nv, ctx), ctx);
  } else {
    q = N_VNew_Serial(nq, ctx);
    v = N_VNew_Serial(nv, ctx);
  }
  InitialState(c, N_VGetArrayPointer(q), N_VGetArrayPointer(v), kind == RUN_GA_FIXED,
               kind == RUN_INDEX2_CALCIC);
  m = LGNJoints_NumConstraints(c->joints);
  flag = LGNSetGroup(mem, c->G);
  if (!flag) flag = LGNSetUserData(mem, c);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetConstraintForceFn(mem, ConstrForce);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  /* (a) the halo before LGNInit (the ghost's entries of q0, v0 unread),
   * (b) after it (they must be a group element then: 1e3's normalise) */
  if (across) halo = LGNHalo_Create(comm, c->G, c->nown, c->gid, c->nghost ? c->owner : NULL);
  if (across && halo == NULL) flag = -1;
  if (!flag && across && kind != RUN_BDF_ADAPTIVE) flag = LGNSetHalo(mem, halo);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
#if defined(LGN_HAVE_PETSC)
  if (across && misuse == SOLVER_MUMPS) { /* (g) the sum of the ranks' matrices */
    sunindextype n = 0, *idx = NULL;
    if (!flag) flag = LGNSetHalo(mem, halo);
    if (!flag) flag = LGNGetSubdomainSize(mem, &n);
    idx  = (sunindextype *)malloc((size_t)SUNMAX(n, 1) * sizeof(sunindextype));
    if (!flag) flag = LGNGetGlobalIndices(mem, idx);
    yloc = N_VNew_Serial(6 * c->nown + m, ctx);
    y    = N_VMake_MPIPlusX(comm, yloc, ctx);
    A    = SUNSparseMatrix(n, n, 1, CSC_MAT, ctx);
    LS   = flag ? NULL : LGNLinSol_PETScSubdomain(y, A, idx, ctx);
    if (!flag && LS == NULL) flag = -1;
    if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
    free(idx);
  } else
#endif
  if (across && misuse == SOLVER_DENSE) {
    y  = N_VNew_Serial(nv + m, ctx);
    A  = SUNDenseMatrix(nv + m, nv + m, ctx);
    LS = LGNLinSol_Dense(y, A, ctx);
    if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  } else if (across) {
    if (!flag && kind == RUN_BDF_ADAPTIVE) flag = LGNSetHalo(mem, halo);
    /* the owned unknowns (with the ghosts': wrong) */
    yloc = N_VNew_Serial(6 * (misuse == SOLVER_WRONG_LENGTH ? nb : c->nown) + m, ctx);
    y    = N_VMake_MPIPlusX(comm, yloc, ctx);
    LS   = SUNLinSol_SPGMR(y, SUN_PREC_LEFT, 50, ctx);
    if (!flag) flag = LGNSetLinearSolver(mem, LS, NULL);
    if (!flag) flag = LGNSetBlockPreconditioner(mem, 1, NULL);
    if (!flag) flag = LGNSetEpsLin(mem, 1e-6);
  } else {
    y  = N_VNew_Serial(nv + m, ctx);
    A  = SUNDenseMatrix(nv + m, nv + m, ctx);
    LS = LGNLinSol_Dense(y, A, ctx);
    if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  }
  if (kind == RUN_GA_FIXED) {
    if (!flag) flag = LGNSetGenAlpha(mem, 0.8);
    if (!flag) flag = LGNSetStepSize(mem, 2e-3);
    if (!flag) flag = LGNSStolerances(mem, 1e-12, 1e-12);
  } else if (kind == RUN_INDEX2_CALCIC) {
    /* (f) index 2, exact kinematics, full Newton, an inconsistent start
     * projected by LGNCalcIC */
    if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
    if (!flag) flag = LGNSetConstraintIndex(mem, LGN_CONSTR_INDEX2);
    if (!flag) flag = LGNSetKinematics(mem, LGN_KINEMATICS_EXACT);
    if (!flag) flag = LGNSetStepSize(mem, 2e-3);
    if (!flag) flag = LGNSStolerances(mem, 1e-12, 1e-12);
    if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_QV);
  } else {
    if (!flag) flag = LGNSetBDF(mem, 5);
    if (!flag) flag = LGNSetNewtonMode(mem, LGN_NEWTON_MODIFIED);
    if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSStolerances(mem, 1e-6, 1e-6);
  }
  for (j = 0; j < NOUT && !flag; j++) {
    const sunrealtype *qd;
    flag = LGNSolve(mem, out_dt * (j + 1), &t, q, v, LGN_NORMAL);
    if (flag) break;
    qd = N_VGetArrayPointer(q);
    for (k = 0; k < nb; k++) memcpy(res->q[j] + 7 * c->gid[k], qd + 7 * k, 7 * sizeof(sunrealtype));
  }
  res->flag  = flag;
  res->tfail = t;
  LGNGetNumSteps(mem, &res->nst);
  LGNGetNumErrTestFails(mem, &res->netf);
  LGNGetNumNewtonConvFails(mem, &res->nncf);
  if (kind == RUN_BDF_ADAPTIVE) LGNGetNumStepsAtOrder(mem, res->nord);
  if (flag == 0) { /* (c): Phi small; the ghost equals its owner (checked by the caller) */
    N_Vector phi = N_VNew_Serial(SUNMAX(m, 1), ctx);
    sunrealtype pmax = 0.0;
    LGNJoints_Residual(c->joints, t, q, phi);
    for (k = 0; k < m; k++) pmax = SUNMAX(pmax, fabs(N_VGetArrayPointer(phi)[k]));
    /* the Newton tolerance of the run: 1e-12 (a), 1e-6 (b); index 2 (f):
     * the drift of Phi, O(h^2) per unit time */
    CHECK(misuse != SOLVER_RIGHT ||
              pmax < (kind == RUN_GA_FIXED ? 1e-10 : kind == RUN_BDF_ADAPTIVE ? 1e-6 : 1e-3),
          "|Phi| = %g at t = %g (rank's joints, boundary ones included)", pmax, t);
    N_VDestroy(phi);
  }
  LGNFree(&mem);
  LGNHalo_Destroy(&halo);
  SUNLinSolFree(LS);
  if (A != NULL) SUNMatDestroy(A);
  if (y != NULL) N_VDestroy(y);
  if (yloc != NULL) N_VDestroy(yloc);
  if (across) {
    N_VDestroy(N_VGetLocalVector_MPIPlusX(q));
    N_VDestroy(N_VGetLocalVector_MPIPlusX(v));
  }
  N_VDestroy(q);
  N_VDestroy(v);
}

static sunrealtype MaxDiffOwned(const Chain *c, const Result *a, const Result *b, int j)
{
  sunrealtype d = 0.0;
  int k, i;
  for (k = c->lo; k < c->hi; k++)
    for (i = 0; i < 7; i++) d = SUNMAX(d, fabs(a->q[j][7 * k + i] - b->q[j][7 * k + i]));
  return d;
}

static int SameOnAllRanks(long int x)
{
  long int lo = 0, hi = 0;
  MPI_Allreduce(&x, &lo, 1, MPI_LONG, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&x, &hi, 1, MPI_LONG, MPI_MAX, MPI_COMM_WORLD);
  return lo == hi;
}

int main(int argc, char **argv)
{
  SUNContext ctx = NULL;
  Chain whole, part;
  Result ref, par;
  int lo, j, total = 0;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  SUNContext_Create((void *)&(MPI_Comm){MPI_COMM_WORLD}, &ctx);
  lo = (int)(((long)rank * NBODIES) / nranks);
  if (BuildChain(&whole, -1, nranks) != 0 || BuildChain(&part, rank, nranks) != 0) {
    printf("[rank %d] model set-up failed\n", rank);
    MPI_Abort(MPI_COMM_WORLD, 2);
  }

  /* (a) fixed steps, tight tolerances: the direct one-process solve */
  Run(&whole, RUN_GA_FIXED, SUNFALSE, MPI_COMM_WORLD, ctx, &ref);
  Run(&part, RUN_GA_FIXED, SUNTRUE, MPI_COMM_WORLD, ctx, &par);
  CHECK(ref.flag == 0 && par.flag == 0, "(a) flags %d (one process), %d (ranks)", ref.flag,
        par.flag);
  for (j = 0; j < NOUT && par.flag == 0; j++) {
    const sunrealtype d = MaxDiffOwned(&part, &par, &ref, j);
    CHECK(d < 1e-9, "(a) t = %.1f: owned bodies differ from the one-process run by %g",
          0.1 * (j + 1), d);
    if (j == NOUT - 1) printf("[rank %d] (a) GA fixed step: max diff %.3g, %ld steps\n", rank, d, par.nst);
  }
  CHECK(par.nst == ref.nst, "(a) %ld steps vs %ld", par.nst, ref.nst);
  /* (c) the ghost's entries equal its owner's (the owner's own copy is in ref) */
  if (part.nghost && par.flag == 0) {
    sunrealtype d = 0.0;
    int i;
    for (i = 0; i < 7; i++)
      d = SUNMAX(d, fabs(par.q[NOUT - 1][7 * (lo - 1) + i] - ref.q[NOUT - 1][7 * (lo - 1) + i]));
    CHECK(d < 1e-9, "(c) the ghost differs from its owner's values by %g", d);
  }

  /* (b) error control, BDF, modified Newton */
  Run(&whole, RUN_BDF_ADAPTIVE, SUNFALSE, MPI_COMM_WORLD, ctx, &ref);
  Run(&part, RUN_BDF_ADAPTIVE, SUNTRUE, MPI_COMM_WORLD, ctx, &par);
  CHECK(ref.flag == 0 && par.flag == 0, "(b) flags %d (one process), %d (ranks)", ref.flag,
        par.flag);
  CHECK(SameOnAllRanks(par.nst) && SameOnAllRanks(par.netf) && SameOnAllRanks(par.nncf) &&
            SameOnAllRanks(par.nord[5]) && SameOnAllRanks(par.nord[3]),
        "(b) the ranks took different decisions (%ld steps)", par.nst);
  if (par.flag == 0) {
    const sunrealtype d = MaxDiffOwned(&part, &par, &ref, NOUT - 1);
    CHECK(d < 1e-5, "(b) end state differs from the one-process BDF run by %g", d);
    printf("[rank %d] (b) BDF adaptive: %ld steps (one process %ld), diff %.3g\n", rank, par.nst,
           ref.nst, d);
  }

  /* (h) the joint and spring between the next rank's first two bodies
   * declared here, on two ghosts: a constraint row with no owned column */
  if (nranks > 1) {
    Chain pairs;
    ghost_pair = 1;
    const int built = BuildChain(&pairs, rank, nranks);
    CHECK(built == 0, "(h) model set-up: %d", built);
    if (built == 0) {
      Run(&whole, RUN_GA_FIXED, SUNFALSE, MPI_COMM_WORLD, ctx, &ref);
      Run(&pairs, RUN_GA_FIXED, SUNTRUE, MPI_COMM_WORLD, ctx, &par);
      CHECK(par.flag == 0, "(h) a joint between two ghosts: flag %d", par.flag);
      if (par.flag == 0) {
        const sunrealtype d = MaxDiffOwned(&pairs, &par, &ref, NOUT - 1);
        CHECK(d < 1e-9, "(h) a joint between two ghosts: %g from the one-process run", d);
        printf("[rank %d] (h) joint between two ghosts: max diff %.3g\n", rank, d);
      }
    }
    FreeChain(&pairs);
    ghost_pair = 0;
  }

  /* (f) index 2, exact kinematics, LGNCalcIC from an inconsistent start */
  Run(&whole, RUN_INDEX2_CALCIC, SUNFALSE, MPI_COMM_WORLD, ctx, &ref);
  Run(&part, RUN_INDEX2_CALCIC, SUNTRUE, MPI_COMM_WORLD, ctx, &par);
  CHECK(ref.flag == 0 && par.flag == 0, "(f) flags %d (one process), %d (ranks)", ref.flag,
        par.flag);
  for (j = 0; j < NOUT && par.flag == 0; j++) {
    const sunrealtype d = MaxDiffOwned(&part, &par, &ref, j);
    CHECK(d < 1e-9, "(f) t = %.1f: owned bodies differ from the one-process run by %g",
          0.1 * (j + 1), d);
    if (j == NOUT - 1) printf("[rank %d] (f) index 2 + LGNCalcIC: max diff %.3g\n", rank, d);
  }

  /* (d) the force fails on the last rank after t = 0.05 */
  part.fail_after = rank == nranks - 1;
  {
    FILE *quiet = fopen("/dev/null", "w");
    (void)quiet;
    Run(&part, RUN_GA_FIXED, SUNTRUE, MPI_COMM_WORLD, ctx, &par);
    if (quiet != NULL) fclose(quiet);
  }
  CHECK(par.flag == LGN_FORCE_FAIL, "(d) flag %d, expected LGN_FORCE_FAIL", par.flag);
  CHECK(SameOnAllRanks((long int)(par.tfail * 1e9)), "(d) the ranks stopped at different t");
  part.fail_after = 0;

  /* (e) a ghost whose owner does not own it: refused everywhere */
  {
    long int bad[NBODIES];
    int owner = nranks > 1 ? (rank + 1) % nranks : 0;
    LGNHalo h;
    memcpy(bad, part.gid, sizeof bad);
    if (nranks > 1 && part.nghost) bad[part.nown] = NBODIES + 5; /* nobody's */
    h = nranks > 1 && part.nghost
            ? LGNHalo_Create(MPI_COMM_WORLD, part.G, part.nown, bad, &owner)
            : LGNHalo_Create(MPI_COMM_WORLD, part.G, part.nown, part.gid,
                             part.nghost ? part.owner : NULL);
    if (nranks > 1)
      CHECK(h == NULL, "(e) a halo with a ghost of no rank was accepted");
    else
      CHECK(h != NULL, "(e) a halo without ghosts was refused");
    LGNHalo_Destroy(&h);
  }
  /* (e) one body per rank, no ghosts: global number 0 owned by every rank is
   * refused (each number has exactly one owner), its own rank's number not */
  {
    LGNGroup G1 = LGNGroup_R3xSO3();
    const long int zero = 0, mine = rank;
    LGNHalo h = LGNHalo_Create(MPI_COMM_WORLD, G1, 1, &zero, NULL);
    if (nranks > 1)
      CHECK(h == NULL, "(e) global number 0 owned by all %d ranks was accepted", nranks);
    else
      CHECK(h != NULL, "(e) one rank owning global number 0 was refused");
    LGNHalo_Destroy(&h);
    h = LGNHalo_Create(MPI_COMM_WORLD, G1, 1, &mine, NULL);
    CHECK(h != NULL, "(e) a body of global number %ld per rank was refused", mine);
    LGNHalo_Destroy(&h);
    LGNGroup_Destroy(G1);
  }

#if defined(LGN_HAVE_PETSC)
  /* (g) MUMPS on the sum of the ranks' subdomain matrices */
  misuse = SOLVER_MUMPS;
  /* on more ranks to t = 0.1 only: each MUMPS solve there waits on the
   * other ranks (on a loaded 2-core machine this part took 48 s of the 88
   * of 2 ranks at t = 0.4) */
  out_dt = nranks > 1 ? SUN_RCONST(0.025) : SUN_RCONST(0.1);
  Run(&whole, RUN_GA_FIXED, SUNFALSE, MPI_COMM_WORLD, ctx, &ref);
  Run(&part, RUN_GA_FIXED, SUNTRUE, MPI_COMM_WORLD, ctx, &par);
  misuse = SOLVER_RIGHT;
  CHECK(par.flag == 0, "(g) MUMPS across the ranks: flag %d", par.flag);
  for (j = 0; j < NOUT && par.flag == 0; j++) {
    const sunrealtype d = MaxDiffOwned(&part, &par, &ref, j);
    CHECK(d < 1e-10, "(g) t = %.3g: owned bodies differ from the one-process run by %g",
          out_dt * (j + 1), d);
    if (j == NOUT - 1) printf("[rank %d] (g) MUMPS: max diff %.3g\n", rank, d);
  }
  out_dt = SUN_RCONST(0.1);
#endif

  /* (e) a solver of one rank's matrix, and a Krylov template that counts
   * the ghosts: LGN_LS_MISMATCH on every rank (with ghosts somewhere) */
  if (nranks > 1) {
    misuse = SOLVER_DENSE;
    Run(&part, RUN_GA_FIXED, SUNTRUE, MPI_COMM_WORLD, ctx, &par);
    CHECK(par.flag == LGN_LS_MISMATCH, "(e) dense solver with a halo: flag %d", par.flag);
    misuse = SOLVER_WRONG_LENGTH;
    Run(&part, RUN_GA_FIXED, SUNTRUE, MPI_COMM_WORLD, ctx, &par);
    CHECK(par.flag == LGN_LS_MISMATCH, "(e) Krylov template of the wrong length: flag %d",
          par.flag);
    misuse = SOLVER_RIGHT;
    /* ghosts with a mass of their own (LGNBodies_SetGhosts forgotten): the
     * sum over the ranks would count them twice; refused on every rank */
    {
      Chain massive;
      forget_ghosts = 1;
      if (BuildChain(&massive, rank, nranks) == 0) {
        Run(&massive, RUN_GA_FIXED, SUNTRUE, MPI_COMM_WORLD, ctx, &par);
        CHECK(par.flag == LGN_ILL_INPUT, "(e) ghosts with a mass: flag %d", par.flag);
      }
      forget_ghosts = 0;
      FreeChain(&massive);
    }
  }

  MPI_Allreduce(&failures, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0) printf("test_mpi_chain on %d ranks: %d failures\n", nranks, total);
  FreeChain(&whole);
  FreeChain(&part);
  SUNContext_Free(&ctx);
  MPI_Finalize();
  return total == 0 ? 0 : 1;
}
