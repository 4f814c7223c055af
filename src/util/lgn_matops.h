/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header of lgn_matops.c: matrix-vector kernels and the finiteness
 * test (pure helpers, no integrator record).
 * ---------------------------------------------------------------------------*/

#ifndef LGN_MATOPS_H
#define LGN_MATOPS_H

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

/* The data array of x. A serial vector's is read directly: Debian builds
 * SUNDIALS at -O0, where N_VGetArrayPointer costs two calls (8 % of a
 * heavy-top step was spent in them). Its operation table tells the type
 * without a call; any other type goes through N_VGetArrayPointer. */
static inline sunrealtype *lgnVecData(N_Vector x)
{
  return x->ops->nvgetarraypointer == N_VGetArrayPointer_Serial ? NV_DATA_S(x)
                                                               : N_VGetArrayPointer(x);
}

/* SUNMatGetID(A), with the same shortcut for the dense and sparse types. */
static inline SUNMatrix_ID lgnMatID(SUNMatrix A)
{
  if (A->ops->getid == SUNMatGetID_Dense) return SUNMATRIX_DENSE;
  if (A->ops->getid == SUNMatGetID_Sparse) return SUNMATRIX_SPARSE;
  return SUNMatGetID(A);
}

/* Is A a SUNSparseMatrix? */
static inline sunbooleantype lgnMatIsSparse(SUNMatrix A)
{
  return lgnMatID(A) == SUNMATRIX_SPARSE;
}

/* y = A x (add: y += A x) for a dense or sparse (CSC or CSR) A; y must not
 * overlap x or A's data. */
void lgnMatvec(SUNMatrix A, const sunrealtype *x, sunrealtype *y,
               sunbooleantype add);
/* y = A^T x (add: y += A^T x). */
void lgnMatTvec(SUNMatrix A, const sunrealtype *x, sunrealtype *y,
                sunbooleantype add);
/* Zero a dense matrix; empty a sparse one (no stored entries). */
void lgnMatClear(SUNMatrix A);
/* Does A hold no entry (a sparse matrix as Lignum passes it to a callback,
 * index pointers 0)? Always false for a dense matrix. */
sunbooleantype lgnMatIsEmpty(SUNMatrix A);
/* A += W for two sparse matrices of one type (CSC or CSR) and size: the
 * helpers' rule for sparse matrices (lignum_bodies.h, "Matrices"). Where
 * W's pattern lies within A's the values are added in place; otherwise A
 * gets the union of the patterns (each compressed column or row sorted by
 * index) and is reallocated. LGN_SUCCESS or LGN_MEM_FAIL (A unchanged). */
int lgnSparseAdd(SUNMatrix A, SUNMatrix W);
/* *W as an empty sparse matrix of A's type and size (made, or made again
 * when A's type or size differs; SUNMatDestroy frees it): the work matrix
 * a helper writes its term into before lgnSparseAdd. NULL if out of
 * memory. */
SUNMatrix lgnSparseWorkLike(SUNMatrix *W, SUNMatrix A);
/* Are all n entries of x finite? */
sunbooleantype lgnAllFinite(const sunrealtype *x, sunindextype n);

#endif
