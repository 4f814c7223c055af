/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header of lgn_methods.c: the admissibility check of a method's
 * parameters (a pure helper, no integrator record).
 * ---------------------------------------------------------------------------*/

#ifndef LGN_METHODS_H
#define LGN_METHODS_H

#include <lignum/lignum.h>

/* LGN_SUCCESS if the step is well defined with these parameters; otherwise
 * LGN_ILL_INPUT and *why says which condition fails. */
int lgnCheckMethodParams(sunrealtype alpha_m, sunrealtype alpha_f,
                         sunrealtype beta, sunrealtype gamma,
                         const char **why);

#endif
