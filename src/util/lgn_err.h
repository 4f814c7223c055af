/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header: where error messages go (an LGNErrSink) and the one
 * function that formats and delivers them. It knows nothing of the
 * integrator's memory record, so every object of the library (the
 * integrator, a joint set, the pure helpers) reports the same way.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_ERR_H
#define LGN_ERR_H

#include <stdarg.h>
#include <stdio.h>

#include <lignum/lignum.h>

/* A destination for messages: the user's handler if set, else a file (NULL:
 * silent). The default is stderr. */
typedef struct {
  LGNErrHandlerFn ehfun;
  void *eh_data;
  FILE *errfp;
} LGNErrSink;

/* The sink of a new object: no handler, stderr. */
void lgnErrSinkInit(LGNErrSink *sink);

/* Format the message into a bounded buffer and hand it to the sink's
 * handler (sink == NULL: the default handler on stderr). */
void lgnReport(const LGNErrSink *sink, int error_code, const char *func,
               const char *msgfmt, ...);
void lgnReportV(const LGNErrSink *sink, int error_code, const char *func,
                const char *msgfmt, va_list ap);

/* The default handler: "[LGN ERROR]  function\n  message" on the FILE in data. */
void lgnDefaultErrHandler(int error_code, const char *module,
                          const char *function, const char *msg, void *data);

#endif
