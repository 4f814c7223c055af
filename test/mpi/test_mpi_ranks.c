/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * A run across MPI ranks (run on 1, 2 and 4 ranks by CTest): every rank
 * holds its part of a model of heavy tops (rank r has 1 + r of them, each an
 * R^3 x SO(3) body on a spherical joint, spun at its own rate), in MPIPlusX
 * or N_Vector_Parallel state vectors; error control, outputs between steps
 * and an event whose root function is the sum of the ranks' parts. Checked
 * against the same model of all tops on one process (serial vectors):
 *
 *   (a) the same trajectory: every rank's tops at every output equal the
 *       one-process run's to round-off (the reductions only add in another
 *       order), the same number of steps and the same event time;
 *   (b) the same step decisions on every rank: steps, step failures,
 *       Newton iterations and the last step size equal on all ranks;
 *   (c) a force callback failing for good on the last rank: LGNSolve
 *       returns LGN_FORCE_FAIL on every rank, at the same time, every rank
 *       gets a message, and nothing hangs (CTest's timeout);
 *   (d) a recoverable failure on the last rank: every rank retries the same
 *       step with a smaller one and goes on; the result is as accurate as
 *       the one-process run's (errors against a run at tolerance 1e-10);
 *       and one that lasts until h collapses (LGN_STEP_TOO_SMALL on every
 *       rank at the same t): once the callback works again the next
 *       LGNSolve goes on, as accurate (generalized-alpha at index 2);
 *   (e) faults and misuse of one rank end alike on every rank: a NaN in its
 *       q0 (LGN_ILL_INPUT from every LGNInit), another rtol, another tout,
 *       no LGNRootInit or vector tolerances on one rank only (LGN_ILL_INPUT
 *       from every LGNSolve), Phi_t set on one rank only and
 *       a preconditioner failing once inside a Krylov solve on one rank (both
 *       run through, with the same steps everywhere); and q0, v0 freed after
 *       LGNInit (the same run);
 *   (f) restart files, one per rank (LGNWriteRestart after an output,
 *       LGNReadRestart into a new integrator): the continued run equals the
 *       uninterrupted one bit for bit (dense LU per rank, SPGMR).
 *
 * Generalized-alpha (modified kinematics) with full Newton and a dense LU
 * of each rank's block, BDF (orders up to 5) with modified Newton, and
 * (with KLU) generalized-alpha with SPGMR over vectors of the ranks and
 * the block preconditioner, one block per rank. The ranks hold different
 * numbers of bodies.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mpi.h>

#include <lignum/lignum.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_mpiplusx.h>
#include <nvector/nvector_parallel.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>

#define NOUT 5
#define TOUT 0.1
#define NQ_TOP 7
#define NV_TOP 6

enum { VEC_SERIAL, VEC_MPIPLUSX, VEC_PARALLEL };
/* what a rank does (Integrate's "inject"): nothing, a fault, a misuse */
enum {
  FAIL_NONE, FAIL_FATAL, FAIL_RECOVERABLE, /* the force callback fails     */
  FAIL_NAN_Q0,    /* a NaN in this rank's q0                               */
  FAIL_SETTING,   /* another rtol on this rank                             */
  FREE_Q0,        /* q0 and v0 freed after LGNInit (every rank: no fault)  */
  PHIT_HERE,      /* Phi_t (zero) set on this rank only                    */
  PSOLVE_REC,     /* the preconditioner fails once, recoverably            */
  FAIL_TOUT,      /* another tout on this rank                             */
  FAIL_NOROOT,    /* no LGNRootInit on this rank                           */
  FAIL_SVTOL,     /* LGNSVtolerances on this rank only                     */
  FAIL_BADTOUT,   /* a tout behind the current time on this rank           */
  FAIL_COLLAPSE   /* recoverable from t = 0.15 on until h collapses (index 2),
                     then healthy: the next LGNSolve goes on                 */
};

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
  int inject;         /* FAIL_*: on this rank's force callback      */
  int injected;       /* the recoverable failure was returned once  */
  int rank_part;      /* this rank owns top 0: its part of the event */
} Model;

typedef struct {
  int flag;
  long int nst, nfails, nni;
  sunrealtype hlast, troot, tret;
  sunrealtype tcollapse; /* FAIL_COLLAPSE: where LGN_STEP_TOO_SMALL came (-1: none) */
  int nmsg;           /* messages the error handler received         */
  sunrealtype *q;     /* the tops' q at each output (NOUT x nq)       */
  sunrealtype *v;
} Run;

static int nfail_checks = 0;
static int collapse_run = 0; /* FAIL_COLLAPSE on some rank: the settings of
                                every rank's run (they must agree) */

static void Check(int ok, int rank, const char *what)
{
  if (!ok) {
    nfail_checks++;
    printf("  rank %d FAILED: %s\n", rank, what);
  }
}

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Model *)ud)->bodies);
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  Model *md = (Model *)ud;
  if (md->inject == FAIL_FATAL && t > 0.2) return -1;
  if (md->inject == FAIL_RECOVERABLE && t > 0.15 && !md->injected) {
    md->injected = 1;
    return 1;
  }
  if (md->inject == FAIL_COLLAPSE && t > 0.15 && !md->injected) return 1; /* until healed */
  return LGNBodies_ForceFn(t, q, v, g, md->bodies);
}

static int ZeroPhit(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  (void)t;
  (void)q;
  (void)ud;
  N_VConst(0.0, phit);
  return 0;
}

/* no preconditioning (z = r), but it can fail once */
static int Psolve(sunrealtype t, N_Vector q, N_Vector v, N_Vector r, N_Vector z,
                  sunrealtype cM, sunrealtype cC, sunrealtype cK, sunrealtype delta, void *ud)
{
  Model *md = (Model *)ud;
  (void)q;
  (void)v;
  (void)cM;
  (void)cC;
  (void)cK;
  (void)delta;
  if (md->inject == PSOLVE_REC && t > 0.15 && !md->injected) {
    md->injected = 1;
    return 1;
  }
  N_VScale(1.0, r, z);
  return 0;
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->joints, t, q, phi);
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->joints, t, q, B);
}

/* The event: |x| of top 0's centre reaches 0.05 (its precession), from the
 * rank that holds top 0; the other ranks' part is zero. */
static int Event(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *g, void *ud)
{
  const sunrealtype *qd = N_VGetArrayPointer(q);
  (void)t;
  (void)v;
  g[0] = ((Model *)ud)->rank_part ? qd[0] * qd[0] - 0.0025 : 0.0;
  return 0;
}

static void CountMessages(int code, const char *module, const char *func, const char *msg,
                          void *data)
{
  (void)code;
  (void)module;
  (void)func;
  (void)msg;
  (*(int *)data)++;
}

static N_Vector NewVector(int kind, MPI_Comm comm, sunindextype n, SUNContext ctx)
{
  if (kind == VEC_SERIAL) return N_VNew_Serial(n, ctx);
  if (kind == VEC_PARALLEL) {
    long long local = n, global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_LONG_LONG, MPI_SUM, comm);
    return N_VNew_Parallel(comm, n, (sunindextype)global, ctx);
  }
  return N_VMake_MPIPlusX(comm, N_VNew_Serial(n, ctx), ctx);
}

static void FreeVector(int kind, N_Vector x)
{
  if (kind == VEC_MPIPLUSX) N_VDestroy(N_VGetLocalVector_MPIPlusX(x));
  N_VDestroy(x);
}

/* (f): the output after which Integrate restarts from a file (0: none) */
static int restart_after = 0;

typedef struct {
  void *mem;
  N_Vector tmpl;
  SUNMatrix A;
  SUNLinearSolver LS;
} Solver;

/* The integrator of Integrate: model, tolerances, method, roots, linear
 * solver (made again for a restart, (f)). */
static int MakeIntegrator(int method, int kind, MPI_Comm comm, int inject, sunrealtype tol,
                          Model *md, LGNGroup G, N_Vector q, N_Vector v, sunindextype m,
                          SUNContext ctx, int *nmsg, sunbooleantype *freed, Solver *out)
{
  const sunindextype nv = G->nv;
  void *mem = LGNCreate(ctx);
  N_Vector tmpl;
  SUNMatrix A;
  SUNLinearSolver LS;
  int flag = 0;
  *nmsg = 0;
  if (!flag) flag = LGNSetErrHandlerFn(mem, CountMessages, nmsg);
  if (!flag) flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, inject == FAIL_SETTING ? 2.0 * tol : tol, tol);
  if (!flag && inject == PHIT_HERE) flag = LGNSetConstraintTimeFn(mem, ZeroPhit);
  if (method != 1) {
    if (!flag) flag = LGNSetKinematics(mem, LGN_KINEMATICS_EXACT);
  } else {
    if (!flag) flag = LGNSetBDF(mem, 5);
    if (!flag) flag = LGNSetNewtonMode(mem, LGN_NEWTON_MODIFIED);
  }
  if (!flag && collapse_run) {
    /* every rank: h collapses within one call; index 2: at index 3 the steps of 1e-17
     * on the way would spoil v (user guide, 8.2) */
    flag = LGNSetMaxConvFails(mem, 200);
    if (!flag) flag = LGNSetConstraintIndex(mem, LGN_CONSTR_INDEX2);
  }
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag && inject == FREE_Q0) {
    /* the integrator keeps no reference to q0, v0 (nor to their
     * communicator): freed, and the outputs go to new vectors */
    *freed = SUNTRUE;
  }
  if (!flag && inject != FAIL_NOROOT) flag = LGNRootInit(mem, 1, Event);
  {
    /* made on every rank: cloning an MPI vector is collective */
    N_Vector atol = N_VClone(v);
    N_VConst(tol, atol);
    if (!flag && inject == FAIL_SVTOL)
      flag = LGNSVtolerances(mem, tol, atol); /* a local call: no hang here */
    N_VDestroy(atol);
  }
  if (method >= 2) {
    /* Krylov over vectors of the ranks (its norms are collective); 3: a
     * user preconditioner (none, really) that may fail */
    tmpl = NewVector(kind, comm, nv + m, ctx);
    A    = NULL;
    LS   = SUNLinSol_SPGMR(tmpl, SUN_PREC_LEFT, method == 2 ? 10 : 40, ctx);
    if (!flag) flag = LGNSetLinearSolver(mem, LS, NULL);
    if (!flag && method == 2) flag = LGNSetBlockPreconditioner(mem, 1, NULL);
    if (!flag && method == 3) flag = LGNSetPreconditioner(mem, NULL, Psolve);
  } else {
    /* each rank solves its own block: the tops do not couple */
    tmpl = N_VNew_Serial(nv + m, ctx);
    A    = SUNDenseMatrix(nv + m, nv + m, ctx);
    LS   = LGNLinSol_Dense(tmpl, A, ctx);
    if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  }

  out->mem  = mem;
  out->tmpl = tmpl;
  out->A    = A;
  out->LS   = LS;
  return flag;
}

static void FreeIntegrator(int method, int kind, Solver *s)
{
  LGNFree(&s->mem);
  SUNLinSolFree(s->LS);
  if (s->A != NULL) SUNMatDestroy(s->A);
  if (method >= 2)
    FreeVector(kind, s->tmpl);
  else
    N_VDestroy(s->tmpl);
}

/* Tops u0 ... u0 + K - 1 of the model, in vectors of the given kind on
 * comm; method 0: mod. generalized-alpha, full Newton; 1: BDF 5, modified;
 * 2: as 0 with SPGMR and the block preconditioner (one block per rank).
 * Generalized-alpha runs at 100 tol_in: with the error per unit step its
 * steps grow like tol^(-1/2) (12k per top at 1e-7, and the run on two
 * ranks took over 240 s on a loaded machine); the comparisons between
 * ranks do not depend on the tolerance. */
static void Integrate(int method, int kind, MPI_Comm comm, int u0, int K, int inject,
                      sunrealtype tol_in, SUNContext ctx, Run *run)
{
  const sunrealtype tol = method == 1 ? tol_in : SUN_RCONST(100.0) * tol_in;
  const sunrealtype J[3]       = {0.234375, 0.46875, 0.234375};
  const sunrealtype gravity[3] = {0.0, 0.0, -9.81};
  const sunrealtype origin[3]  = {0.0, 0.0, 0.0};
  const sunrealtype tip[3]     = {0.0, -1.0, 0.0};
  LGNGroup body = LGNGroup_R3xSO3(), G;
  LGNGroup *factors = (LGNGroup *)malloc((size_t)K * sizeof(LGNGroup));
  Model md = {NULL, NULL, inject, 0, u0 == 0};
  N_Vector q, v;
  Solver solver;
  void *mem = NULL;
  sunindextype nq, nv, m;
  sunrealtype *qd, *vd, t = 0.0;
  int k, flag = 0, rootsfound = 0;

  for (k = 0; k < K; k++) factors[k] = body;
  G  = LGNGroup_Product(K, factors);
  nq = G->nq;
  nv = G->nv;
  md.bodies = LGNBodies_Create(G);
  md.joints = LGNJoints_Create(G);
  for (k = 0; k < K && !flag; k++) {
    flag = LGNBodies_SetPrincipalInertia(md.bodies, k, 15.0, J);
    if (!flag) flag = LGNJoints_AddSpherical(md.joints, LGN_GROUND, origin, k, tip);
  }
  if (!flag) flag = LGNBodies_SetGravity(md.bodies, gravity);
  m = LGNJoints_NumConstraints(md.joints);

  q  = NewVector(kind, comm, nq, ctx);
  v  = NewVector(kind, comm, nv, ctx);
  qd = N_VGetArrayPointer(q);
  vd = N_VGetArrayPointer(v);
  LGNGroup_Identity(G, qd);
  N_VConst(0.0, v);
  for (k = 0; k < K; k++) {
    const int u = u0 + k; /* the top's number in the whole model */
    qd[NQ_TOP * k + 1] = 1.0;                       /* centre at (0, 1, 0) */
    vd[NV_TOP * k + 4] = 150.0 - 5.0 * u;           /* spin (body frame)   */
    vd[NV_TOP * k + 5] = -4.61538 + 0.3 * u;
    vd[NV_TOP * k + 0] = -vd[NV_TOP * k + 5];       /* u = Omega x X: tip fixed */
  }
  if (inject == FAIL_NAN_Q0) qd[3] = NAN;

  {
    sunbooleantype freed = SUNFALSE;
    if (!flag)
      flag = MakeIntegrator(method, kind, comm, inject, tol, &md, G, q, v, m, ctx, &run->nmsg,
                            &freed, &solver);
    else
      memset(&solver, 0, sizeof solver);
    if (freed) {
      /* the integrator keeps no reference to q0, v0 (nor to their
       * communicator): freed, and the outputs go to new vectors */
      N_Vector q2 = NewVector(kind, comm, nq, ctx), v2 = NewVector(kind, comm, nv, ctx);
      FreeVector(kind, q);
      FreeVector(kind, v);
      q  = q2;
      v  = v2;
      qd = N_VGetArrayPointer(q);
      vd = N_VGetArrayPointer(v);
    }
    mem = solver.mem;
  }
  run->troot     = -1.0;
  run->tcollapse = -1.0;
  for (k = 1; k <= NOUT && !flag;) {
    flag = LGNSolve(mem,
                    inject == FAIL_BADTOUT ? -1.0
                                           : k * TOUT + (inject == FAIL_TOUT ? 0.01 : 0.0),
                    &t, q, v, LGN_NORMAL);
    if (flag == LGN_ROOT_RETURN) {
      if (!rootsfound++) run->troot = t;
      flag = 0;
      continue;
    }
    if (flag == LGN_STEP_TOO_SMALL && run->tcollapse < 0.0) {
      /* (every rank: the failure is agreed) the callback works again: on */
      run->tcollapse = t;
      md.injected    = 1;
      flag           = 0;
      continue;
    }
    if (flag) break;
    memcpy(run->q + (size_t)(k - 1) * (size_t)nq, qd, (size_t)nq * sizeof(sunrealtype));
    memcpy(run->v + (size_t)(k - 1) * (size_t)nv, vd, (size_t)nv * sizeof(sunrealtype));
    if (k == restart_after) {
      /* (f) a restart file per rank, read into a new integrator */
      char name[64];
      sunbooleantype freed = SUNFALSE;
      int rank;
      MPI_Comm_rank(comm, &rank);
      snprintf(name, sizeof name, "test_mpi_ranks.%d.lgr", rank);
      flag = LGNWriteRestart(mem, name);
      FreeIntegrator(method, kind, &solver);
      if (!flag)
        flag = MakeIntegrator(method, kind, comm, inject, tol, &md, G, q, v, m, ctx, &run->nmsg,
                              &freed, &solver);
      mem = solver.mem;
      if (!flag) flag = LGNReadRestart(mem, name);
      remove(name);
      if (flag) break;
    }
    k++;
  }
  run->flag = flag;
  run->tret = t;
  LGNGetNumSteps(mem, &run->nst);
  LGNGetNumStepFails(mem, &run->nfails);
  LGNGetNumNewtonIters(mem, &run->nni);
  LGNGetLastStep(mem, &run->hlast);

  FreeIntegrator(method, kind, &solver);
  FreeVector(kind, q);
  FreeVector(kind, v);
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  free(factors);
}

/* min == max over the ranks */
static int SameOnAllRanks(double x, MPI_Comm comm)
{
  double lo, hi;
  MPI_Allreduce(&x, &lo, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(&x, &hi, 1, MPI_DOUBLE, MPI_MAX, comm);
  return lo == hi;
}

static Run NewRun(int K)
{
  Run r;
  memset(&r, 0, sizeof(r));
  r.q = (sunrealtype *)calloc((size_t)NOUT * NQ_TOP * (size_t)K, sizeof(sunrealtype));
  r.v = (sunrealtype *)calloc((size_t)NOUT * NV_TOP * (size_t)K, sizeof(sunrealtype));
  return r;
}

static void FreeRun(Run *r)
{
  free(r->q);
  free(r->v);
}

/* max over the outputs and this rank's tops of |x_ranks - x_one| */
static sunrealtype MaxDiff(const Run *par, const Run *one, int u0, int K, int N)
{
  sunrealtype d = 0.0;
  int k, i;
  for (k = 0; k < NOUT; k++) {
    for (i = 0; i < NQ_TOP * K; i++)
      d = fmax(d, fabs(par->q[k * NQ_TOP * K + i] - one->q[k * NQ_TOP * N + NQ_TOP * u0 + i]));
    for (i = 0; i < NV_TOP * K; i++)
      d = fmax(d, fabs(par->v[k * NV_TOP * K + i] - one->v[k * NV_TOP * N + NV_TOP * u0 + i]) /
                      150.0);
  }
  return d;
}

int main(int argc, char **argv)
{
  MPI_Comm comm = MPI_COMM_WORLD;
  SUNContext ctx_par = NULL, ctx_one = NULL;
  int rank, size, N, K, u0, method, kind, fails = 0;
  Run exact;
  static const char *mname[3] = {"mod. LGGalpha, full Newton", "BDF5, modified Newton",
                                 "mod. LGGalpha, SPGMR+block"};
#ifdef LGN_HAVE_KLU
  const int nmethods = 3;
#else
  const int nmethods = 2; /* the block preconditioner needs KLU */
#endif
  static const char *kname[3] = {"serial", "MPIPlusX", "Parallel"};

  MPI_Init(&argc, &argv);
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  N  = size * (size + 1) / 2; /* rank r holds 1 + r tops */
  K  = 1 + rank;
  u0 = rank * (rank + 1) / 2;
  SUNContext_Create(&comm, &ctx_par);
  SUNContext_Create(NULL, &ctx_one);
  if (rank == 0) printf("test_mpi_ranks: %d ranks, %d heavy tops (rank r holds 1 + r)\n", size, N);

  /* the accurate solution, for the errors of (d) */
  exact = NewRun(N);
  Integrate(1, VEC_SERIAL, MPI_COMM_SELF, 0, N, FAIL_NONE, 1e-10, ctx_one, &exact);
  Check(exact.flag == 0, rank, "the accurate one-process run succeeds");

  for (method = 0; method < nmethods; method++) {
    Run one = NewRun(N), par;
    char what[200];
    /* the reference: all tops on one process */
    Integrate(method, VEC_SERIAL, MPI_COMM_SELF, 0, N, FAIL_NONE, 1e-7, ctx_one, &one);
    Check(one.flag == 0, rank, "the one-process run succeeds");
    for (kind = VEC_MPIPLUSX; kind <= VEC_PARALLEL; kind++) {
      sunrealtype d, dmax;
      par = NewRun(K);
      Integrate(method, kind, comm, u0, K, FAIL_NONE, 1e-7, ctx_par, &par);
      d = MaxDiff(&par, &one, u0, K, N);
      MPI_Allreduce(&d, &dmax, 1, MPI_DOUBLE, MPI_MAX, comm);
      if (rank == 0)
        printf("  %-27s %-8s: steps %ld (one process %ld), event t = %.10f (%.10f), "
               "max difference %.1e\n",
               mname[method], kname[kind], par.nst, one.nst, (double)par.troot,
               (double)one.troot, (double)dmax);
      snprintf(what, sizeof what, "(a) %s %s: success", mname[method], kname[kind]);
      Check(par.flag == 0, rank, what);
      snprintf(what, sizeof what, "(a) %s %s: same trajectory as one process (%.1e)",
               mname[method], kname[kind], (double)d);
      Check(d <= 1e-10, rank, what);
      snprintf(what, sizeof what, "(a) %s %s: same steps and event", mname[method],
               kname[kind]);
      Check(par.nst == one.nst && one.troot > 0.0 &&
                fabs(par.troot - one.troot) <= 1e-10, rank, what);
      snprintf(what, sizeof what, "(b) %s %s: same decisions on every rank", mname[method],
               kname[kind]);
      Check(SameOnAllRanks((double)par.nst, comm) && SameOnAllRanks((double)par.nfails, comm) &&
                SameOnAllRanks((double)par.nni, comm) && SameOnAllRanks(par.hlast, comm),
            rank, what);
      FreeRun(&par);
    }

    /* (c) a fatal failure on the last rank */
    par = NewRun(K);
    Integrate(method, VEC_MPIPLUSX, comm, u0, K, rank == size - 1 ? FAIL_FATAL : FAIL_NONE,
              1e-7, ctx_par, &par);
    if (rank == 0) printf("  %-27s fatal force failure on rank %d: flag %s at t = %.6f\n",
                          mname[method], size - 1, LGNGetReturnFlagName(par.flag),
                          (double)par.tret);
    snprintf(what, sizeof what, "(c) %s: LGN_FORCE_FAIL on every rank (%s)", mname[method],
             LGNGetReturnFlagName(par.flag));
    Check(par.flag == LGN_FORCE_FAIL, rank, what);
    snprintf(what, sizeof what, "(c) %s: the same time and steps on every rank, a message",
             mname[method]);
    Check(SameOnAllRanks(par.tret, comm) && SameOnAllRanks((double)par.nst, comm) &&
              par.nmsg >= 1 && par.tret >= 0.1, rank, what);
    FreeRun(&par);

    /* (d) a recoverable failure on the last rank */
    par = NewRun(K);
    Integrate(method, VEC_MPIPLUSX, comm, u0, K,
              rank == size - 1 ? FAIL_RECOVERABLE : FAIL_NONE, 1e-7, ctx_par, &par);
    {
      sunrealtype e[2], emax[2];
      e[0] = MaxDiff(&par, &exact, u0, K, N); /* its error */
      e[1] = MaxDiff(&one, &exact, 0, N, N);  /* the one-process run's */
      MPI_Allreduce(e, emax, 2, MPI_DOUBLE, MPI_MAX, comm);
      if (rank == 0)
        printf("  %-27s recoverable failure on rank %d: flag %s, %ld steps, %ld failed, "
               "error %.1e (one process %.1e)\n",
               mname[method], size - 1, LGNGetReturnFlagName(par.flag), par.nst, par.nfails,
               (double)emax[0], (double)emax[1]);
      snprintf(what, sizeof what, "(d) %s: retried and finished on every rank", mname[method]);
      Check(par.flag == 0 && par.nfails >= 1 && SameOnAllRanks((double)par.nst, comm) &&
                SameOnAllRanks((double)par.nfails, comm), rank, what);
      snprintf(what, sizeof what, "(d) %s: as accurate as one process (%.1e against %.1e)",
               mname[method], (double)emax[0], (double)emax[1]);
      Check(emax[0] <= 3.0 * emax[1], rank, what);
    }
    FreeRun(&par);

    /* (d) h collapsed by a recoverable failure on the last rank from t = 0.15
     * on (LGN_STEP_TOO_SMALL on every rank); once the callback works again
     * the next LGNSolve goes on, to the accuracy of the tolerances */
    if (method == 0) {
      sunrealtype e[2], emax[2];
      par          = NewRun(K);
      collapse_run = 1;
      Integrate(method, VEC_MPIPLUSX, comm, u0, K,
                rank == size - 1 ? FAIL_COLLAPSE : FAIL_NONE, 1e-7, ctx_par, &par);
      collapse_run = 0;
      e[0] = MaxDiff(&par, &exact, u0, K, N);
      e[1] = MaxDiff(&one, &exact, 0, N, N);
      MPI_Allreduce(e, emax, 2, MPI_DOUBLE, MPI_MAX, comm);
      if (rank == 0)
        printf("  %-27s collapse on rank %d at t = %.17g, then healthy: flag %s, error "
               "%.1e (one process %.1e)\n", mname[method], size - 1, (double)par.tcollapse,
               LGNGetReturnFlagName(par.flag), (double)emax[0], (double)emax[1]);
      snprintf(what, sizeof what, "(d) %s: LGN_STEP_TOO_SMALL near t = 0.15 on every rank, "
               "then on to the end", mname[method]);
      Check(par.flag == 0 && par.tcollapse > 0.1499 && par.tcollapse <= 0.15 &&
                SameOnAllRanks(par.tcollapse, comm) && SameOnAllRanks((double)par.nst, comm),
            rank, what);
      snprintf(what, sizeof what, "(d) %s: after the collapse as accurate as the tolerance "
               "(%.1e against %.1e)", mname[method], (double)emax[0], (double)emax[1]);
      Check(emax[0] <= 10.0 * emax[1], rank, what);
      FreeRun(&par);
    }
    FreeRun(&one);
  }

  /* (e) faults and misuse of one rank end alike on every rank */
  {
    const int last = size - 1;
    Run one = NewRun(N), par;
    char what[200];
    sunrealtype d, dmax;
    Integrate(0, VEC_SERIAL, MPI_COMM_SELF, 0, N, FAIL_NONE, 1e-7, ctx_one, &one);

    par = NewRun(K);
    Integrate(0, VEC_MPIPLUSX, comm, u0, K, rank == last ? FAIL_NAN_Q0 : FAIL_NONE, 1e-7,
              ctx_par, &par);
    snprintf(what, sizeof what, "(e) a NaN in rank %d's q0: LGN_ILL_INPUT everywhere (%s)",
             last, LGNGetReturnFlagName(par.flag));
    Check(par.flag == LGN_ILL_INPUT && par.nmsg >= 1, rank, what);
    FreeRun(&par);

    par = NewRun(K);
    Integrate(0, VEC_MPIPLUSX, comm, u0, K, rank == last ? FAIL_SETTING : FAIL_NONE, 1e-7,
              ctx_par, &par);
    snprintf(what, sizeof what, "(e) another rtol on rank %d: LGN_ILL_INPUT everywhere (%s)",
             last, LGNGetReturnFlagName(par.flag));
    Check(size == 1 ? par.flag == 0 : par.flag == LGN_ILL_INPUT && par.nmsg >= 1, rank, what);
    FreeRun(&par);

    {
      /* misuse that LGNSolve's check of the settings refuses on every rank
       * (instead of a hang in a collective some ranks never reach) */
      static const int misuse[4] = {FAIL_TOUT, FAIL_NOROOT, FAIL_SVTOL, FAIL_BADTOUT};
      static const char *mname3[4] = {"another tout", "no LGNRootInit",
                                      "LGNSVtolerances only", "a tout behind t"};
      int j;
      for (j = 0; j < 4; j++) {
        const int expected = misuse[j] == FAIL_BADTOUT ? LGN_BAD_TOUT : LGN_ILL_INPUT;
        par = NewRun(K);
        Integrate(0, VEC_MPIPLUSX, comm, u0, K, rank == last ? misuse[j] : FAIL_NONE, 1e-7,
                  ctx_par, &par);
        snprintf(what, sizeof what, "(e) %s on rank %d: %s everywhere (%s)", mname3[j],
                 last, LGNGetReturnFlagName(expected), LGNGetReturnFlagName(par.flag));
        Check((size == 1 && misuse[j] != FAIL_BADTOUT) ||
                  (par.flag == expected && par.nmsg >= 1 && SameOnAllRanks(par.tret, comm)),
              rank, what);
        FreeRun(&par);
      }
    }

    par = NewRun(K);
    Integrate(0, VEC_MPIPLUSX, comm, u0, K, FREE_Q0, 1e-7, ctx_par, &par);
    d = MaxDiff(&par, &one, u0, K, N);
    MPI_Allreduce(&d, &dmax, 1, MPI_DOUBLE, MPI_MAX, comm);
    snprintf(what, sizeof what, "(e) q0, v0 freed after LGNInit: the same run (%.1e)",
             (double)dmax);
    Check(par.flag == 0 && dmax <= 1e-10 && par.nst == one.nst, rank, what);
    FreeRun(&par);

    par = NewRun(K);
    Integrate(0, VEC_MPIPLUSX, comm, u0, K, rank == 0 ? PHIT_HERE : FAIL_NONE, 1e-7, ctx_par,
              &par);
    snprintf(what, sizeof what, "(e) Phi_t on rank 0 only: success, the same steps (%s)",
             LGNGetReturnFlagName(par.flag));
    Check(par.flag == 0 && SameOnAllRanks((double)par.nst, comm) &&
              SameOnAllRanks(par.hlast, comm), rank, what);
    FreeRun(&par);

    /* (f) restart files, one per rank: written after the second output,
     * read into a new integrator; the continued run equals the
     * uninterrupted one bit for bit (every output, steps, event), with the
     * dense LU of each rank and with SPGMR over the ranks (on 1 and 2
     * ranks: kept cheap, 4 ranks oversubscribe the machine) */
    if (size <= 2) {
      static const int rmethods[2] = {0, 3};
      static const char *rname[2] = {"GA, dense LU per rank", "GA, SPGMR over the ranks"};
      int i;
      for (i = 0; i < 2; i++) {
        Run cont = NewRun(K);
        int same;
        par = NewRun(K);
        Integrate(rmethods[i], VEC_MPIPLUSX, comm, u0, K, FAIL_NONE, 1e-7, ctx_par, &par);
        restart_after = 2;
        Integrate(rmethods[i], VEC_MPIPLUSX, comm, u0, K, FAIL_NONE, 1e-7, ctx_par, &cont);
        restart_after = 0;
        same = par.flag == 0 && cont.flag == 0 && par.nst == cont.nst &&
               memcmp(&par.troot, &cont.troot, sizeof par.troot) == 0 &&
               memcmp(par.q, cont.q, (size_t)NOUT * (size_t)(NQ_TOP * K) * sizeof(sunrealtype)) == 0 &&
               memcmp(par.v, cont.v, (size_t)NOUT * (size_t)(NV_TOP * K) * sizeof(sunrealtype)) == 0;
        if (rank == 0)
          printf("  restart file per rank, %s: %s (%ld steps)\n", rname[i],
                 same ? "continued bit for bit" : "DIFFERENT", cont.nst);
        snprintf(what, sizeof what, "(f) %s: restarted from files, bit for bit (%s, %s)",
                 rname[i], LGNGetReturnFlagName(par.flag),
                 LGNGetReturnFlagName(cont.flag));
        Check(same, rank, what);
        FreeRun(&par);
        FreeRun(&cont);
      }
    }

    par = NewRun(K);
    Integrate(3, VEC_MPIPLUSX, comm, u0, K, rank == last ? PSOLVE_REC : FAIL_NONE, 1e-7,
              ctx_par, &par);
    if (rank == 0)
      printf("  faults of one rank: preconditioner failing once on rank %d: %s, %ld steps, "
             "%ld failed\n", last, LGNGetReturnFlagName(par.flag), par.nst, par.nfails);
    snprintf(what, sizeof what, "(e) a preconditioner failing once on rank %d: retried "
             "everywhere (%s, %ld failed)", last, LGNGetReturnFlagName(par.flag), par.nfails);
    Check(par.flag == 0 && par.nfails >= 1 && SameOnAllRanks((double)par.nst, comm) &&
              SameOnAllRanks((double)par.nfails, comm), rank, what);
    FreeRun(&par);
    FreeRun(&one);
  }

  FreeRun(&exact);
  MPI_Allreduce(&nfail_checks, &fails, 1, MPI_INT, MPI_SUM, comm);
  if (rank == 0) printf("test_mpi_ranks: %s\n", fails == 0 ? "OK" : "FAILED");
  SUNContext_Free(&ctx_one);
  SUNContext_Free(&ctx_par);
  MPI_Finalize();
  return fails == 0 ? 0 : 1;
}
