/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header: what the integrator and the joint helpers may know about
 * the built-in groups beyond their public ops.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_GROUP_IMPL_H
#define LGN_GROUP_IMPL_H

#include <lignum/lignum_group.h>

/* The factors of a product group and their offsets in q and v (not copies).
 * Returns 0 when G is a product, -1 otherwise. */
int lgnGroupProductFactors(LGNGroup G, int *nf, const LGNGroup **factors,
                           const sunindextype **qoff, const sunindextype **voff);

#endif
