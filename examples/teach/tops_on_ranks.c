/* -----------------------------------------------------------------------------
 * Lignum teaching example: a model split over MPI ranks.
 *
 * Shows: a run across ranks (user guide §11). Eight heavy tops, each on its
 * own spherical joint and spun at its own rate, are shared out among the
 * ranks (rank r holds tops first_r ... first_r + K_r - 1). Every rank
 *   - describes only its own tops: its group is the product of its bodies,
 *     its constraints are its tops' joints, its callbacks fill its blocks;
 *   - keeps its part of the state in MPIPlusX vectors over a serial local
 *     vector, on the communicator of the SUNContext;
 *   - solves its own block of the Newton system (LGNLinSol_Dense with a
 *     serial template of the block's length nv + m);
 *   - calls LGNInit and LGNSolve with the same arguments as the others:
 *     they are collective. The ranks take the same steps, since the
 *     Newton and error tests use norms over all ranks.
 * The table is made from sums over the ranks (MPI_Allreduce) and printed by
 * rank 0: it is the same, to round-off, on 1, 2, 4 or 8 ranks, and so are
 * the step counts. Started without mpiexec it runs on one rank.
 *
 *   mpiexec -n 2 ./tops_on_ranks
 *
 * Model (each top: Brüls and Cardona's heavy top, see heavy_top.c): one
 * body on R^3 x SO(3), mass 15, principal inertia diag(0.234375, 0.46875,
 * 0.234375), centre of mass at X = (0, 1, 0) in the body frame, the body
 * point -X held at the origin; top k spins with Omega = (0, 150 - 10 k,
 * -4.61538), u = R (Omega x X). Output every 0.1 s: the total energy (a
 * sum over all tops: constant up to the integration error), the largest
 * height change of the centres of mass, and the largest |Phi|.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <mpi.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_model.h>
#include <nvector/nvector_mpiplusx.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#define NTOPS 8

/* The table's row: energy summed over all tops, the largest height change
 * and |Phi| over all ranks (each rank computes its part, MPI combines). */
static int Report(MPI_Comm comm, int rank, LGNModel md, sunrealtype t, N_Vector q,
                  N_Vector v, N_Vector phi, int K)
{
  const sunrealtype *qd = N_VGetArrayPointer(q), *ph = N_VGetArrayPointer(phi);
  double part[1], sum[1], mx[2], mxall[2], kin = 0.0, pot = 0.0;
  int k, i;
  if (LGNBodies_Energy(LGNModel_GetBodies(md), q, v, &kin, &pot) ||
      LGNJoints_Residual(LGNModel_GetJoints(md), t, q, phi))
    return -1;
  part[0] = kin + pot;
  mx[0] = mx[1] = 0.0;
  for (k = 0; k < K; k++) mx[0] = fmax(mx[0], fabs(qd[7 * k + 2])); /* z of a centre */
  for (i = 0; i < 3 * K; i++) mx[1] = fmax(mx[1], fabs(ph[i]));
  MPI_Allreduce(part, sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(mx, mxall, 2, MPI_DOUBLE, MPI_MAX, comm);
  if (rank == 0)
    printf("%4.1f %16.8f %12.8f %9.1e\n", t, sum[0], mxall[0], mxall[1]);
  return 0;
}

int main(int argc, char **argv)
{
  const sunrealtype J[3]       = {0.234375, 0.46875, 0.234375};
  const sunrealtype gravity[3] = {0.0, 0.0, -9.81};
  const sunrealtype origin[3]  = {0.0, 0.0, 0.0};
  const sunrealtype tip[3]     = {0.0, -1.0, 0.0}; /* -X: the joint's body point */
  MPI_Comm comm = MPI_COMM_WORLD;
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, factors[NTOPS];
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel md = NULL;
  N_Vector q = NULL, v = NULL, phi = NULL, tmpl = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunindextype nv, m;
  sunrealtype *qd, *vd, t = 0.0;
  long int nst = 0, nni = 0, netf = 0;
  int rank, size, first, K, k, flag = 0;

  /* Step 1: MPI, and the context on its communicator */
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size > NTOPS) {
    if (rank == 0) fprintf(stderr, "at most %d ranks: one top each at least\n", NTOPS);
    MPI_Finalize();
    return 1;
  }
  if (SUNContext_Create(&comm, &ctx) != 0) return 1;

  /* Step 2: this rank's share of the tops, and its group */
  K     = NTOPS / size + (rank < NTOPS % size ? 1 : 0);
  first = rank * (NTOPS / size) + (rank < NTOPS % size ? rank : NTOPS % size);
  body  = LGNGroup_R3xSO3();
  for (k = 0; k < K; k++) factors[k] = body;
  G  = LGNGroup_Product(K, factors); /* nq = 7 K, nv = 6 K */
  nv = G->nv;

  /* Step 3: its bodies and joints, from the helpers, as on one process */
  bodies = LGNBodies_Create(G);
  joints = LGNJoints_Create(G);
  md = LGNModel_Create(bodies, joints);
  for (k = 0; k < K && !flag; k++) {
    flag = LGNBodies_SetPrincipalInertia(bodies, k, 15.0, J);
    if (!flag) flag = LGNJoints_AddSpherical(joints, LGN_GROUND, origin, k, tip);
  }
  if (!flag) flag = LGNBodies_SetGravity(bodies, gravity);
  m = LGNJoints_NumConstraints(joints); /* 3 K */

  /* Step 4: its part of the state, in MPIPlusX vectors */
  q   = N_VMake_MPIPlusX(comm, N_VNew_Serial(G->nq, ctx), ctx);
  v   = N_VMake_MPIPlusX(comm, N_VNew_Serial(nv, ctx), ctx);
  phi = N_VNew_Serial(m, ctx);
  qd  = N_VGetArrayPointer(q); /* the rank's local array */
  vd  = N_VGetArrayPointer(v);
  LGNGroup_Identity(G, qd);
  N_VConst(0.0, v);
  for (k = 0; k < K; k++) {
    qd[7 * k + 1] = 1.0;                          /* centre at X = (0, 1, 0) */
    vd[6 * k + 4] = 150.0 - 10.0 * (first + k);  /* Omega_y of top first + k */
    vd[6 * k + 5] = -4.61538;                     /* Omega_z                 */
    vd[6 * k + 0] = -vd[6 * k + 5];               /* u = Omega x X (R = I)   */
  }

  /* Step 5: the integrator, with this rank's model; the settings are the
   * same on every rank */
  mem = LGNCreate(ctx);
  if (mem == NULL) return 1;
  if (!flag) flag = LGNModel_Attach(md, mem);
  if (!flag) flag = LGNSetKinematics(mem, LGN_KINEMATICS_EXACT);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, 1e-6, 1e-6);
  /* a set-up error on one rank must stop every rank before the collective
   * LGNInit: the flags combined (the most negative wins) */
  MPI_Allreduce(MPI_IN_PLACE, &flag, 1, MPI_INT, MPI_MIN, comm);
  if (!flag) flag = LGNInit(mem, 0.0, q, v); /* collective */

  /* Step 6: the rank's block of the Newton system, its own dense LU */
  tmpl = N_VNew_Serial(nv + m, ctx);
  A    = SUNDenseMatrix(nv + m, nv + m, ctx);
  LS   = LGNLinSol_Dense(tmpl, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);

  /* Step 7: the time loop; every rank calls LGNSolve with the same tout */
  if (rank == 0) {
    printf("%d heavy tops shared out among the ranks: mod. LGGalpha, error control, "
           "rtol = atol = 1e-6\n\n", NTOPS);
    printf("%4s %16s %12s %9s\n", "t", "energy", "max |z|", "max |Phi|");
  }
  if (!flag) flag = Report(comm, rank, md, t, q, v, phi, K);
  for (k = 1; k <= 5 && !flag; k++) {
    flag = LGNSolve(mem, 0.1 * k, &t, q, v, LGN_NORMAL);
    if (!flag) flag = Report(comm, rank, md, t, q, v, phi, K);
  }
  if (flag && rank == 0) fprintf(stderr, "failed at t = %g (%d)\n", t, flag);

  /* Step 8: the counters are the same on every rank: the same steps */
  LGNGetNumSteps(mem, &nst);
  LGNGetNumNewtonIters(mem, &nni);
  LGNGetNumErrTestFails(mem, &netf);
  if (rank == 0)
    printf("\nsteps %ld, Newton iterations %ld, error test failures %ld\n", nst, nni, netf);

  /* Step 9: free what we created (an MPIPlusX vector does not free its
   * local vector) */
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(tmpl);
  N_VDestroy(phi);
  N_VDestroy(N_VGetLocalVector_MPIPlusX(q));
  N_VDestroy(N_VGetLocalVector_MPIPlusX(v));
  N_VDestroy(q);
  N_VDestroy(v);
  LGNModel_Destroy(&md); /* after LGNFree */
  LGNJoints_Destroy(&joints);
  LGNBodies_Destroy(&bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
  MPI_Finalize();
  return flag ? 1 : 0;
}
