/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header of lgn_methods.c: the admissibility check of a method's
 * parameters, and the Lagrange basis of the BDF family's polynomials (pure
 * helpers, no integrator record).
 * ---------------------------------------------------------------------------*/

#ifndef LGN_METHODS_H
#define LGN_METHODS_H

#include <lignum/lignum.h>

/* LGN_SUCCESS if the step is well defined with these parameters; otherwise
 * LGN_ILL_INPUT and *why says which condition fails. */
int lgnCheckMethodParams(sunrealtype alpha_m, sunrealtype alpha_f,
                         sunrealtype beta, sunrealtype gamma,
                         const char **why);

/* The Lagrange basis on the nodes tau[0..n] at t: l[j] = l_j(t) and, if dl
 * is not NULL, dl[j] = l_j'(t). */
void lgnLagrangeBasis(const sunrealtype *tau, int n, sunrealtype t, sunrealtype *l,
                      sunrealtype *dl);

#endif
