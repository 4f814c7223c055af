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

/* y = A x (add: y += A x) for a dense or sparse (CSC or CSR) A. */
void lgnMatvec(SUNMatrix A, const sunrealtype *x, sunrealtype *y,
               sunbooleantype add);
/* y = A^T x (add: y += A^T x). */
void lgnMatTvec(SUNMatrix A, const sunrealtype *x, sunrealtype *y,
                sunbooleantype add);
/* Zero a dense matrix; empty a sparse one (no stored entries). */
void lgnMatClear(SUNMatrix A);
/* Are all n entries of x finite? */
sunbooleantype lgnAllFinite(const sunrealtype *x, sunindextype n);

#endif
