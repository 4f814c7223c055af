/* -----------------------------------------------------------------------------
 * The heavy top runs that test_ggl (the BDF family) and test_ggl_newmark
 * (the Newmark family) share: Brüls and Cardona's top on R^3 x SO(3) (mass
 * 15, centre of mass at X = e_y, a spherical joint at the origin, Omega0 =
 * (0, 150, -4.61538)) installed with the model object (lignum_model.h) on a
 * dense integrator of n unknowns, and the measures both tests take.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#ifndef LGN_TEST_HEAVY_TOP_RUN_H
#define LGN_TEST_HEAVY_TOP_RUN_H

#include <lignum/lignum.h>
#include <lignum/lignum_model.h>

#include "lgn_reference.h"

/* A heavy top run; n = nv + 2m = 12 unknowns under GGL (nalg rows of
 * multipliers), 9 otherwise. */
typedef struct {
  SUNContext ctx;
  LGNGroup G;
  LGNBodies bodies;
  LGNJoints joints;
  LGNModel model;
  N_Vector q, v, y, lambda, phi;
  SUNMatrix A, B;
  SUNLinearSolver LS;
  void *mem;
} Run;

/* The top at its initial state, attached to a new integrator (outputs: the
 * step's own values, neither consistent nor projected), constraint
 * formulation index, a dense LU of n unknowns. Returns a Lignum flag. */
int RunCreate(Run *r, SUNContext ctx, int index, int n);
void RunFree(Run *r);

/* |Phi(q)|_inf and |B(q) v|_inf at the run's state. */
void Violations(Run *r, double *phi, double *bv);

/* The errors of the centre of mass, of the velocities (u, Omega) and of the
 * multipliers against the reference. */
void Errors(Run *r, const LGNRefHeavyTop *ref, double e[3]);

/* Slope of log(y) against log(x). */
double Fit(const double *x, const double *y, int n);

#endif
