/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The public planar elements of lignum_planar.h: each finds the planar part
 * of its body or joint set (lgn_bodies.c, lgn_joints.c) and adds the element
 * there (lgn_planar_bodies.c, lgn_planar_joints.c); a spatial or NULL set
 * is refused with LGN_ILL_INPUT through its sink (stderr for NULL).
 * ---------------------------------------------------------------------------*/

#include "lgn_planar.h"

#define NOT_PLANAR_J "J: a planar joint needs a joint set on a planar group " \
                     "(SE(2), R^2 x SO(2) or a product of them)."
#define NOT_PLANAR_B "B: a planar element needs a body set on a planar group " \
                     "(SE(2), R^2 x SO(2) or a product of them)."

static lgnPlanarJoints *PlanarJoints(LGNJoints J, const char *func)
{
  lgnPlanarJoints *P = lgnJointsPlanarPart(J);
  if (P == NULL)
    lgnReport(lgnJointsSink(J), LGN_ILL_INPUT, func, "%s",
              J == NULL ? "J = NULL illegal." : NOT_PLANAR_J);
  return P;
}

static lgnPlanarBodies *PlanarBodies(LGNBodies B, const char *func)
{
  lgnPlanarBodies *P = lgnBodiesPlanarPart(B);
  if (P == NULL)
    lgnReport(lgnBodiesSink(B), LGN_ILL_INPUT, func, "%s",
              B == NULL ? "B = NULL illegal." : NOT_PLANAR_B);
  return P;
}

int LGNBodies_SetPlanarMass(LGNBodies B, int k, sunrealtype m, sunrealtype J)
{
  lgnPlanarBodies *P = PlanarBodies(B, __func__);
  return P != NULL ? lgnPlanarBodiesSetMass(P, k, m, J, __func__) : LGN_ILL_INPUT;
}

int LGNBodies_AddPlanarSpringDamper(LGNBodies B, int a, const sunrealtype sa[2], int b,
                                    const sunrealtype sb[2], sunrealtype k, sunrealtype c,
                                    sunrealtype L0)
{
  lgnPlanarBodies *P = PlanarBodies(B, __func__);
  return P != NULL ? lgnPlanarBodiesAddSpring2(P, a, sa, b, sb, k, c, L0, __func__)
                   : LGN_ILL_INPUT;
}

int LGNBodies_AddPlanarRotationalSpringDamper(LGNBodies B, int a, int b, sunrealtype kr,
                                              sunrealtype cr, sunrealtype theta0)
{
  lgnPlanarBodies *P = PlanarBodies(B, __func__);
  return P != NULL ? lgnPlanarBodiesAddRotSpring(P, a, b, kr, cr, theta0, __func__)
                   : LGN_ILL_INPUT;
}

int LGNJoints_AddPlanarRevolute(LGNJoints J, int a, const sunrealtype sa[2], int b,
                                const sunrealtype sb[2])
{
  lgnPlanarJoints *P = PlanarJoints(J, __func__);
  return P != NULL ? lgnPlanarJointsAddRevolute2(P, a, sa, b, sb, __func__) : LGN_ILL_INPUT;
}

int LGNJoints_AddPlanarPrismatic(LGNJoints J, int a, const sunrealtype sa[2],
                                 const sunrealtype axis_a[2], int b, const sunrealtype sb[2],
                                 sunrealtype theta0)
{
  lgnPlanarJoints *P = PlanarJoints(J, __func__);
  return P != NULL ? lgnPlanarJointsAddPrismatic(P, a, sa, axis_a, b, sb, theta0, __func__)
                   : LGN_ILL_INPUT;
}

int LGNJoints_AddPlanarRotationDriver(LGNJoints J, int a, int b, LGNDriveFn f,
                                      void *drive_data)
{
  lgnPlanarJoints *P = PlanarJoints(J, __func__);
  return P != NULL ? lgnPlanarJointsAddRotationDriver(P, a, b, f, drive_data, __func__)
                   : LGN_ILL_INPUT;
}

int LGNJoints_AddPlanarTranslationDriver(LGNJoints J, int a, const sunrealtype sa[2],
                                         const sunrealtype axis_a[2], int b,
                                         const sunrealtype sb[2], LGNDriveFn f,
                                         void *drive_data)
{
  lgnPlanarJoints *P = PlanarJoints(J, __func__);
  return P != NULL ? lgnPlanarJointsAddTranslationDriver(P, a, sa, axis_a, b, sb, f, drive_data,
                                                         __func__)
                   : LGN_ILL_INPUT;
}
