/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header: the argument checks shared by the objects that report
 * through an error sink of their own (a joint set, a body set). Each
 * reports a refused argument, named, as an error of the public function
 * func and returns LGN_ILL_INPUT; LGN_SUCCESS otherwise.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_ARGCHECK_H
#define LGN_ARGCHECK_H

#include <nvector/nvector_serial.h>

#include "lgn_err.h"

/* A point, axis or vector of R^3 (named name): not NULL, finite. */
int lgnCheckVec3(const LGNErrSink *sink, const sunrealtype *x, const char *name,
                 const char *func);

/* A vector argument (named name): serial data of length len. */
int lgnCheckSerialVector(const LGNErrSink *sink, N_Vector x, sunindextype len,
                         const char *name, const char *func);

#endif
