/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The step-failure policy the error-controlled loops of every family share
 * (lgn_newmark_adapt.c, lgn_bdf.c), on the model of IDA's IDAHandleNFlag: a Newton
 * iteration that did not converge, a singular iteration matrix (the setup
 * is recoverable inside the loops: lgnLsSetup returns LGN_RECOVERABLE) or a
 * callback that asked for a retry is retried with the step cut by
 * LGN_CUT_NFAIL, up to maxncf times per step and down to hmin; then the run
 * stops with the state at t_n kept and one flag on every rank.
 * ---------------------------------------------------------------------------*/

#include "lgn_impl.h"

/* LGN_RECOVERABLE: retry the step with h * LGN_CUT_NFAIL (ncf counted);
 * any other flag is final and reported: LGN_CONV_FAILURE, LGN_LSETUP_FAIL
 * (with the diagnosis of the singular matrix) or LGN_REPTD_CALLBACK_ERR. */
int lgnHandleNFlag(LGNMem mem, int flag, sunrealtype h, int *ncf)
{
  /* singular on any rank: the same flag on all */
  const sunbooleantype singular =
      lgnMaxAll(mem, flag == LGN_RECOVERABLE && mem->ls.last_flag != 0 ? SUN_RCONST(1.0)
                                                                         : SUN_RCONST(0.0)) >
      SUN_RCONST(0.0);
  int out;
  (*ncf)++;
  if (*ncf < mem->ec.maxncf && h > mem->ec.hmin) return LGN_RECOVERABLE;
  out = flag == LGN_CONV_FAILURE ? LGN_CONV_FAILURE
      : singular                 ? LGN_LSETUP_FAIL
                                 : LGN_REPTD_CALLBACK_ERR;
  LGN_ERROR(mem, out,
            MSG_TIME "%s %d times, the last with h = %g%s (the state at t "
            "is kept).%s", (double)mem->tn,
            flag == LGN_CONV_FAILURE ? "the Newton iteration failed to converge"
            : singular ? "the iteration matrix was singular"
                       : "a callback failed recoverably",
            *ncf, (double)h, h <= mem->ec.hmin ? " at the minimum step size" : "",
            singular ? mem->diag.text : "");
  return out;
}
