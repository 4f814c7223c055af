/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header of lgn_petsc.c, the direct solve through PETSc and MUMPS
 * (its constructor LGNLinSol_PETSc is public, lignum_petsc.h): what the
 * rest of the library may ask of it. Without PETSc (LGN_ENABLE_PETSC=OFF)
 * no solver is one of these. A pure helper: no integrator record.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_PETSC_H
#define LGN_PETSC_H

#include <lignum/lignum.h>
#include <lignum/lignum_config.h>

#if defined(LGN_HAVE_PETSC)
/* The order N of the matrices LS was created for if LS is an
 * LGNLinSol_PETSc solver; else -1. */
sunindextype lgnPetscLUSize(SUNLinearSolver LS);
#else
static inline sunindextype lgnPetscLUSize(SUNLinearSolver LS)
{
  (void)LS;
  return -1;
}
#endif

#endif
