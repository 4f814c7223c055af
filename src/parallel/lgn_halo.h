/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header: the halo of ghost bodies (lgn_halo.c; public part in
 * lignum_halo.h). A pure helper over MPI and the group's body offsets: it
 * knows nothing of the integrator. A rank's local arrays hold its owned
 * bodies first, then its ghosts, in the order of its group's leaves.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_HALO_H
#define LGN_HALO_H

#include <lignum/lignum_config.h>

#if defined(LGN_HAVE_MPI)
#include <lignum/lignum_halo.h>

/* The group the halo was made for. */
LGNGroup lgnHaloGroup(const LGNHalo H);

/* The owned bodies' lengths in q and v (the first entries of the arrays). */
void lgnHaloOwnedLengths(const LGNHalo H, sunindextype *nq_own, sunindextype *nv_own);

/* x's ghost entries <- their owners' entries (kind LGN_HALO_CONFIGURATION:
 * x has nq entries, LGN_HALO_VELOCITY: nv). Collective. */
void lgnHaloForward(LGNHalo H, int kind, sunrealtype *x);

/* The reverse of the velocity-kind forward: owned[i] += the entries other
 * ranks hold in their ghost rows of this rank's bodies (their src), i.e.
 * the sum over the ranks of a quantity each rank computed in part. src is
 * this rank's nv-array (its ghost rows are sent), owned its nv_own owned
 * rows (may be src itself). Sums in a fixed order (neighbours by rank, then
 * the order of their lists). Collective. */
void lgnHaloReverse(LGNHalo H, const sunrealtype *src, sunrealtype *owned);

/* The ghosts' entries of a configuration q <- the identity (x = 0, unit
 * quaternion), of a velocity-type v <- 0: placeholders until the owners'
 * values arrive (either may be NULL). */
void lgnHaloClearGhosts(const LGNHalo H, sunrealtype *q, sunrealtype *v);

/* The communicator of the halo (a duplicate of the one given). */
MPI_Comm lgnHaloComm(const LGNHalo H);
#endif

#endif
