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
#include "lgn_impl.h"

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

void lgnProcessError(LGNMem mem, int error_code, int line, const char *func,
                     const char *file, const char *msgfmt, ...)
{
  va_list ap;
  (void)line;
  (void)file;
  va_start(ap, msgfmt);
  lgnReportV(mem == NULL ? NULL : &mem->err, error_code, func, msgfmt, ap);
  va_end(ap);
}

static const char *CallbackName(LGNCallbackId cb)
{
  static const char *names[LGN_CB_COUNT] = {
    "mass matrix", "force", "constraint", "constraint Jacobian",
    "stiffness", "damping", "curvature", "constraint force", "Lie group"};
  return names[cb];
}

static int UnrecoverableFlag(LGNCallbackId cb)
{
  switch (cb) {
  case LGN_CB_MASS:       return LGN_MASS_FAIL;
  case LGN_CB_FORCE:      return LGN_FORCE_FAIL;
  case LGN_CB_CONSTR:     return LGN_CONSTR_FAIL;
  case LGN_CB_CONSTR_JAC:
  case LGN_CB_CONSTR_FORCE: return LGN_CONSTR_JAC_FAIL;
  case LGN_CB_GROUP:      return LGN_GROUP_FAIL;
  default:                return LGN_TANGENT_FAIL;
  }
}

/* Map the return value of a user callback (0 ok, > 0 recoverable, < 0 fatal)
 * to a flag and report it. With a fixed step size a recoverable failure
 * cannot be cured by a smaller step, so it is reported as
 * LGN_REPTD_CALLBACK_ERR; the state at t_n stays intact either way. */
int lgnCallbackFlag(LGNMem mem, LGNCallbackId cb, int retval, const char *func)
{
  int flag;
  if (retval == 0) return LGN_SUCCESS;
  if (retval > 0) {
    flag = LGN_REPTD_CALLBACK_ERR;
    lgnProcessError(mem, flag, __LINE__, func, __FILE__,
                    MSG_TIME "the %s function failed recoverably (returned %d)"
                    " and the fixed step size cannot be reduced.",
                    (double)mem->tn, CallbackName(cb), retval);
  } else {
    flag = UnrecoverableFlag(cb);
    lgnProcessError(mem, flag, __LINE__, func, __FILE__,
                    MSG_TIME "the %s function failed unrecoverably"
                    " (returned %d).",
                    (double)mem->tn, CallbackName(cb), retval);
  }
  return flag;
}
