/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * A run across MPI ranks (lgn_parallel.h): the communicator of the user's
 * vectors, vectors of other lengths of their type, collective reductions
 * and the agreement on failures. The reductions are MPI_Allreduce on the
 * vectors' communicator: a sum of weighted squares is what
 * N_VDotProdMultiAllReduce does, and maxima and the agreement (MINLOC)
 * have no N_Vector operation.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>

#include <lignum/lignum_config.h>
#include <nvector/nvector_serial.h>

#include "lgn_parallel.h"

#ifdef LGN_HAVE_MPI
#include <mpi.h>
#include <nvector/nvector_mpiplusx.h>
#include <nvector/nvector_parallel.h>

struct LGNParallelRec {
  MPI_Comm comm;    /* a duplicate of the vectors' communicator (owned: the
                       user may free q0 and v0, and Lignum's reductions
                       never pair with the user's own)                   */
  int rank, size;
  N_Vector_ID type; /* SUNDIALS_NVEC_PARALLEL or SUNDIALS_NVEC_MPIPLUSX    */
};

#if defined(SUNDIALS_DOUBLE_PRECISION)
#define LGN_MPI_REAL MPI_DOUBLE
#elif defined(SUNDIALS_SINGLE_PRECISION)
#define LGN_MPI_REAL MPI_FLOAT
#else
#define LGN_MPI_REAL MPI_LONG_DOUBLE
#endif
#endif /* LGN_HAVE_MPI */

int lgnParallelCreate(N_Vector q0, N_Vector v0, const LGNErrSink *sink,
                      const char *func, LGNParallel *par)
{
  void *cq = N_VGetCommunicator(q0), *cv = N_VGetCommunicator(v0);
  *par = NULL;
  if (cq == NULL && cv == NULL) return LGN_SUCCESS; /* one process */
#ifdef LGN_HAVE_MPI
  {
    const N_Vector_ID id = N_VGetVectorID(q0);
    int same = MPI_UNEQUAL;
    if (cq == NULL || cv == NULL) {
      lgnReport(sink, LGN_ILL_INPUT, func,
                "%s has a communicator and %s has none: both must be on the same ranks.",
                cq != NULL ? "q0" : "v0", cq != NULL ? "v0" : "q0");
      return LGN_ILL_INPUT;
    }
    MPI_Comm_compare(*(MPI_Comm *)cq, *(MPI_Comm *)cv, &same);
    if (same != MPI_IDENT && same != MPI_CONGRUENT) {
      lgnReport(sink, LGN_ILL_INPUT, func, "q0 and v0 are on different communicators.");
      return LGN_ILL_INPUT;
    }
    if ((id != SUNDIALS_NVEC_PARALLEL && id != SUNDIALS_NVEC_MPIPLUSX) ||
        N_VGetVectorID(v0) != id) {
      lgnReport(sink, LGN_ILL_INPUT, func,
                "q0 and v0 across ranks must both be N_Vector_Parallel or both "
                "MPIPlusX vectors (types %d and %d given).",
                (int)id, (int)N_VGetVectorID(v0));
      return LGN_ILL_INPUT;
    }
    *par = (LGNParallel)malloc(sizeof(**par));
    if (*par == NULL) {
      lgnReport(sink, LGN_MEM_FAIL, func, "A memory request failed.");
      return LGN_MEM_FAIL;
    }
    MPI_Comm_dup(*(MPI_Comm *)cq, &(*par)->comm);
    (*par)->type = id;
    MPI_Comm_rank((*par)->comm, &(*par)->rank);
    MPI_Comm_size((*par)->comm, &(*par)->size);
    return LGN_SUCCESS;
  }
#else
  lgnReport(sink, LGN_ILL_INPUT, func,
            "q0 and v0 are MPI vectors, but Lignum was built without MPI "
            "(LGN_ENABLE_MPI=OFF).");
  return LGN_ILL_INPUT;
#endif
}

void lgnParallelFree(LGNParallel *par)
{
#ifdef LGN_HAVE_MPI
  int finalized = 0;
  if (*par != NULL) {
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Comm_free(&(*par)->comm);
  }
#endif
  free(*par);
  *par = NULL;
}

int lgnParallelRank(const LGNParallel par)
{
#ifdef LGN_HAVE_MPI
  if (par != NULL) return par->rank;
#endif
  (void)par;
  return 0;
}

int lgnParallelSize(const LGNParallel par)
{
#ifdef LGN_HAVE_MPI
  if (par != NULL) return par->size;
#endif
  (void)par;
  return 1;
}

N_Vector lgnParallelNewVector(LGNParallel par, sunindextype n, SUNContext ctx)
{
#ifdef LGN_HAVE_MPI
  if (par != NULL && par->type == SUNDIALS_NVEC_PARALLEL) {
    long long local = (long long)n, global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_LONG_LONG, MPI_SUM, par->comm);
    return N_VNew_Parallel(par->comm, n, (sunindextype)global, ctx);
  }
  if (par != NULL) {
    /* MPIPlusX over a serial part; the clone owns its part, so every
     * vector of the record is freed by N_VDestroy alone. Making and
     * cloning are collective (a communicator is duplicated, the global
     * length summed): the ranks agree first that each has its part. */
    N_Vector local = N_VNew_Serial(n, ctx), made = NULL, clone = NULL;
    int ok = local != NULL, all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, par->comm);
    if (all_ok) made = N_VMake_MPIPlusX(par->comm, local, ctx);
    ok = made != NULL;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, par->comm);
    if (all_ok) clone = N_VClone(made);
    if (made != NULL) N_VDestroy(made);
    if (local != NULL) N_VDestroy(local);
    return clone;
  }
#endif
  (void)par;
  return N_VNew_Serial(n, ctx);
}

void lgnParallelSum(const LGNParallel par, sunrealtype *x, int n)
{
#ifdef LGN_HAVE_MPI
  if (par != NULL && par->size > 1)
    MPI_Allreduce(MPI_IN_PLACE, x, n, LGN_MPI_REAL, MPI_SUM, par->comm);
#endif
  (void)par;
  (void)x;
  (void)n;
}

sunrealtype lgnParallelMax(const LGNParallel par, sunrealtype x)
{
#ifdef LGN_HAVE_MPI
  /* a NaN counts as the largest, as on one process (MPI's MAX may drop it
   * and other ranks' values with it) */
  if (isnan(x)) x = (sunrealtype)INFINITY;
  if (par != NULL && par->size > 1)
    MPI_Allreduce(MPI_IN_PLACE, &x, 1, LGN_MPI_REAL, MPI_MAX, par->comm);
#endif
  (void)par;
  return x;
}

/* Failures are keyed below recoverable flags below success: key = flag -
 * 1000 for flag < 0, -flag for flag >= 0 (flags lie in (-1000, 1000)); the
 * smallest key over the ranks, with the lowest rank that has it (MINLOC),
 * is the agreed flag. */
int lgnParallelAgree(const LGNParallel par, int flag, int *rank)
{
  *rank = flag != 0 ? lgnParallelRank(par) : -1;
#ifdef LGN_HAVE_MPI
  if (par != NULL && par->size > 1) {
    struct { int key, rank; } in, out;
    in.key  = flag < 0 ? flag - 1000 : -flag;
    in.rank = par->rank;
    MPI_Allreduce(&in, &out, 1, MPI_2INT, MPI_MINLOC, par->comm);
    *rank = out.key != 0 ? out.rank : -1;
    return out.key < -999 ? out.key + 1000 : -out.key;
  }
#endif
  (void)par;
  return flag;
}

/* x and -x reduced with MAX together: equal everywhere when max x = min x. */
int lgnParallelSame(const LGNParallel par, const sunrealtype *x, int n, int *first)
{
  *first = -1;
#ifdef LGN_HAVE_MPI
  if (par != NULL && par->size > 1) {
    sunrealtype both[2 * LGN_PARALLEL_MAXSAME];
    int i;
    if (n > LGN_PARALLEL_MAXSAME) n = LGN_PARALLEL_MAXSAME;
    for (i = 0; i < n; i++) {
      both[i]     = x[i];
      both[n + i] = -x[i];
    }
    MPI_Allreduce(MPI_IN_PLACE, both, 2 * n, LGN_MPI_REAL, MPI_MAX, par->comm);
    for (i = 0; i < n; i++)
      if (both[i] != -both[n + i]) {
        *first = i;
        return 0;
      }
  }
#endif
  (void)par;
  (void)x;
  (void)n;
  return 1;
}
