/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * One error-controlled step (LGN_STEP_ADAPTIVE): try h, test the local
 * error (lgn_newmark_errtest.c), accept or retry with a smaller h, and propose the
 * next h. A rejected attempt writes only the iterate, so the state at t_n
 * stays as it was, bit for bit.
 *
 *   accept when |e| <= 1, then h_new = h min(fmax, max(fmin, 0.9 e^(-1/2)))
 *   with e = max(|e_n|, |e_{n-1}|) (the larger of this step's error and the
 *   last accepted one's: an estimate that drops for one step does not
 *   propose a step that then fails; it cut the rejections on the heavy top
 *   at tol 1e-5 from 47 to 0), fmax = 2 (1 right after a rejection),
 *   fmin = 0.2, and h kept when the factor lies in [1, 1.2) (no rescaling,
 *   no new matrix for little);
 *   error-test failure: h *= max(fmin, min(0.9, 0.9 |e|^(-1/2))), from the
 *   second failure on h *= max(0.01, min(0.25, 0.9 |e|^(-1/2)));
 *   Newton failure, a singular iteration matrix or a recoverable callback
 *   error: h *= 0.25;
 *   each retried up to maxnef / maxncf times, and not below hmin.
 *
 * A stop time is landed on without a short step: within 1.1 h it is
 * reached in one step, within 2.2 h in two halves of the rest.
 *
 * Before every attempt of size h after a step of size h_old, the auxiliary
 * variable is rescaled: a_n approximates vdot(t_n + (alpha_m - alpha_f) h),
 * so its meaning depends on h, and without
 *   a_n <- vdot_n + (h / h_old) (a_n - vdot_n)
 * generalized-alpha falls to first order under frequent changes of h. The
 * rescaled a lives in a_scaled: a itself changes only when a step is accepted.
 * The Newton iteration converges to epcon times the error test's tolerances.
 * ---------------------------------------------------------------------------*/

#include <math.h>

#include "lgn_impl.h"

#define FMAX        SUN_RCONST(2.0)
#define FMIN        SUN_RCONST(0.2)
#define SAFETY      SUN_RCONST(0.9)
#define KEEP_BELOW  SUN_RCONST(1.2) /* 1 <= factor < 1.2: keep h           */
#define CUT_FAIL    SUN_RCONST(0.25)
#define CUT_MIN     SUN_RCONST(0.01) /* the largest cut after an error-test failure */
#define RESCALE_MAX SUN_RCONST(100.0) /* the largest h / h_old a is rescaled by */
#define LAND_STRETCH SUN_RCONST(1.1) /* a step lands on tstop within 10 %   */

/* The controller's factor for an error norm err: error per unit step, the
 * estimate over h, |e| / h ~ h^2 (order 2, lgn_newmark_errtest.c). */
static sunrealtype ErrorFactor(sunrealtype err)
{
  if (err <= SUN_RCONST(0.0)) return FMAX;
  return SAFETY / sqrt(err);
}

/* The smallest step error control takes: the step divides by h^2, which
 * must stay a normal number (as LGNSetStepSize requires). */
#define H_FLOOR SUN_RCONST(1.0e-150)

/* h limited to [hmin, hmax] (and the floor). */
sunrealtype lgnLimitStep(LGNMem mem, sunrealtype h)
{
  if (mem->hmax > SUN_RCONST(0.0)) h = SUNMIN(h, mem->hmax);
  return SUNMAX(SUNMAX(h, mem->hmin), H_FLOOR);
}

/* The first step size when the user gives none: the displacement by the
 * initial acceleration, h^2 |vdot_0| / 2, one error tolerance (weighted
 * norm, weights at a zero increment), and not beyond tout. */
sunrealtype lgnInitialStep(LGNMem mem, sunrealtype tout)
{
  const sunrealtype span = fabs(tout - mem->tn);
  sunrealtype h, anorm, vnorm;
  lgnErrorWeights(mem, mem->zero_nv, SUN_RCONST(1.0), mem->ewt);
  anorm = lgnWrmsNorm(mem, lgnData(mem->vdot), mem->ewt);
  vnorm = lgnWrmsNorm(mem, lgnData(mem->v), mem->ewt);
  if (anorm > SUN_RCONST(0.0))
    h = sqrt(SUN_RCONST(2.0) / anorm);
  else if (vnorm > SUN_RCONST(0.0))
    h = SUN_RCONST(1.0) / vnorm; /* a displacement of one tolerance */
  else
    h = SUN_RCONST(1.0e-3) * span;
  if (span > SUN_RCONST(0.0)) h = SUNMIN(h, span);
  if (!(h > SUN_RCONST(0.0))) h = SUN_RCONST(1.0e-6);
  return lgnLimitStep(mem, h);
}

/* The first step of an error-controlled run: the user's h0 (LGNSetInitStep)
 * or lgnInitialStep's, either at most |tout - t0|, as IDA limits its first
 * step by tstop and hmax. A step far beyond the time scale of the motion
 * can pass the error test: the estimate compares the step with a Taylor
 * increment of the same data, and both are meaningless there (a pendulum of
 * period 2 s took a first step h0 = 1e6 cut to 61 s with |e| = 1.2e-3 and
 * returned q off by 1.1 with success). */
sunrealtype lgnFirstStep(LGNMem mem, sunrealtype tout)
{
  const sunrealtype span = fabs(tout - mem->tn);
  sunrealtype h;
  if (!(mem->h0_user > SUN_RCONST(0.0))) return lgnInitialStep(mem, tout);
  h = mem->h0_user;
  if (span > SUN_RCONST(0.0)) h = SUNMIN(h, span);
  return lgnLimitStep(mem, h);
}

/* The auxiliary variable for a step of size h (header comment). */
static void RescaleAux(LGNMem mem, sunrealtype h)
{
  const sunindextype nv = mem->nv;
  const sunrealtype *a = lgnData(mem->a), *vdot = lgnData(mem->vdot);
  sunrealtype r;
  sunindextype i;
  if (!(mem->hlast > SUN_RCONST(0.0)) || h == mem->hlast) {
    mem->a_step = a;
    return;
  }
  /* a - vdot ~ (alpha_m - alpha_f) h_old vddot plus Newton's noise: the
   * controller grows h by 2 at most, but a restart of the step size (after
   * a collapse to 1e-18, or LGNSetInitStep after steps) would multiply the
   * noise by h / h_old ~ 1e9; beyond RESCALE_MAX a is taken as ~ vdot */
  r = SUNMIN(h / mem->hlast, RESCALE_MAX);
  for (i = 0; i < nv; i++) mem->a_scaled[i] = vdot[i] + r * (a[i] - vdot[i]);
  mem->a_step = mem->a_scaled;
}

/* One accepted step from tn (LGN_SUCCESS), or the flag of a failure, with
 * the state at tn as it was. A stop time is landed on exactly. */
int lgnAdaptiveStep(LGNMem mem, sunrealtype tout)
{
  sunrealtype h, err = SUN_RCONST(0.0), factor, h_wanted;
  sunbooleantype landing;
  int nef = 0, ncf = 0, flag;
  LGNStepCoeffs c;

  if (!(mem->hnext > SUN_RCONST(0.0))) {
    mem->hnext     = lgnFirstStep(mem, tout);
    mem->h0_actual = mem->hnext;
  }
  h = lgnLimitStep(mem, mem->hnext); /* the limits may have changed since */
  for (;;) {
    /* a stop time ahead: a step that would leave less than a tenth of
     * itself stretches to land on it, and one that would leave less than a
     * step (up to 1.1 h) takes half the rest, so that no landing step is
     * short (as the BDF family does, lgn_bdf.c): a short step is an
     * abrupt change of h, which generalized-alpha's rescaled a_n and its
     * multipliers follow badly. The stretch stays within hmax. */
    h_wanted = h;
    landing  = mem->tstop_set && mem->tn + h * LAND_STRETCH >= mem->tstop &&
               !(mem->hmax > SUN_RCONST(0.0) && mem->tstop - mem->tn > mem->hmax);
    if (landing)
      h = mem->tstop - mem->tn;
    else if (mem->tstop_set && mem->tn + SUN_RCONST(2.0) * h * LAND_STRETCH > mem->tstop)
      h = SUN_RCONST(0.5) * (mem->tstop - mem->tn);

    flag = lgnCheckProgress(mem, h);
    if (flag != LGN_SUCCESS) return flag;
    RescaleAux(mem, h);
    c    = lgnStepCoeffs(mem, h);
    lgnNewtonTolerances(mem, &c);
    /* a singular iteration matrix at this h: retried with a smaller one
     * (LGN_RECOVERABLE from lgnLsSetup), as IDA's IDAHandleNFlag does */
    mem->lsetup_recoverable = SUNTRUE;
    flag = lgnStepAttempt(mem, &c);
    mem->lsetup_recoverable = SUNFALSE;
    if (flag == LGN_SUCCESS) flag = lgnLocalError(mem, &c, &err);
    if (flag == LGN_SUCCESS && mem->lambda_errcon) { /* the multipliers too (lgn_output.c) */
      sunrealtype err_l;
      flag = lgnMultiplierError(mem, c.t1, &err_l);
      err  = SUNMAX(err, err_l);
    }
    mem->err_norm = err;

    if (flag == LGN_SUCCESS && err <= SUN_RCONST(1.0)) {
      lgnStepComplete(mem, &c);
      if (landing) mem->tn = mem->tstop; /* exactly */
      /* growth judged by the larger of the last two errors: generalized-
       * alpha's estimate may drop for one step (after a change of h) and
       * would otherwise propose a step that fails */
      factor = ErrorFactor(SUNMAX(err, mem->err_prev));
      mem->err_prev = err;
      factor = SUNMIN(factor, nef > 0 || ncf > 0 ? SUN_RCONST(1.0) : FMAX);
      if (factor >= SUN_RCONST(1.0) && factor < KEEP_BELOW) factor = SUN_RCONST(1.0);
      factor = SUNMAX(factor, FMIN);
      /* after a landing, go on from the step size the controller wanted */
      mem->hnext = lgnLimitStep(mem, landing ? SUNMAX(h * factor, h_wanted) : h * factor);
      return LGN_SUCCESS;
    }

    if (flag == LGN_SUCCESS) {
      /* error test failed */
      lgnStepRejected(mem);
      mem->netf++;
      nef++;
      if (nef >= mem->maxnef || h <= mem->hmin || !isfinite(err)) {
        LGN_ERROR(mem, LGN_ERR_FAILURE,
                  MSG_TIME "the error test failed %d times, the last with "
                  "h = %g and |e| = %g%s (the state at t is kept).%s",
                  (double)mem->tn, nef, (double)h, (double)err,
                  h <= mem->hmin ? " at the minimum step size" : "",
                  isfinite(err) ? ""
                                : " The error norm is not finite: the tolerances (rtol, "
                                  "atol) are too small for finite error weights.");
        return LGN_ERR_FAILURE;
      }
      /* from the second failure on at most CUT_FAIL, less when the error
       * says so (a first step far too large: h0 = 1e6 on the heavy top
       * needs 1e-9 of it), but not below CUT_MIN */
      factor = nef == 1 ? SUNMAX(FMIN, SUNMIN(SAFETY, ErrorFactor(err)))
                        : SUNMAX(CUT_MIN, SUNMIN(CUT_FAIL, ErrorFactor(err)));
    } else if (flag == LGN_CONV_FAILURE || flag == LGN_RECOVERABLE) {
      /* singular on any rank: the same flag on all */
      const sunbooleantype singular =
          lgnMaxAll(mem, flag == LGN_RECOVERABLE && mem->last_lin_flag != 0 ? SUN_RCONST(1.0)
                                                                             : SUN_RCONST(0.0)) >
          SUN_RCONST(0.0);
      ncf++;
      if (ncf >= mem->maxncf || h <= mem->hmin) {
        const int out = flag == LGN_CONV_FAILURE ? LGN_CONV_FAILURE
                      : singular                 ? LGN_LSETUP_FAIL
                                                 : LGN_REPTD_CALLBACK_ERR;
        LGN_ERROR(mem, out,
                  MSG_TIME "%s %d times, the last with h = %g%s (the state at t "
                  "is kept).%s", (double)mem->tn,
                  flag == LGN_CONV_FAILURE ? "the Newton iteration failed to converge"
                  : singular ? "the iteration matrix was singular"
                             : "a callback failed recoverably",
                  ncf, (double)h, h <= mem->hmin ? " at the minimum step size" : "",
                  singular ? mem->diag_text : "");
        return out;
      }
      factor = CUT_FAIL;
    } else {
      lgnStepRejected(mem); /* (the estimate itself failed) */
      return flag; /* unrecoverable: reported where it happened */
    }
    h = lgnLimitStep(mem, h * factor);
    mem->hnext = h;
  }
}
