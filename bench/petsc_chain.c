/* -----------------------------------------------------------------------------
 * Lignum benchmark: the direct solve through PETSc and MUMPS
 * (LGNLinSol_PETSc) against KLU on the chain's iteration matrix.
 *
 *   petsc_chain [N ...]                (default: 1000 10000)
 *   mpiexec -n 2 petsc_chain [N ...]
 *
 * For each chain of N bodies (spherical joints, index 3, generalized-alpha
 * 0.9, h = 1e-3): two steps with KLU on a CSR matrix leave the iteration
 * matrix A (nv + m = 9 N unknowns) in the user's matrix; then, on that A,
 * the wall time of one setup (factorisation; KLU: refactorisation with the
 * first analysis kept, PETSc: numerical factorisation with MUMPS' analysis
 * kept) and one solve, each the median of several, and the time of the
 * first setup (with the analysis). KLU runs on every rank alone (rank 0's
 * times are printed); PETSc on all ranks of MPI_COMM_WORLD. Also the
 * relative difference of the solutions. A program to run by hand (timings
 * are not tests): `cmake --build build --target run_petsc_chain`.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mpi.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_petsc.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Model;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Model *)ud)->bodies);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Model *)ud)->bodies);
}
static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  return LGNBodies_DampingFn(t, q, v, C, ((Model *)ud)->bodies);
}
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->joints, t, q, phi) ? -1 : 0;
}
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->joints, t, q, B) ? -1 : 0;
}
static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Model *)ud)->joints, t, q, v, z) ? -1 : 0;
}
static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  (void)v; (void)vdot;
  return LGNJoints_Stiffness(((Model *)ud)->joints, t, q, lambda, K) ? -1 : 0;
}

static int CmpDouble(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}
static double Median(double *t, int n)
{
  qsort(t, (size_t)n, sizeof *t, CmpDouble);
  return t[n / 2];
}

/* first setup, median setup and median solve of LS on A (seconds) */
static int Time(SUNLinearSolver LS, SUNMatrix A, N_Vector b, N_Vector x, int reps,
                double *first, double *setup, double *solve)
{
  double ts[64], tv[64], t0;
  int k, flag = SUNLinSolInitialize(LS);
  MPI_Barrier(MPI_COMM_WORLD);
  t0 = MPI_Wtime();
  if (!flag) flag = SUNLinSolSetup(LS, A);
  *first = MPI_Wtime() - t0;
  for (k = 0; k < reps && !flag; k++) {
    MPI_Barrier(MPI_COMM_WORLD);
    t0    = MPI_Wtime();
    flag  = SUNLinSolSetup(LS, A);
    ts[k] = MPI_Wtime() - t0;
  }
  for (k = 0; k < reps && !flag; k++) {
    MPI_Barrier(MPI_COMM_WORLD);
    t0    = MPI_Wtime();
    flag  = SUNLinSolSolve(LS, A, x, b, 0.0);
    tv[k] = MPI_Wtime() - t0;
  }
  if (flag) return flag;
  *setup = Median(ts, reps);
  *solve = Median(tv, reps);
  return 0;
}

static int Bench(int nb, int rank, int nranks, SUNContext ctx)
{
  const sunrealtype L = 1.0, mass = 1.0, radius = 0.02;
  const sunrealtype J[3] = {0.5 * mass * radius * radius, mass * L * L / 12.0,
                            mass * L * L / 12.0};
  const sunrealtype gvec[3] = {0.0, 0.0, -9.81}, origin[3] = {0.0, 0.0, 0.0};
  const sunrealtype left[3] = {-0.5 * L, 0.0, 0.0}, right[3] = {0.5 * L, 0.0, 0.0};
  const int reps = nb >= 10000 ? 7 : 21;
  LGNGroup body = LGNGroup_R3xSO3(), G, *factors;
  Model md;
  N_Vector q, v, y, b, x1, x2;
  SUNMatrix A;
  SUNLinearSolver klu, pet;
  void *mem;
  sunrealtype t = 0.0, *qd;
  sunindextype m, n, i;
  long int nnz = 0;
  double kf, ks, kv, pf, ps, pv, d = 0.0, s = 0.0;
  int k, flag = 0;

  factors = (LGNGroup *)malloc((size_t)nb * sizeof *factors);
  for (k = 0; k < nb; k++) factors[k] = body;
  G         = LGNGroup_Product(nb, factors);
  md.bodies = LGNBodies_Create(G);
  md.joints = LGNJoints_Create(G);
  flag      = LGNBodies_SetGravity(md.bodies, gvec);
  for (k = 0; k < nb && !flag; k++) {
    flag = LGNBodies_SetPrincipalInertia(md.bodies, k, mass, J);
    if (!flag)
      flag = k == 0 ? LGNJoints_AddSpherical(md.joints, LGN_GROUND, origin, 0, left)
                    : LGNJoints_AddSpherical(md.joints, k - 1, right, k, left);
  }
  m  = LGNJoints_NumConstraints(md.joints);
  n  = G->nv + m;
  q  = N_VNew_Serial(G->nq, ctx);
  v  = N_VNew_Serial(G->nv, ctx);
  y  = N_VNew_Serial(n, ctx);
  b  = N_VNew_Serial(n, ctx);
  x1 = N_VNew_Serial(n, ctx);
  x2 = N_VNew_Serial(n, ctx);
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  qd = N_VGetArrayPointer(q);
  for (k = 0; k < nb; k++) {
    qd[7 * k]     = (k + 0.5) * L;
    qd[7 * k + 3] = 1.0;
  }
  mem = LGNCreate(ctx);
  if (!flag) flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetStiffnessFn(mem, Stiffness);
  if (!flag) flag = LGNSetDampingFn(mem, Damping);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  A   = SUNSparseMatrix(n, n, 1, CSR_MAT, ctx);
  klu = SUNLinSol_KLU(y, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, klu, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepSize(mem, 1e-3);
  if (!flag) flag = LGNSolve(mem, 2e-3, &t, q, v, LGN_NORMAL); /* A: the last matrix */
  LGNGetIterationMatrixNnz(mem, &nnz);
  LGNFree(&mem);
  for (i = 0; i < n; i++) N_VGetArrayPointer(b)[i] = sin(0.37 * (double)i);

  /* KLU: a new solver on A (analysis at its first setup) */
  SUNLinSolFree(klu);
  klu = SUNLinSol_KLU(y, A, ctx);
  if (!flag) flag = Time(klu, A, b, x1, reps, &kf, &ks, &kv);
  pet = LGNLinSol_PETSc(y, A, MPI_COMM_WORLD, ctx);
  if (pet == NULL) flag = -1;
  if (!flag) flag = Time(pet, A, b, x2, reps, &pf, &ps, &pv);
  for (i = 0; i < n && !flag; i++) {
    d = fmax(d, fabs(N_VGetArrayPointer(x1)[i] - N_VGetArrayPointer(x2)[i]));
    s = fmax(s, fabs(N_VGetArrayPointer(x1)[i]));
  }
  if (rank == 0 && !flag) {
    printf("%7d %8lld %9ld %5d | %9.2f %9.2f %8.3f | %9.2f %9.2f %8.3f | %8.1e\n", nb,
           (long long)n, nnz, nranks, 1e3 * kf, 1e3 * ks, 1e3 * kv, 1e3 * pf, 1e3 * ps, 1e3 * pv,
           d / s);
    fflush(stdout);
  }
  if (flag && rank == 0) fprintf(stderr, "petsc_chain: N = %d failed (%d)\n", nb, flag);
  SUNLinSolFree(pet);
  SUNLinSolFree(klu);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(b);
  N_VDestroy(x1);
  N_VDestroy(x2);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  free(factors);
  return flag;
}

int main(int argc, char **argv)
{
  SUNContext ctx = NULL;
  int rank = 0, nranks = 1, i, flag = 0;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  SUNContext_Create(NULL, &ctx);
  if (rank == 0) {
    printf("Chain iteration matrix (index 3, CSR): KLU (one rank) vs LGNLinSol_PETSc (MUMPS on "
           "all ranks); wall ms, setup and solve medians\n");
    printf("%7s %8s %9s %5s | %9s %9s %8s | %9s %9s %8s | %8s\n", "N", "n", "nnz", "ranks",
           "KLU 1st", "KLU setup", "solve", "MUMPS 1st", "setup", "solve", "rel.diff");
  }
  if (argc > 1)
    for (i = 1; i < argc && !flag; i++) flag = Bench(atoi(argv[i]), rank, nranks, ctx);
  else {
    flag = Bench(1000, rank, nranks, ctx);
    if (!flag) flag = Bench(10000, rank, nranks, ctx);
  }
  SUNContext_Free(&ctx);
  MPI_Finalize();
  return flag ? 1 : 0;
}
