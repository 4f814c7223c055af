/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The only C code of the Fortran interface (library lignum_fortran):
 *  - the C streams stdout and stderr as functions, for LGNSetErrFile and
 *    LGNPrintAllStats (stdout/stderr are macros or variables of the C
 *    library, not portably reachable from Fortran);
 *  - compile-time checks of the type mapping that flignum_mod and
 *    flignum_sundials_mod hard-code: sunrealtype = real(c_double),
 *    sunindextype = integer(c_int64_t), and enums the size of an int.
 * ---------------------------------------------------------------------------*/

#include <stdint.h>
#include <stdio.h>

#include <lignum/lignum.h>

FILE *FLGNStdout(void);
FILE *FLGNStderr(void);

_Static_assert(sizeof(sunrealtype) == sizeof(double),
               "flignum_mod maps sunrealtype to real(c_double)");
_Static_assert(sizeof(sunindextype) == sizeof(int64_t),
               "flignum_mod maps sunindextype to integer(c_int64_t)");
_Static_assert(sizeof(LGNGroupKind) == sizeof(int) &&
                 sizeof(SUNOutputFormat) == sizeof(int),
               "flignum_mod maps C enums to integer(c_int)");

/* The C stream stdout. */
FILE *FLGNStdout(void) { return stdout; }

/* The C stream stderr. */
FILE *FLGNStderr(void) { return stderr; }
