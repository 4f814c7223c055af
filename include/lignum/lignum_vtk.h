/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Trajectories for ParaView: the bodies' poses at output times as VTK XML
 * PolyData files (.vtp, one per output time) and a ParaView collection
 * (.pvd) that lists them with their times. Pure C, no dependency.
 *
 *   w = LGNVtk_Create(G, "run/chain");          bodies: the group's leaves
 *   LGNVtk_SetCylinder(w, k, 0.02, 1.0);         shapes in the body frame
 *   LGNVtk_AddFrame(w, k, r, R, 0.1);            joint frames (axes)
 *   loop: LGNSolve(...); LGNVtk_Write(w, t, q);  run/chain_000000.vtp ...
 *   LGNVtk_Destroy(&w);                          run/chain.pvd is complete
 *
 * Each file holds one PolyData: the shapes' triangles moved to the bodies'
 * poses (cell data "body": the body's number, -1 for frames on the ground),
 * the frames as three lines each (cell data "axis": 0, 1, 2 for x, y, z),
 * and the poses themselves as field data "pose" (7 per body: the position
 * and the unit quaternion (w, x, y, z)) and "time". Data arrays are
 * written in VTK's binary (base64) encoding, Float64: exact.
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_VTK_H
#define LIGNUM_VTK_H

#include <lignum/lignum.h>

#ifdef __cplusplus
extern "C" {
#endif

/** A writer of trajectories (opaque). */
typedef struct LGNVtkRec *LGNVtk;

/** A writer for the bodies of group G: its leaves of kind R^3 x SO(3) or
 *  SE(3) (q of each: x, then the unit quaternion w, x, y, z), numbered from
 *  0 in the order of q; other leaves (R^n, SO(3)) are not drawn. Files are
 *  basename_NNNNNN.vtp (NNNNNN: the output's number) and basename.pvd,
 *  rewritten after each output so that it always lists the files written.
 *  Bodies have no shape until one is set (then only their pose is
 *  written). Messages go to stderr (LGNVtk_SetErrHandlerFn).
 *  @param G the group of the integrator (not copied: keep it alive)
 *  @param basename path and file name prefix (copied)
 *  @return the writer, or NULL (G or basename NULL or empty, no body in G,
 *          memory). */
LGN_EXPORT LGNVtk LGNVtk_Create(LGNGroup G, const char *basename);

/** Free the writer (the files stay); sets *w to NULL. */
LGN_EXPORT void LGNVtk_Destroy(LGNVtk *w);

/** Where the writer's messages go (as LGNSetErrHandlerFn). */
LGN_EXPORT int LGNVtk_SetErrHandlerFn(LGNVtk w, LGNErrHandlerFn ehfun, void *eh_data);

/** The number of bodies drawn (leaves R^3 x SO(3) or SE(3)). */
LGN_EXPORT int LGNVtk_GetNumBodies(LGNVtk w, int *nbodies);

/** Body k is a box of edge lengths lx, ly, lz centred at its origin, edges
 *  along its axes (12 triangles).
 *  @return LGN_SUCCESS, LGN_ILL_INPUT (w NULL, k out of range, a length
 *          not positive and finite), LGN_MEM_FAIL. */
LGN_EXPORT int LGNVtk_SetBox(LGNVtk w, int k, sunrealtype lx, sunrealtype ly, sunrealtype lz);

/** Body k is a solid cylinder of this radius and length along its z axis,
 *  centred at its origin (24 sides, closed).
 *  @return as LGNVtk_SetBox. */
LGN_EXPORT int LGNVtk_SetCylinder(LGNVtk w, int k, sunrealtype radius, sunrealtype length);

/** Body k is a sphere of this radius centred at its origin (a UV sphere,
 *  12 x 24 facets).
 *  @return as LGNVtk_SetBox. */
LGN_EXPORT int LGNVtk_SetSphere(LGNVtk w, int k, sunrealtype radius);

/** Body k is a triangle mesh given in its body frame: npoints points
 *  (3 coordinates each) and ntriangles triangles (3 point numbers each,
 *  from 0). Copied.
 *  @return LGN_SUCCESS, LGN_ILL_INPUT (w NULL, k out of range, npoints or
 *          ntriangles < 1, points or triangles NULL, a point not finite, a
 *          point number out of range), LGN_MEM_FAIL. */
LGN_EXPORT int LGNVtk_SetMesh(LGNVtk w, int k, int npoints, const sunrealtype *points,
                              int ntriangles, const int *triangles);

/** A frame (e.g. of a joint) drawn as its three axes of length size: at r
 *  with axes the columns of R (row-major 3x3, R[3*i+j]; NULL: the body's
 *  axes), in the frame of body k, or fixed in space for k = -1 (the
 *  ground, LGN_GROUND of lignum_joints.h).
 *  @return LGN_SUCCESS, LGN_ILL_INPUT (w NULL, k out of range, r NULL, a
 *          value not finite, size not positive), LGN_MEM_FAIL. */
LGN_EXPORT int LGNVtk_AddFrame(LGNVtk w, int k, const sunrealtype r[3], const sunrealtype R[9],
                               sunrealtype size);

/** Write the output at time t: the bodies at the poses of q (nq entries of
 *  the group, e.g. the q of LGNSolve; across MPI ranks this rank's part,
 *  its bodies and ghosts, written by each rank under its own basename) into
 *  the next .vtp file, and the .pvd collection with it. Times should
 *  increase (ParaView orders by them).
 *  @return LGN_SUCCESS, LGN_ILL_INPUT (w NULL, q NULL or of another length,
 *          t or an entry of q not finite), LGN_MEM_FAIL, LGN_IO_FAIL (a
 *          file could not be written; nothing is counted). */
LGN_EXPORT int LGNVtk_Write(LGNVtk w, sunrealtype t, N_Vector q);

#ifdef __cplusplus
}
#endif

#endif
