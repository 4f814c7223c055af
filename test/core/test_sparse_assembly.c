/* -----------------------------------------------------------------------------
 * The sparse iteration matrix through its scatter maps (lgn_assemble_sparse.c,
 * doc/theory.md §2). A chain of 6 rigid bodies (R^3 x SO(3) or SE(3),
 * spherical joints) is integrated three times in lock step, one step at a
 * time: with the maps as in use (the fill path whenever the patterns are
 * known), with every map dropped by the model's callbacks (so that every
 * assembly takes the build path), and with dense matrices. After each step
 *  (a) the two sparse runs hold the same A, bit for bit (indices and
 *      values), and the same state; the first run assembled most steps
 *      without building a map, the second built its maps at every assembly;
 *  (b) at step GROW_M the mass callback, and at GROW_C the damping
 *      callback, write entries outside the pattern so far (and at MOVE_C
 *      the damping entry moves to another row of its column, the counts
 *      unchanged): both sparse runs extend A's pattern (a new symbolic
 *      analysis, more entries, the new entries closed over T's blocks)
 *      and stay equal;
 *  (c) for CSC and CSR, full and modified Newton, index 3 and index 2 with
 *      the exact kinematics, analytic and difference-quotient tangents;
 *  (d) with Lignum's solves on a copy of KLU's factors (opted in): for CSC
 *      each new pattern is one fallback to KLU (LGNGetNumKLUFallbacks) and
 *      one more whole copy, and Lignum refactors in between; for CSR
 *      nothing is refactored into the copy.
 * With full Newton A also equals the dense run's A to round-off, and the
 * final states agree with the dense run's.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"   /* private: the memory record */
#include "lgn_sparse.h" /* private: the maps and their counter */
#include "models/chain.h"
#include "test_util.h"

#define NBODY  6
#define NSTEP  16
#define GROW_M 5  /* the mass callback couples body 0 with 1 and 2 from here */
#define GROW_C 10 /* the damping callback couples bodies 0 and 2 from here */
#define MOVE_C 13 /* ... through another row: the same counts, other rows */

/* ---------------------------------------------------------------------------
 * The model: the examples' chain with its own callbacks, whose patterns can
 * grow, and which can drop the scatter maps of the integrator using them.
 * ------------------------------------------------------------------------ */

typedef struct {
  RigidSystem *sys;
  void *mem;      /* the integrator of this model                      */
  int forget;     /* drop the maps at every callback: always the build path */
  int grow_M, grow_C;  /* grow_C = 2: the damping entry moved */
} Model;

/* Entries (r, c, v) of a matrix, written into a dense or sparse one. */
#define MAXENT 512
typedef struct {
  int n;
  sunindextype r[MAXENT], c[MAXENT];
  double v[MAXENT];
} Entries;

static void Add(Entries *E, sunindextype r, sunindextype c, double v)
{
  if (E->n < MAXENT) {
    E->r[E->n] = r;
    E->c[E->n] = c;
    E->v[E->n] = v;
    E->n++;
  }
}

/* The whole structure of S, as a callback writes it (entries in the order
 * given within each column or row). */
static int Put(const Entries *E, SUNMatrix S)
{
  sunindextype *ptr, *ind, *next, np, i;
  double *val;
  int e, csc;
  if (SUNMatGetID(S) == SUNMATRIX_DENSE) {
    SUNMatZero(S);
    for (e = 0; e < E->n; e++) SM_ELEMENT_D(S, E->r[e], E->c[e]) += E->v[e];
    return 0;
  }
  csc = SUNSparseMatrix_SparseType(S) == CSC_MAT;
  np  = SUNSparseMatrix_NP(S);
  if (SUNSparseMatrix_NNZ(S) < E->n && SUNSparseMatrix_Reallocate(S, E->n) != 0) return -1;
  ptr  = SUNSparseMatrix_IndexPointers(S);
  ind  = SUNSparseMatrix_IndexValues(S);
  val  = SUNSparseMatrix_Data(S);
  next = (sunindextype *)malloc((size_t)(np + 1) * sizeof *next);
  if (next == NULL) return -1;
  memset(ptr, 0, (size_t)(np + 1) * sizeof *ptr);
  for (e = 0; e < E->n; e++) ptr[(csc ? E->c[e] : E->r[e]) + 1]++;
  for (i = 0; i < np; i++) ptr[i + 1] += ptr[i];
  memcpy(next, ptr, (size_t)(np + 1) * sizeof *next);
  for (e = 0; e < E->n; e++) {
    const sunindextype q = next[csc ? E->c[e] : E->r[e]]++;
    ind[q] = csc ? E->r[e] : E->c[e];
    val[q] = E->v[e];
  }
  free(next);
  return 0;
}

/* The test's hook: every map of the integrator is forgotten. */
static void Forget(Model *md)
{
  LGNMem mem = (LGNMem)md->mem;
  int s;
  if (md->forget && mem != NULL && mem->ls.sp != NULL)
    for (s = 0; s < LGN_NMAPS; s++) mem->ls.sp->map[s].valid = SUNFALSE;
}

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  Model *md = (Model *)ud;
  const RigidSystem *sys = md->sys;
  Entries E;
  int k, i;
  (void)t;
  (void)q;
  E.n = 0;
  for (k = 0; k < NBODY; k++)
    for (i = 0; i < 3; i++) {
      Add(&E, 6 * k + i, 6 * k + i, sys->mass[k]);
      Add(&E, 6 * k + 3 + i, 6 * k + 3 + i, sys->inertia[3 * k + i]);
    }
  if (md->grow_M) {
    /* small inertial couplings of the rotations of body 0 and bodies 1
     * (inside A's pattern when K_t is a difference quotient on M u B^T B,
     * outside with the joints' K_t) and 2 (outside) */
    Add(&E, 3, 9, 1e-4);
    Add(&E, 9, 3, 1e-4);
    Add(&E, 3, 15, 1e-4);
    Add(&E, 15, 3, 1e-4);
  }
  Forget(md);
  return Put(&E, M);
}

static void Cross(const double *a, const double *b, double *c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Gravity and the gyroscopic terms (as models/rigid_bodies.c). */
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  Model *md = (Model *)ud;
  const RigidSystem *sys = md->sys;
  const double *qd = N_VGetArrayPointer(q), *vd = N_VGetArrayPointer(v);
  double *gd = N_VGetArrayPointer(g), Jw[3], R[9], mu[3];
  int k, i;
  (void)t;
  for (k = 0; k < NBODY; k++) {
    const double *u = vd + 6 * k, *w = u + 3, *J = sys->inertia + 3 * k;
    double *gk = gd + 6 * k;
    for (i = 0; i < 3; i++) Jw[i] = J[i] * w[i];
    Cross(w, Jw, gk + 3);
    if (sys->formulation == RB_SE3) { /* body frame: m w x U - R^T m gravity */
      LGNQuaternionToRotation(qd + 7 * k + 3, R);
      for (i = 0; i < 3; i++)
        mu[i] = sys->mass[k] * (R[i] * sys->gravity[0] + R[3 + i] * sys->gravity[1] +
                                R[6 + i] * sys->gravity[2]);
      Cross(w, u, gk);
      for (i = 0; i < 3; i++) gk[i] = sys->mass[k] * gk[i] - mu[i];
    } else {
      for (i = 0; i < 3; i++) gk[i] = -sys->mass[k] * sys->gravity[i];
    }
  }
  Forget(md);
  return 0;
}

/* (a~)_ij, a~ b = a x b */
static double Skew(const double *a, int i, int j)
{
  return i == (j + 1) % 3 ? a[(j + 2) % 3] : i == (j + 2) % 3 ? -a[(j + 1) % 3] : 0.0;
}

/* C = dg/dv: d(w x J w)/dw = w~ J - (J w)~; in SE(3) also d(m w x U) =
 * m w~ dU - m U~ dw. */
static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  Model *md = (Model *)ud;
  const RigidSystem *sys = md->sys;
  const int se3 = sys->formulation == RB_SE3;
  const double *vd = N_VGetArrayPointer(v);
  Entries E;
  int k, i, j;
  (void)t;
  (void)q;
  E.n = 0;
  for (k = 0; k < NBODY; k++) {
    const double *u = vd + 6 * k, *w = u + 3, *J = sys->inertia + 3 * k, m = sys->mass[k];
    const sunindextype o = 6 * k;
    double Jw[3];
    for (i = 0; i < 3; i++) Jw[i] = J[i] * w[i];
    for (j = 0; j < 3; j++) { /* columns: U (SE(3) only), then w */
      for (i = 0; i < 3 && se3; i++) Add(&E, o + i, o + j, m * Skew(w, i, j));
    }
    for (j = 0; j < 3; j++) {
      for (i = 0; i < 3 && se3; i++) Add(&E, o + i, o + 3 + j, -m * Skew(u, i, j));
      for (i = 0; i < 3; i++) Add(&E, o + 3 + i, o + 3 + j, Skew(w, i, j) * J[j] - Skew(Jw, i, j));
    }
  }
  /* body 2's translation on body 0's rotation */
  if (md->grow_C) Add(&E, md->grow_C == 1 ? 12 : 14, 4, 1.0);
  Forget(md);
  return Put(&E, C);
}

static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                     N_Vector lambda, SUNMatrix K, void *ud)
{
  Model *md = (Model *)ud;
  (void)v;
  (void)vdot;
  Forget(md);
  return LGNJoints_Stiffness(md->sys->joints, t, q, lambda, K) == 0 ? 0 : -1;
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->sys->joints, t, q, phi) == 0 ? 0 : -1;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->sys->joints, t, q, B) == 0 ? 0 : -1;
}

/* ---------------------------------------------------------------------------
 * Runs
 * ------------------------------------------------------------------------ */

/* The dense solver factors A in place: its setup keeps a copy of A first. */
static SUNMatrix dense_copy = NULL;
static int (*dense_setup)(SUNLinearSolver, SUNMatrix) = NULL;

static int SetupKeepingA(SUNLinearSolver S, SUNMatrix A)
{
  if (dense_copy != NULL) SUNMatCopy(A, dense_copy);
  return dense_setup(S, A);
}

typedef struct {
  const char *name;
  RigidFormulation formulation;
  int sparsetype;      /* CSC_MAT or CSR_MAT */
  int newton;
  int index, kinematics;
  int tangents;        /* 1: K (R^3 x SO(3) only) and C from the model; 0: DQ */
} Config;

typedef struct {
  Model md;
  void *mem;
  SUNMatrix A, Acopy; /* Acopy: a dense A before its factorisation */
  SUNLinearSolver LS;
  N_Vector q, v, tmpl;
} Run;

static int RunCreate(Run *r, RigidSystem *sys, const Config *c, int dense, int forget,
                     SUNContext ctx)
{
  const sunindextype nv = 6 * NBODY, m = LGNJoints_NumConstraints(sys->joints), n = nv + m;
  int flag;
  memset(r, 0, sizeof *r);
  r->md.sys    = sys;
  r->md.forget = forget;
  r->q         = N_VClone(sys->q0);
  r->v         = N_VClone(sys->v0);
  N_VScale(1.0, sys->q0, r->q);
  N_VScale(1.0, sys->v0, r->v);
  r->tmpl = N_VNew_Serial(n, ctx);
  if (dense) {
    r->A  = SUNDenseMatrix(n, n, ctx);
    r->LS = SUNLinSol_Dense(r->tmpl, r->A, ctx);
    r->Acopy         = SUNDenseMatrix(n, n, ctx);
    dense_copy       = r->Acopy;
    dense_setup      = r->LS->ops->setup;
    r->LS->ops->setup = SetupKeepingA;
  } else {
    r->A  = SUNSparseMatrix(n, n, 1, c->sparsetype, ctx);
    r->LS = SUNLinSol_KLU(r->tmpl, r->A, ctx);
  }
  r->mem    = LGNCreate(ctx);
  /* the step's own values (q_n, v_n, vdot_n, lambda_n): not the consistent,
   * projected outputs (LGNSetConsistentOutputs, LGNSetProjectOutputs) */
  LGNSetConsistentOutputs(r->mem, SUNFALSE);
  LGNSetProjectOutputs(r->mem, LGN_PROJECT_NONE);
  r->md.mem = r->mem;
  flag = LGNSetGroup(r->mem, sys->G);
  if (!flag) flag = LGNInit(r->mem, 0.0, sys->q0, sys->v0);
  if (!flag) flag = LGNSetUserData(r->mem, &r->md);
  if (!flag) flag = LGNSetMassFn(r->mem, Mass);
  if (!flag) flag = LGNSetForceFn(r->mem, Force);
  if (!flag) flag = LGNSetConstraints(r->mem, m, Constr, ConstrJac);
  if (!flag && c->tangents && c->formulation == RB_R3XSO3)
    flag = LGNSetStiffnessFn(r->mem, Stiffness);
  if (!flag && c->tangents) flag = LGNSetDampingFn(r->mem, Damping);
  if (!flag) flag = LGNSetLinearSolver(r->mem, r->LS, r->A);
  /* Lignum's solves on a copy of KLU's factors, off by default: opted in,
   * as when this test was written */
  if (!flag && !dense) flag = LGNSetOwnKLUSolves(r->mem, SUNTRUE);
  if (!flag) flag = LGNSetStepSize(r->mem, 2e-3);
  if (!flag) flag = LGNSetGenAlpha(r->mem, 0.9);
  if (!flag) flag = LGNSetNewtonMode(r->mem, c->newton);
  if (!flag && c->newton == LGN_NEWTON_MODIFIED) flag = LGNSetPredictor(r->mem, LGN_PREDICTOR_EXTRAPOLATE);
  if (!flag && c->newton == LGN_NEWTON_MODIFIED) flag = LGNSetLSetupFrequency(r->mem, 2);
  if (!flag) flag = LGNSetConstraintIndex(r->mem, c->index);
  if (!flag) flag = LGNSetKinematics(r->mem, c->kinematics);
  return flag;
}

static void RunFree(Run *r)
{
  LGNFree(&r->mem);
  SUNLinSolFree(r->LS);
  SUNMatDestroy(r->A);
  if (r->Acopy != NULL) {
    SUNMatDestroy(r->Acopy);
    dense_copy = NULL;
  }
  N_VDestroy(r->q);
  N_VDestroy(r->v);
  N_VDestroy(r->tmpl);
}

/* Same pattern and values, to the last bit. */
static int SameSparse(SUNMatrix A, SUNMatrix B)
{
  const sunindextype np = SUNSparseMatrix_NP(A);
  const sunindextype *pa = SUNSparseMatrix_IndexPointers(A), *pb = SUNSparseMatrix_IndexPointers(B);
  const sunindextype nnz = pa[np];
  return SUNSparseMatrix_NP(B) == np && memcmp(pa, pb, (size_t)(np + 1) * sizeof *pa) == 0 &&
         memcmp(SUNSparseMatrix_IndexValues(A), SUNSparseMatrix_IndexValues(B),
                (size_t)nnz * sizeof(sunindextype)) == 0 &&
         memcmp(SUNSparseMatrix_Data(A), SUNSparseMatrix_Data(B),
                (size_t)nnz * sizeof(sunrealtype)) == 0;
}

static int SameVector(N_Vector x, N_Vector y)
{
  return memcmp(N_VGetArrayPointer(x), N_VGetArrayPointer(y),
                (size_t)N_VGetLength(x) * sizeof(sunrealtype)) == 0;
}

/* A(r, c) is in the pattern of the sparse A. */
static int HasEntry(SUNMatrix A, sunindextype r, sunindextype c)
{
  const int csc = SUNSparseMatrix_SparseType(A) == CSC_MAT;
  const sunindextype o = csc ? c : r, x = csc ? r : c;
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(A), *ind = SUNSparseMatrix_IndexValues(A);
  sunindextype p;
  for (p = ptr[o]; p < ptr[o + 1]; p++)
    if (ind[p] == x) return 1;
  return 0;
}

/* max |S - D| over all entries of the sparse S and the dense D, and max |D|. */
static double DiffDense(SUNMatrix S, SUNMatrix D, double *dmax)
{
  const sunindextype n = SUNDenseMatrix_Rows(D);
  const int csc = SUNSparseMatrix_SparseType(S) == CSC_MAT;
  const sunindextype *ptr = SUNSparseMatrix_IndexPointers(S), *ind = SUNSparseMatrix_IndexValues(S);
  const double *val = SUNSparseMatrix_Data(S);
  double *full = (double *)calloc((size_t)(n * n), sizeof *full), d = 0.0;
  sunindextype o, p, i, j;
  *dmax = 0.0;
  if (full == NULL) return INFINITY;
  for (o = 0; o < n; o++)
    for (p = ptr[o]; p < ptr[o + 1]; p++) {
      i = csc ? ind[p] : o;
      j = csc ? o : ind[p];
      full[i + j * n] += val[p];
    }
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++) {
      d     = fmax(d, fabs(full[i + j * n] - SM_ELEMENT_D(D, i, j)));
      *dmax = fmax(*dmax, fabs(SM_ELEMENT_D(D, i, j)));
    }
  free(full);
  return d;
}

static long int Mapped(const Run *r) { return ((LGNMem)r->mem)->ls.sp->nmapped; }

static long int Get(void *mem, int (*fn)(void *, long int *))
{
  long int x = -1;
  fn(mem, &x);
  return x;
}

static void Check(const Config *c, SUNContext ctx)
{
  RigidSystem *sys = chain_create(NBODY, c->formulation, ctx);
  Run fast, build, dense;
  sunrealtype t;
  long int nje0, nje1, map0, map1, bmap0, bmap1, bnje0, bnje1;
  long int npat_grow = -1, nnz_grow = -1;
  int step, flag, fast_steps = 0, fast_built = 0, build_skipped = 0;
  int same_A = 1, same_state = 1;
  double dA = 0.0, Amax = 0.0, d, amax, dq;

  flag = RunCreate(&fast, sys, c, 0, 0, ctx);
  flag |= RunCreate(&build, sys, c, 0, 1, ctx);
  flag |= RunCreate(&dense, sys, c, 1, 0, ctx);
  CHECK(flag == 0, "%s: set-up", c->name);
  for (step = 1; step <= NSTEP && flag == 0; step++) {
    if (step == GROW_M) {
      fast.md.grow_M = build.md.grow_M = dense.md.grow_M = 1;
      npat_grow = Get(fast.mem, LGNGetNumSparsityAnalyses);
      nnz_grow  = Get(fast.mem, LGNGetIterationMatrixNnz);
    }
    if ((step == GROW_C || step == MOVE_C) && c->tangents)
      fast.md.grow_C = build.md.grow_C = dense.md.grow_C = step == GROW_C ? 1 : 2;
    nje0  = Get(fast.mem, LGNGetNumJacEvals);
    bnje0 = Get(build.mem, LGNGetNumJacEvals);
    map0  = step > 1 ? Mapped(&fast) : 0;
    bmap0 = step > 1 ? Mapped(&build) : 0;
    flag = LGNSolve(fast.mem, 1.0, &t, fast.q, fast.v, LGN_ONE_STEP);
    flag |= LGNSolve(build.mem, 1.0, &t, build.q, build.v, LGN_ONE_STEP);
    flag |= LGNSolve(dense.mem, 1.0, &t, dense.q, dense.v, LGN_ONE_STEP);
    CHECK(flag == 0, "%s: step %d", c->name, step);
    if (flag != 0) break;
    nje1  = Get(fast.mem, LGNGetNumJacEvals);
    bnje1 = Get(build.mem, LGNGetNumJacEvals);
    map1  = Mapped(&fast);
    bmap1 = Mapped(&build);
    /* (a) bit for bit */
    if (!SameSparse(fast.A, build.A)) {
      same_A = 0;
      printf("  %s: step %d: A differs between the fill and build paths\n", c->name, step);
    }
    if (!SameVector(fast.q, build.q) || !SameVector(fast.v, build.v)) same_state = 0;
    if (step > 1 && nje1 > nje0) {
      if (map1 == map0) fast_steps++;
      else fast_built++;
    }
    /* every assembly of the build run built its maps (5: M, C, K, B, B^T) */
    if (step > 1 && bmap1 - bmap0 < 5 * (bnje1 - bnje0)) build_skipped++;
    /* against the dense matrix (full Newton: both hold the last iteration's) */
    if (c->newton == LGN_NEWTON_FULL) {
      d    = DiffDense(fast.A, dense.Acopy, &amax);
      dA   = fmax(dA, d);
      Amax = fmax(Amax, amax);
    }
  }
  CHECK(same_A, "%s: (a) the fill path's A = the build path's A, bit for bit, at every step", c->name);
  CHECK(same_state, "%s: (a) and the same states", c->name);
  CHECK(fast_steps >= (c->newton == LGN_NEWTON_FULL ? NSTEP / 2 : 3) && fast_built <= 4,
        "%s: (a) steps assembled by the fill path alone: %d, with a map built: %d",
        c->name, fast_steps, fast_built);
  CHECK(build_skipped == 0, "%s: (a) the build run built its maps at every assembly (%d steps not)",
        c->name, build_skipped);
  /* (b) the patterns grew */
  CHECK(Get(fast.mem, LGNGetNumSparsityAnalyses) > npat_grow &&
            Get(fast.mem, LGNGetIterationMatrixNnz) > nnz_grow,
        "%s: (b) A's pattern extended after the model's grew: analyses %ld -> %ld, nnz %ld -> %ld",
        c->name, npat_grow, Get(fast.mem, LGNGetNumSparsityAnalyses), nnz_grow,
        Get(fast.mem, LGNGetIterationMatrixNnz));
  CHECK(Get(fast.mem, LGNGetNumSparsityAnalyses) == Get(build.mem, LGNGetNumSparsityAnalyses),
        "%s: (b) the same analyses in both sparse runs", c->name);
  /* M(3, 15) and M(15, 3), in every column of their rotation (or SE(3)) block */
  CHECK(HasEntry(fast.A, 3, 15) && HasEntry(fast.A, 3, 17) && HasEntry(fast.A, 15, 3) &&
            HasEntry(fast.A, 15, 5) && HasEntry(fast.A, 9, 3),
        "%s: (b) the new mass entries are in A, closed over T's blocks", c->name);
  if (c->tangents)
    CHECK(HasEntry(fast.A, 12, 3) && HasEntry(fast.A, 12, 5) && HasEntry(fast.A, 14, 3) &&
              HasEntry(fast.A, 14, 5),
          "%s: (b) the new damping entries are in A, closed over T's blocks", c->name);
  if (c->newton == LGN_NEWTON_FULL)
    CHECK(dA <= 1e-9 * Amax, "%s: sparse A = dense A: max |dA| = %.3e (max |A| = %.3e)",
          c->name, dA, Amax);
  /* (d) the copy of KLU's factors (opted in): by rows (CSC) Lignum
   * refactors into it, and each new pattern made KLU factor (and analyse)
   * again, counted as such, and its factors be copied anew; by columns
   * (CSR) KLU refactors and the copy is never refactored into */
  {
    long int npivot = -1, npattern = -1, nnocopy = -1;
    const long int ncopy = Get(fast.mem, LGNGetNumKLUFactorCopies);
    const long int nref  = Get(fast.mem, LGNGetNumOwnKLURefactors);
    const long int nan   = Get(fast.mem, LGNGetNumSparsityAnalyses);
    LGNGetNumKLUFallbacks(fast.mem, &npivot, &npattern, &nnocopy);
    if (c->sparsetype == CSC_MAT)
      CHECK(npattern == nan - 1 && ncopy == 1 + npattern + npivot && nref > 0 &&
                nnocopy == 0,
            "%s: (d) the copy: %ld new patterns handed to KLU (%ld analyses), "
            "%ld copies, %ld refactorisations, %ld pivot and %ld no-copy fallbacks",
            c->name, npattern, nan, ncopy, nref, npivot, nnocopy);
    else
      CHECK(npattern == 0 && npivot == 0 && nref == 0 && nnocopy == 0 &&
                (c->newton == LGN_NEWTON_FULL ? ncopy == 0 : ncopy >= 1),
            "%s: (d) the copy by columns: %ld copies, no refactorisation (%ld), "
            "no fallback (%ld, %ld, %ld)", c->name, ncopy, nref, npivot, npattern,
            nnocopy);
  }
  dq = 0.0;
  for (step = 0; step < 7 * NBODY; step++)
    dq = fmax(dq, fabs(N_VGetArrayPointer(fast.q)[step] - N_VGetArrayPointer(dense.q)[step]));
  CHECK(dq <= 1e-9, "%s: sparse = dense: |dq| = %.3e", c->name, dq);
  printf("%s: %d steps by the fill path alone, %d with maps built; analyses %ld, nnz %ld; "
         "|A - A_dense| = %.1e, |q - q_dense| = %.1e\n",
         c->name, fast_steps, fast_built, Get(fast.mem, LGNGetNumSparsityAnalyses),
         Get(fast.mem, LGNGetIterationMatrixNnz), dA, dq);
  RunFree(&fast);
  RunFree(&build);
  RunFree(&dense);
  rigid_free(&sys);
}

int main(void)
{
  const Config configs[] = {
      {"R3xSO3 CSC full index 3 analytic", RB_R3XSO3, CSC_MAT, LGN_NEWTON_FULL,
       LGN_CONSTR_INDEX3, LGN_KINEMATICS_SIMPLIFIED, 1},
      {"R3xSO3 CSR full index 3 analytic", RB_R3XSO3, CSR_MAT, LGN_NEWTON_FULL,
       LGN_CONSTR_INDEX3, LGN_KINEMATICS_SIMPLIFIED, 1},
      {"SE3 CSC full index 2 exact DQ", RB_SE3, CSC_MAT, LGN_NEWTON_FULL,
       LGN_CONSTR_INDEX2, LGN_KINEMATICS_EXACT, 0},
      {"SE3 CSR full index 2 exact C", RB_SE3, CSR_MAT, LGN_NEWTON_FULL,
       LGN_CONSTR_INDEX2, LGN_KINEMATICS_EXACT, 1},
      {"R3xSO3 CSR modified index 3 analytic", RB_R3XSO3, CSR_MAT, LGN_NEWTON_MODIFIED,
       LGN_CONSTR_INDEX3, LGN_KINEMATICS_SIMPLIFIED, 1},
      {"SE3 CSC modified index 3 C", RB_SE3, CSC_MAT, LGN_NEWTON_MODIFIED,
       LGN_CONSTR_INDEX3, LGN_KINEMATICS_SIMPLIFIED, 1},
  };
  SUNContext ctx;
  size_t i;
  setvbuf(stdout, NULL, _IONBF, 0); /* a stale map may crash: keep what was printed */
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  for (i = 0; i < sizeof configs / sizeof configs[0]; i++) Check(&configs[i], ctx);
  SUNContext_Free(&ctx);
  return test_summary("test_sparse_assembly");
}
