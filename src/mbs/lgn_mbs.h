/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header of the multibody helpers: what the body and joint sets
 * (lgn_bodies.c, lgn_joints.c) tell the model object (lgn_mbs_model.c)
 * beyond their public headers.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_MBS_H
#define LGN_MBS_H

#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>

/* The group a set was created on (NULL for a NULL set). */
LGNGroup lgnBodiesGroup(LGNBodies B);
LGNGroup lgnJointsGroup(LGNJoints J);

#endif
