/* -----------------------------------------------------------------------------
 * Lignum example: one chain of N bodies split over MPI ranks, with joints
 * and force elements between bodies of different ranks (user guide §11).
 *
 *   mpiexec -n 2 build/examples/chain_mpi --n 100000
 *
 * Shows:
 *   - the partition: rank r owns the contiguous bodies [lo, hi) of the
 *     chain and holds one ghost, body lo - 1 (the last body of rank r - 1),
 *     because the joint and the spring between lo - 1 and lo are declared
 *     here. Its group, vectors and model (bodies, joints: LGNModel_Attach)
 *     cover its bodies and its ghost;
 *   - LGNHalo_Create (who owns the ghost), LGNBodies_SetGhosts (the ghost's
 *     mass and weight belong to its owner), LGNSetHalo (Lignum adds what
 *     each rank's joints and springs put on a ghost to the owner's rows, and
 *     keeps the ghosts' state equal to their owners');
 *   - the coupled Newton system solved across the ranks: SPGMR over the
 *     ranks' owned unknowns with the block preconditioner (each rank
 *     factors its own bodies and joints with KLU), or, with --solver mumps
 *     (built with PETSc), MUMPS on the sum of the ranks' matrices.
 *
 * Model: N bodies (R^3 x SO(3)), rods of length 1 and mass 1 (inertia of a
 * thin rod of radius 0.05), the first held at the origin by a spherical
 * joint, consecutive ones joined by spherical joints and rotational
 * spring-dampers (k = 20, c = 0.5), under gravity, released horizontally
 * at rest. Generalized-alpha (rho_inf = 0.8), fixed steps h = 1e-3,
 * modified Newton. The table (every 10 steps): the position of the free
 * end, the total energy and the largest |Phi| (sums and maxima over the
 * ranks); it is the same on any number of ranks (to the Krylov tolerance).
 * Then the costs: time per step on the slowest rank, memory per rank, and
 * Krylov iterations per Newton iteration.
 *
 * Options: --n N (bodies, default 64), --steps S (default 40),
 * --solver krylov|mumps, --no-timing (the table only: CTest compares it).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include <mpi.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_halo.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_model.h>
#include <lignum/lignum_ls.h>
#if defined(LGN_HAVE_PETSC)
#include <lignum/lignum_petsc.h>
#include <sunmatrix/sunmatrix_sparse.h>
#endif
#include <nvector/nvector_mpiplusx.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_spgmr.h>

/* B^T lambda without forming B (LGNSetConstraintForceFn); the model is the
 * user data of every callback set on the integrator */
static int ConstrForce(sunrealtype t, N_Vector q, N_Vector lambda, N_Vector f, void *ud)
{
  return LGNJoints_ConstraintForce(LGNModel_GetJoints((LGNModel)ud), t, q, lambda, f) ? -1 : 0;
}

/* A flag every rank goes on with: nonzero if any rank's is (a local
 * failure must stop every rank before the next collective call). */
static int Agreed(MPI_Comm comm, int flag)
{
  int any = 0, local = flag != 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
  return any ? (flag != 0 ? flag : -1) : 0;
}

/* The free end (the far end of body N - 1, on the last rank), the total
 * energy and the largest |Phi|, reduced over the ranks to rank 0. */
static void PrintRow(MPI_Comm comm, int rank, int nranks, LGNModel md, sunrealtype t,
                     N_Vector q, N_Vector v, N_Vector phi, int nown, sunindextype m)
{
  double mine[4] = {0.0, 0.0, 0.0, 0.0}, sum[4], pmax = 0.0, pall = 0.0;
  sunrealtype kin, pot;
  sunindextype i;
  LGNBodies_Energy(LGNModel_GetBodies(md), q, v, &kin, &pot);
  mine[0] = kin + pot;
  if (rank == nranks - 1) { /* the end point: x + R (0.5, 0, 0) */
    const sunrealtype *x = N_VGetArrayPointer(q) + 7 * (nown - 1), *p = x + 3;
    mine[1] = x[0] + 0.5 * (1.0 - 2.0 * (p[2] * p[2] + p[3] * p[3]));
    mine[2] = x[1] + 0.5 * 2.0 * (p[1] * p[2] + p[0] * p[3]);
    mine[3] = x[2] + 0.5 * 2.0 * (p[1] * p[3] - p[0] * p[2]);
  }
  LGNJoints_Residual(LGNModel_GetJoints(md), t, q, phi);
  for (i = 0; i < m; i++) pmax = fmax(pmax, fabs(N_VGetArrayPointer(phi)[i]));
  MPI_Reduce(mine, sum, 4, MPI_DOUBLE, MPI_SUM, 0, comm);
  MPI_Reduce(&pmax, &pall, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
  if (rank == 0)
    printf("%7.3f %14.6f %12.6f %14.6f %16.6f %10.1e\n", t, sum[1], sum[2], sum[3], sum[0],
           pall < 1e-12 ? 0.0 : pall);
}

int main(int argc, char **argv)
{
  const sunrealtype L = 1.0, mass = 1.0, radius = 0.05, h = 1e-3;
  const sunrealtype J[3] = {0.5 * mass * radius * radius, mass * L * L / 12.0,
                            mass * L * L / 12.0};
  const sunrealtype gvec[3] = {0.0, 0.0, -9.81}, origin[3] = {0.0, 0.0, 0.0};
  const sunrealtype left[3] = {-0.5 * L, 0.0, 0.0}, right[3] = {0.5 * L, 0.0, 0.0};
  MPI_Comm comm = MPI_COMM_WORLD;
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, *factors = NULL;
  LGNHalo halo = NULL;
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel md = NULL;
  N_Vector q = NULL, v = NULL, phi = NULL, y = NULL, yloc = NULL;
  SUNMatrix A = NULL; /* MUMPS's matrix (NULL for Krylov) */
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  long int N = 64, nsteps = 40, *gid = NULL, s;
  long int nst = 0, nni = 0, nli = 0, nlsetup = 0, lenrw = 0, leniw = 0;
  int rank, nranks, nown, nghost, k, flag = 0, ghost_owner, timing = 1, mumps = 0;
  sunindextype m;
  sunrealtype t = 0.0, *qd;
  double tsolve, tmax = 0.0;
  struct rusage ru;

  MPI_Init(&argc, &argv);
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &nranks);
  for (k = 1; k < argc; k++) {
    if (!strcmp(argv[k], "--n") && k + 1 < argc) N = atol(argv[++k]);
    else if (!strcmp(argv[k], "--steps") && k + 1 < argc) nsteps = atol(argv[++k]);
    else if (!strcmp(argv[k], "--solver") && k + 1 < argc) mumps = !strcmp(argv[++k], "mumps");
    else if (!strcmp(argv[k], "--no-timing")) timing = 0;
    else flag = 1;
  }
  if (flag || N < nranks || nsteps < 1) {
    if (rank == 0)
      fprintf(stderr, "usage: chain_mpi [--n N >= ranks] [--steps S] [--solver krylov|mumps] "
                      "[--no-timing]\n");
    MPI_Finalize();
    return 1;
  }
#if !defined(LGN_HAVE_PETSC)
  if (mumps) {
    if (rank == 0) fprintf(stderr, "chain_mpi: --solver mumps needs Lignum built with PETSc\n");
    MPI_Finalize();
    return 1;
  }
#endif
  /* the SUNContext on the run's communicator */
  if (SUNContext_Create((void *)&comm, &ctx) != 0) MPI_Abort(comm, 1);

  /* 1. The partition: bodies [lo, hi) here, and the ghost lo - 1 (r > 0),
   *    whose owner is rank r - 1. Local numbering: owned bodies 0 ... nown-1
   *    (body lo + j is local j), then the ghost. */
  {
    const long int lo = (long int)(((long long)rank * N) / nranks);
    const long int hi = (long int)(((long long)(rank + 1) * N) / nranks);
    nown   = (int)(hi - lo);
    nghost = rank > 0 ? 1 : 0;
    ghost_owner = rank - 1;
    gid = (long int *)malloc((size_t)(nown + nghost) * sizeof(long int));
    factors = (LGNGroup *)malloc((size_t)(nown + nghost) * sizeof(LGNGroup));
    if (gid == NULL || factors == NULL) MPI_Abort(comm, 1);
    for (k = 0; k < nown; k++) gid[k] = lo + k;
    if (nghost) gid[nown] = lo - 1;
    body = LGNGroup_R3xSO3();
    for (k = 0; k < nown + nghost; k++) factors[k] = body;
    G = LGNGroup_Product(nown + nghost, factors);

    /* 2. The bodies (the ghost: no mass or weight of its own here), the
     *    joints and springs of this rank: those ending at one of its bodies
     *    (between lo - 1 and lo: the ghost and local body 0). */
    bodies = LGNBodies_Create(G);
    joints = LGNJoints_Create(G);
    md = LGNModel_Create(bodies, joints);
    if (bodies == NULL || joints == NULL) flag = -1;
    if (!flag) flag = LGNBodies_SetGravity(bodies, gvec);
    for (k = 0; k < nown && !flag; k++) flag = LGNBodies_SetPrincipalInertia(bodies, k, mass, J);
    if (!flag && nghost) flag = LGNBodies_SetGhosts(bodies, nown);
    for (k = 0; k < nown && !flag; k++) {
      const int prev = k > 0 ? k - 1 : nown; /* the local number of body lo + k - 1 */
      if (lo + k == 0) {
        flag = LGNJoints_AddSpherical(joints, LGN_GROUND, origin, 0, left);
      } else {
        flag = LGNJoints_AddSpherical(joints, prev, right, k, left);
        if (!flag) flag = LGNBodies_AddRotationalSpringDamper(bodies, prev, k, 20.0, 0.5, NULL);
      }
    }
  }
  m = LGNJoints_NumConstraints(joints);

  /* 3. The state: MPIPlusX vectors over the rank's bodies and ghost. The
   *    chain lies along x at rest; the ghost's entries are filled by Lignum
   *    from its owner. */
  q   = N_VMake_MPIPlusX(comm, N_VNew_Serial(G->nq, ctx), ctx);
  v   = N_VMake_MPIPlusX(comm, N_VNew_Serial(G->nv, ctx), ctx);
  phi = N_VNew_Serial(m > 0 ? m : 1, ctx);
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  qd = N_VGetArrayPointer(q);
  for (k = 0; k < nown; k++) {
    qd[7 * k]     = ((sunrealtype)gid[k] + 0.5) * L;
    qd[7 * k + 3] = 1.0;
  }

  /* 4. The integrator, as on one process, and the halo (collective). */
  mem = LGNCreate(ctx);
  if (!flag) flag = LGNModel_Attach(md, mem);
  if (!flag) flag = LGNSetConstraintForceFn(mem, ConstrForce);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.8);
  if (!flag) flag = LGNSetStepSize(mem, h);
  if (!flag) flag = LGNSetNewtonMode(mem, LGN_NEWTON_MODIFIED);
  /* set-up errors are local: agree before the collective calls */
  flag = Agreed(comm, flag);
  halo = flag == 0 ? LGNHalo_Create(comm, G, nown, gid, nghost ? &ghost_owner : NULL) : NULL;
  if (!flag && halo == NULL) flag = -1; /* NULL on every rank alike */
  /* the halo before LGNInit: the ghost's entries of q and v are not read;
   * it is referenced, so it is destroyed after LGNFree */
  if (!flag) flag = LGNSetHalo(mem, halo);
  flag = Agreed(comm, flag);
  if (!flag) flag = LGNInit(mem, 0.0, q, v); /* collective */

  /* 5. The linear solver across the ranks. Krylov: SPGMR over the owned
   *    unknowns (6 per owned body and this rank's constraints), the block
   *    preconditioner with one block per rank. MUMPS: a sparse matrix over
   *    the rank's subdomain (bodies, ghost, constraints) and the global
   *    numbers of its unknowns. */
  yloc = N_VNew_Serial(6 * (sunindextype)nown + m, ctx);
  y    = N_VMake_MPIPlusX(comm, yloc, ctx);
  if (!mumps) {
    /* 15 directions, restarted up to 3 times: block-Jacobi needs about 2
     * iterations per rank here */
    LS = SUNLinSol_SPGMR(y, SUN_PREC_LEFT, 15, ctx);
    if (LS == NULL || SUNLinSol_SPGMRSetMaxRestarts(LS, 3) != 0) flag = -1;
    if (!flag) flag = LGNSetLinearSolver(mem, LS, NULL);
    if (!flag) flag = LGNSetBlockPreconditioner(mem, 1, NULL);
  }
#if defined(LGN_HAVE_PETSC)
  else {
    sunindextype n = 0, *idx = NULL;
    if (!flag) flag = LGNGetSubdomainSize(mem, &n);
    idx = (sunindextype *)malloc((size_t)(n > 0 ? n : 1) * sizeof(sunindextype));
    if (idx == NULL) flag = -1;
    flag = Agreed(comm, flag);
    if (!flag) flag = LGNGetGlobalIndices(mem, idx); /* collective */
    /* Lignum fills the pattern (1 entry will do: it grows the room) */
    if (!flag) A = SUNSparseMatrix(n, n, 1, CSC_MAT, ctx);
    flag = Agreed(comm, flag);
    LS = flag ? NULL : LGNLinSol_PETScSubdomain(y, A, idx, ctx); /* collective */
    if (!flag && LS == NULL) flag = -1;
    if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
    free(idx);
  }
#endif
  /* 6. The time loop: every call collective; the table from rank 0. */
  if (rank == 0) {
    printf("Chain of %ld bodies, generalized-alpha(0.8), h = %.0e\n\n", N, h);
    printf("%7s %14s %12s %14s %16s %10s\n", "t", "x_end", "y_end", "z_end", "energy",
           "|Phi|");
  }
  /* the table evaluates this rank's joints, which need the ghost: before
   * the first LGNSolve its entries are ours to fill (Lignum fills them in
   * the vectors LGNSolve returns) */
  flag = Agreed(comm, flag);
  if (!flag) flag = LGNHalo_UpdateGhosts(halo, LGN_HALO_CONFIGURATION, N_VGetArrayPointer(q));
  if (!flag) PrintRow(comm, rank, nranks, md, t, q, v, phi, nown, m);
  tsolve = 0.0;
  for (s = 10; !flag && s <= nsteps; s += 10) {
    const double t1 = MPI_Wtime();
    flag = LGNSolve(mem, (sunrealtype)s * h, &t, q, v, LGN_NORMAL);
    /* the steady cost: the steps after the first call (which also makes
     * the work space, analyses the matrices' patterns and computes the
     * initial accelerations) */
    if (s > 10) tsolve += MPI_Wtime() - t1;
    if (!flag) PrintRow(comm, rank, nranks, md, t, q, v, phi, nown, m);
  }
  if (flag) fprintf(stderr, "chain_mpi (rank %d): %s\n", rank, LGNGetReturnFlagName(flag));

  /* 7. The costs: the slowest rank's time, this rank's memory. */
  LGNGetNumSteps(mem, &nst);
  LGNGetNumNewtonIters(mem, &nni);
  LGNGetNumLinIters(mem, &nli);
  LGNGetNumLinSolvSetups(mem, &nlsetup);
  LGNGetWorkSpace(mem, &lenrw, &leniw);
  MPI_Reduce(&tsolve, &tmax, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
  getrusage(RUSAGE_SELF, &ru);
  {
    double mb = (double)ru.ru_maxrss / 1024.0, mbmax = 0.0;
    MPI_Reduce(&mb, &mbmax, 1, MPI_DOUBLE, MPI_MAX, 0, comm);
    if (rank == 0) {
      printf("\nsteps = %ld   Newton iterations = %ld   matrix setups = %ld\n", nst, nni, nlsetup);
      if (!mumps && timing) /* depends on the number of ranks */
        printf("Krylov iterations per Newton iteration = %.2f\n",
               nni > 0 ? (double)nli / (double)nni : 0.0);
      if (timing && nst > 10) {
        const double steps = (double)(nst - 10); /* after the first call */
        printf("%s, %d rank%s: time per step (slowest rank, steps 11 ... %ld) = %.3f ms   "
               "per step and body = %.3f us\n",
               mumps ? "MUMPS" : "SPGMR + block preconditioner", nranks, nranks > 1 ? "s" : "", nst,
               1e3 * tmax / steps, 1e6 * tmax / steps / (double)N);
        printf("memory per rank (max RSS) = %.1f MB   Lignum's work space on rank 0 = %.1f MB\n",
               mbmax, (8.0 * (double)lenrw + 8.0 * (double)leniw) / 1048576.0);
      }
    }
  }

  LGNFree(&mem);
  LGNHalo_Destroy(&halo);
  SUNLinSolFree(LS);
  if (A != NULL) SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(yloc);
  N_VDestroy(N_VGetLocalVector_MPIPlusX(q));
  N_VDestroy(N_VGetLocalVector_MPIPlusX(v));
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(phi);
  LGNModel_Destroy(&md); /* after LGNFree */
  LGNJoints_Destroy(&joints);
  LGNBodies_Destroy(&bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  free(factors);
  free(gid);
  SUNContext_Free(&ctx);
  MPI_Finalize();
  return flag ? 1 : 0;
}
