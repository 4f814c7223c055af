/* -----------------------------------------------------------------------------
 * Planar mechanisms on the planar groups (lignum_planar.h), shared by the
 * planar tests, the group-choice benchmark and the example:
 *   Andrews' squeezing mechanism (Test Set for IVP Solvers; Hairer and
 *     Wanner II, VII.7): 7 bodies, 10 revolute joints (3 of them at the
 *     point E), a spring and a motor torque; the joint angles of the Test
 *     Set's R^7 formulation follow from the body angles;
 *   a slider-crank: crank, rod and slider under gravity, a rotational
 *     spring-damper on the crank and a spring-damper on the slider; and the
 *     same slider-crank written separately on R^3 in the joint coordinates
 *     (phi, psi, s) with hand-derived M, g, Phi and B (the comparison).
 * The glue (every model callback from the body and joint sets, plus the
 * motor torque the helpers lack) is planar_set_model, until the model
 * object lands.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_PLANAR_MECHANISMS_H
#define LGN_PLANAR_MECHANISMS_H

#include <lignum/lignum.h>
#include <lignum/lignum_planar.h>

typedef struct {
  int nb;                 /* bodies                                   */
  LGNGroup G;             /* nb copies of the body group              */
  LGNBodies bodies;
  LGNJoints joints;
  int torque_body;        /* a body driven by a constant torque, or -1 */
  sunrealtype torque;
  sunindextype m;         /* constraint rows                          */
} PlanarMechanism;

/* Build Andrews' mechanism on bodies of group `body` (SE(2) or R^2 x
 * SO(2), referenced): q0 (21 reals) and v0 (21) its consistent start (the
 * Test Set's, at rest). Returns 0 or -1. */
int planar_andrews(LGNGroup body, PlanarMechanism *pm, sunrealtype *q0, sunrealtype *v0);

/* The Test Set's 7 joint angles (beta, Theta, gamma, Phi, delta, Omega,
 * epsilon) and their rates from the planar q, v. */
void planar_andrews_angles(const PlanarMechanism *pm, const sunrealtype *q,
                           const sunrealtype *v, double ang[7], double rate[7]);

/* The Test Set's reference at t = 0.03: angles and rates. */
extern const double PLANAR_ANDREWS_Q_REF[7], PLANAR_ANDREWS_V_REF[7];

/* Build the slider-crank (9 velocities, 8 rows) at crank angle 0.3 rad and
 * crank rate 6 rad/s (consistent). Returns 0 or -1. */
int planar_slider_crank(LGNGroup body, PlanarMechanism *pm, sunrealtype *q0,
                        sunrealtype *v0);

/* Its joint coordinates (phi, psi, s) from the planar q. */
void planar_slider_crank_coords(const sunrealtype *q, double x[3]);

/* Install every callback of pm in mem (mass, force, constraints,
 * curvature, stiffness, damping; Phi_t with drivers). Returns 0 or the
 * first failing flag. */
int planar_set_model(void *mem, PlanarMechanism *pm);

/* Free the sets and the product group (not the body group). */
void planar_free(PlanarMechanism *pm);

/* The slider-crank on R^3, q = (phi, psi, s): install its callbacks in mem
 * (group R^3 of the caller) and give its consistent start. */
int rn_slider_crank_set_model(void *mem);
void rn_slider_crank_start(sunrealtype q0[3], sunrealtype v0[3]);

#endif

/* One integration: generalized-alpha (bdf_order 0: rho_inf 0.9, exact
 * kinematics, i.e. the modified generalized-alpha) or BDF of that maximal
 * order; adaptive (rtol = atol = tol) or fixed steps h (BDF: its history
 * first built under error control at tol 1e-12 to t = t_start). Index 3,
 * dense. */
typedef struct {
  int bdf_order;
  int adaptive;
  double tol, h, t_start, t_end;
} PlanarRun;

typedef int (*PlanarSetModelFn)(void *mem, void *model);

/* Integrate the model (installed by set_model with its group G and m
 * rows) from (q0, v0) at t = 0 to run->t_end: q, v at the end, the steps
 * and Newton iterations taken (may be NULL). Returns 0 or the flag. */
int planar_integrate(SUNContext ctx, LGNGroup G, sunindextype m, PlanarSetModelFn set_model,
                     void *model, const sunrealtype *q0, const sunrealtype *v0,
                     const PlanarRun *run, sunrealtype *q, sunrealtype *v, long *nsteps,
                     long *nniters);

/* set_model functions for planar_integrate: a PlanarMechanism, and the R^3
 * slider-crank (model ignored). */
int planar_set_model_fn(void *mem, void *model);
int rn_slider_crank_set_model_fn(void *mem, void *model);
