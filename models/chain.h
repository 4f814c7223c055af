/* -----------------------------------------------------------------------------
 * Lignum study models: the N-body spherical pendulum chain.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * N identical rods (solid cylinders, length 1 m, mass 1 kg, radius 0.02 m,
 * axis = body z) joined by spherical joints, the top of rod 0 to the ground
 * at the origin, under gravity g = (0, 0, -9.81). Initial configuration, at
 * rest: rod k (k = 0..N-1) points from its top to its bottom along
 *   d_k = (sin th_k cos ph_k, sin th_k sin ph_k, -cos th_k),
 *   th_k = (pi/2)(1 - k/N),   ph_k = 0.3 k/N,
 * i.e. the chain starts horizontal at the support and bends down towards the
 * vertical, slightly twisted out of the x-z plane so the motion is spatial.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_EXAMPLES_CHAIN_H
#define LGN_EXAMPLES_CHAIN_H

#include "rigid_bodies.h"

/* The chain of n rods with its joints and initial state. */
RigidSystem *chain_create(int n, RigidFormulation formulation, SUNContext ctx);

#endif
