/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header: what the integrator and the joint and body helpers may
 * know about the built-in groups beyond their public ops.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_GROUP_IMPL_H
#define LGN_GROUP_IMPL_H

#include <lignum/lignum_group.h>

/* The factors of a product group and their offsets in q and v (not copies).
 * Returns 0 when G is a product, -1 otherwise. */
int lgnGroupProductFactors(LGNGroup G, int *nf, const LGNGroup **factors,
                           const sunindextype **qoff, const sunindextype **voff);

/* The rigid bodies of G: its leaves in order, each R^3 x SO(3) or SE(3)
 * (a product of products is flattened). With qoff, voff and se3 not NULL
 * (room for the count), also each body's offsets in q and v and whether it
 * is an SE(3) body. Returns the count, or -1 if a leaf is another group.
 * Shared by the joint and the body helpers. */
int lgnGroupRigidBodies(LGNGroup G, sunindextype *qoff, sunindextype *voff,
                        sunbooleantype *se3);

#endif
