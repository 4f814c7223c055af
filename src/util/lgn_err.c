/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Error reporting: one path (lgnProcessError) formats the message into a
 * bounded buffer and hands it to the replaceable handler; lgnCallbackFlag maps
 * a user callback's return value to a flag with a message naming the callback.
 * ---------------------------------------------------------------------------*/

#include <stdio.h>
#include <string.h>

#include "lgn_err.h"

#define LGN_MSG_LEN 512

void lgnErrSinkInit(LGNErrSink *sink)
{
  sink->ehfun   = NULL;
  sink->eh_data = NULL;
  sink->errfp   = stderr;
}

/* The default handler: "[LGN ERROR]  function\n  message" on errfp. */
void lgnDefaultErrHandler(int error_code, const char *module,
                          const char *function, const char *msg, void *data)
{
  FILE *fp = (FILE *)data;
  (void)module;
  if (fp == NULL) return;
  fprintf(fp, "\n[LGN %s]  %s\n  %s\n\n",
          error_code >= 0 ? "WARNING" : "ERROR", function, msg);
}

void lgnReportV(const LGNErrSink *sink, int error_code, const char *func,
                const char *msgfmt, va_list ap)
{
  char msg[LGN_MSG_LEN];
  vsnprintf(msg, sizeof msg, msgfmt, ap);
  if (sink == NULL) {
    /* no object: nowhere to find a handler, so write to stderr */
    lgnDefaultErrHandler(error_code, "LGN", func, msg, stderr);
  } else if (sink->ehfun != NULL) {
    sink->ehfun(error_code, "LGN", func, msg, sink->eh_data);
  } else {
    lgnDefaultErrHandler(error_code, "LGN", func, msg, sink->errfp);
  }
}

void lgnReport(const LGNErrSink *sink, int error_code, const char *func,
               const char *msgfmt, ...)
{
  va_list ap;
  va_start(ap, msgfmt);
  lgnReportV(sink, error_code, func, msgfmt, ap);
  va_end(ap);
}

