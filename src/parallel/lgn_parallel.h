/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header: a run across MPI ranks. The communicator is the one of
 * the user's state vectors (N_VGetCommunicator); every rank holds the
 * bodies and constraints of its part of the model, and the integrator's
 * local arrays are the rank-local parts of its vectors. This layer gives
 *
 *   - vectors of other lengths (m, nv + m) of the user's type, for the
 *     multipliers and the Newton system (there is no N_VClone with another
 *     length): N_Vector_Parallel or MPIPlusX over the rank-local part;
 *   - the collective reductions every decision of a step goes through
 *     (sums of the weighted norms, maxima), so that every rank computes
 *     the same norm and takes the same decision;
 *   - the agreement on a failure: a callback or linear solve that failed
 *     on one rank fails the attempt on every rank, with the same flag.
 *
 * A NULL LGNParallel is a run on one process (vectors without a
 * communicator): every function is then a no-op or serial. Built without
 * MPI (LGN_HAVE_MPI undefined), vectors with a communicator are refused.
 * It knows nothing of the integrator's record (messages go to a sink).
 * ---------------------------------------------------------------------------*/

#ifndef LGN_PARALLEL_H
#define LGN_PARALLEL_H

#include <lignum/lignum.h>

#include "lgn_err.h"

typedef struct LGNParallelRec *LGNParallel;

/* The length of x's rank-local part (all of x on one process), through
 * the operation N_VGetLocalLength (deprecated in SUNDIALS 6) calls. */
static inline sunindextype lgnLocalLength(N_Vector x)
{
  return x->ops->nvgetlocallength != NULL ? x->ops->nvgetlocallength(x) : N_VGetLength(x);
}

/* The run the vectors q0 and v0 belong to: *par = NULL for vectors without
 * a communicator (one process), else a new record on a duplicate of their
 * communicator (collective). LGN_ILL_INPUT (reported for func) for an
 * unsupported vector type, vectors on different communicators, or MPI not
 * built in. lgnParallelFree frees the duplicate (collective too). */
int lgnParallelCreate(N_Vector q0, N_Vector v0, const LGNErrSink *sink,
                      const char *func, LGNParallel *par);
void lgnParallelFree(LGNParallel *par);

/* This rank and the number of ranks (0 and 1 on one process). */
int lgnParallelRank(const LGNParallel par);
int lgnParallelSize(const LGNParallel par);

/* A vector whose rank-local part has length n, of the user's type (a
 * serial one on one process). Collective. NULL when out of memory. */
N_Vector lgnParallelNewVector(LGNParallel par, sunindextype n, SUNContext ctx);

/* x[0 .. n-1] <- their sums over all ranks (in place). Collective. */
void lgnParallelSum(const LGNParallel par, sunrealtype *x, int n);

/* The maximum of x over all ranks. Collective. */
sunrealtype lgnParallelMax(const LGNParallel par, sunrealtype x);

/* Are x[0 .. n-1] (n <= LGN_PARALLEL_MAXSAME) the same on every rank? If
 * not, *first is the first that differs (else -1). Collective. */
#define LGN_PARALLEL_MAXSAME 64
int lgnParallelSame(const LGNParallel par, const sunrealtype *x, int n, int *first);

/* The flag every rank continues with: a failure (< 0) on any rank before
 * a recoverable one (> 0) before success; among failures the most negative
 * flag, of the lowest rank that has it (*rank: that rank, -1 for success).
 * Collective. */
int lgnParallelAgree(const LGNParallel par, int flag, int *rank);

#endif
