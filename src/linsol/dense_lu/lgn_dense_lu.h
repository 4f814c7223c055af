/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header of lgn_dense_lu.c, Lignum's dense LU linear solver (its
 * constructor LGNLinSol_Dense is public, lignum_ls.h): what the rest of the
 * library may ask of it. A pure helper: no integrator record.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_DENSE_LU_H
#define LGN_DENSE_LU_H

#include <lignum/lignum.h>

/* The order N of the matrices LS was created for if LS is an
 * LGNLinSol_Dense solver; else -1. */
sunindextype lgnDenseLUSize(SUNLinearSolver LS);

#endif
