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

#include <stdlib.h>

#include <lignum/lignum_config.h>
#include <nvector/nvector_serial.h>

#include "lgn_parallel.h"

#ifdef LGN_HAVE_MPI
#include <mpi.h>
#include <nvector/nvector_mpiplusx.h>
#include <nvector/nvector_parallel.h>

struct LGNParallelRec {
  MPI_Comm comm;    /* the user's communicator (not owned)                 */
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
    (*par)->comm = *(MPI_Comm *)cq;
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
     * vector of the record is freed by N_VDestroy alone. Every rank makes
     * both vectors, whatever fails, so that the collectives match. */
    N_Vector local = N_VNew_Serial(n, ctx);
    N_Vector made  = local != NULL ? N_VMake_MPIPlusX(par->comm, local, ctx) : NULL;
    N_Vector clone = made != NULL ? N_VClone(made) : NULL;
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
