/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Argument checks shared by the joint and body sets (lgn_argcheck.h); the
 * integrator's own vector check, which names the public function the user
 * called, is lgnCheckVector in lgn_mem.c.
 * ---------------------------------------------------------------------------*/

#include <math.h>

#include "lgn_argcheck.h"
#include "lgn_parallel.h"

int lgnCheckVec3(const LGNErrSink *sink, const sunrealtype *x, const char *name,
                 const char *func)
{
  if (x == NULL) {
    lgnReport(sink, LGN_ILL_INPUT, func, "%s = NULL illegal.", name);
    return LGN_ILL_INPUT;
  }
  if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2])) {
    lgnReport(sink, LGN_ILL_INPUT, func, "%s = (%g, %g, %g) illegal: not finite.", name,
              (double)x[0], (double)x[1], (double)x[2]);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int lgnCheckSerialVector(const LGNErrSink *sink, N_Vector x, sunindextype len,
                         const char *name, const char *func)
{
  if (x == NULL || (N_VGetArrayPointer(x) == NULL && len > 0) || lgnLocalLength(x) != len) {
    lgnReport(sink, LGN_ILL_INPUT, func, "%s is NULL or does not have length %lld.", name,
              (long long)len);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}
