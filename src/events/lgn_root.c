/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Events: root finding on user functions g(t, q, v), as IDA does it
 * (IDARcheck1-3, IDARootfind), located on the dense output of the last
 * step (lgn_dense_output.c):
 *   - LGNSolve starts root finding at t_n (after LGNInit, LGNReInit or
 *     LGNRootInit): g at t_n becomes glo, the value at tlo, the last point
 *     checked;
 *   - after every accepted step g is evaluated at thi = t_{n+1} (or at tout
 *     when LGN_NORMAL interpolates there) and a sign change of an active
 *     g_i in (tlo, thi], allowed by its direction, is bracketed and
 *     narrowed by the Illinois method (modified regula falsi) on the dense
 *     output to ttol = 100 eps (|t_n| + |h|); the right end of the final
 *     bracket is the root returned (LGN_ROOT_RETURN), where g has changed
 *     sign (or is exactly 0);
 *   - tlo moves to the root, so roots between it and t_{n+1} are found by
 *     the next LGNSolve, which checks the rest of the step first;
 *   - a g_i exactly 0 at tlo (at the start, at a root) is inactive: at the
 *     next check it is looked at ttol later and becomes active with that
 *     value as soon as it is not 0, so a root is never reported twice.
 * The state of the integrator stays at t_{n+1}; only the output is at the
 * root. Also the public LGNRootInit, LGNSetRootDirection,
 * LGNSetNoInactiveRootWarn, LGNGetRootInfo, LGNGetNumGEvals.
 * The arrays and scratch vectors are lgn_mem.c's (lgnAllocRoots).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>

#include "lgn_impl.h"

#define FUNC_SOLVE "LGNSolve" /* the public function the messages belong to */

/* =============================================================================
 * g on the dense output
 * ===========================================================================*/

/* Round-off in t near the last step: IDA's ttol. */
static sunrealtype RootTol(LGNMem mem)
{
  sunrealtype h;
  if (mem->dense.valid) h = mem->tn - mem->dense.tprev;
  else h = mem->ec.step_control == LGN_STEP_ADAPTIVE ? mem->ec.hnext : mem->h;
  return SUN_RCONST(100.0) * SUN_UNIT_ROUNDOFF * (fabs(mem->tn) + fabs(h));
}

/* q and v at t (t_n itself, or the dense output of the last step). */
static int StateAt(LGNMem mem, sunrealtype t, N_Vector q, N_Vector v)
{
  int flag;
  if (t == mem->tn || !mem->dense.valid) {
    N_VScale(SUN_RCONST(1.0), mem->q, q);
    N_VScale(SUN_RCONST(1.0), mem->v, v);
    return LGN_SUCCESS;
  }
  flag = lgnDenseOutput(mem, t, 0, lgnData(q));
  if (flag == LGN_SUCCESS) flag = lgnDenseOutput(mem, t, 1, lgnData(v));
  return flag;
}

/* gout = g(t, q(t), v(t)); a nonzero return or a value not finite is
 * LGN_RTFUNC_FAIL. Across ranks g is the sum of the ranks' returns (each
 * returns its part: what its bodies contribute, zero for the others'), so
 * that every rank finds the same roots. */
static int EvalG(LGNMem mem, sunrealtype t, sunrealtype *gout)
{
  int i, ret, flag = lgnAgree(mem, StateAt(mem, t, mem->rt.q, mem->rt.v));
  if (flag != LGN_SUCCESS) return flag;
  ret = mem->rt.gfun(t, mem->rt.q, mem->rt.v, gout, mem->user_data);
  mem->rt.nge++;
  if (ret != 0) {
    lgnProcessError(mem, LGN_RTFUNC_FAIL, __LINE__, FUNC_SOLVE, __FILE__,
                    MSG_TIME "the root function failed (returned %d).",
                    (double)t, ret);
    flag = LGN_RTFUNC_FAIL;
  }
  for (i = 0; i < mem->rt.nrtfn && flag == LGN_SUCCESS; i++) {
    if (!isfinite(gout[i])) {
      lgnProcessError(mem, LGN_RTFUNC_FAIL, __LINE__, FUNC_SOLVE, __FILE__,
                      MSG_TIME "the root function returned g[%d] = %g, not "
                      "finite.", (double)t, i, (double)gout[i]);
      flag = LGN_RTFUNC_FAIL;
    }
  }
  flag = lgnAgree(mem, flag);
  if (flag == LGN_SUCCESS) lgnSumAll(mem, gout, mem->rt.nrtfn);
  return flag;
}

/* =============================================================================
 * The Illinois method (IDARootfind)
 * ===========================================================================*/

/* g_i counts for a root going from glo to gx: its sign changed (or it is
 * 0 at x) in a direction rootdir allows (+1: increasing, -1: decreasing). */
static sunbooleantype DirectionOk(int dir, sunrealtype glo)
{
  return (sunrealtype)dir * glo <= SUN_RCONST(0.0);
}

/* Among the active g_i, is there a sign change from glo to gx (*imax: the
 * one whose change is relatively nearest to the left end) or an exact 0
 * at x (*zroot)? */
static sunbooleantype SignChange(LGNMem mem, const sunrealtype *gx, int *imax,
                                 sunbooleantype *zroot)
{
  sunrealtype maxfrac = SUN_RCONST(0.0), gfrac;
  sunbooleantype sgnchg = SUNFALSE;
  int i;
  *zroot = SUNFALSE;
  for (i = 0; i < mem->rt.nrtfn; i++) {
    if (!mem->rt.gactive[i] || !DirectionOk(mem->rt.rootdir[i], mem->rt.glo[i])) continue;
    if (gx[i] == SUN_RCONST(0.0)) {
      *zroot = SUNTRUE;
    } else if (mem->rt.glo[i] * gx[i] < SUN_RCONST(0.0)) {
      gfrac = fabs(gx[i] / (gx[i] - mem->rt.glo[i]));
      if (gfrac > maxfrac) {
        sgnchg  = SUNTRUE;
        maxfrac = gfrac;
        *imax   = i;
      }
    }
  }
  return sgnchg;
}

/* The earliest root in (tlo, thi] of the active g_i, ghi = g(thi) given.
 * On return *trout is the root (or thi: none, *found false), grout g
 * there, and iroots the direction of each g_i with a root at trout;
 * glo, the left end's values, may have moved towards the root. */
static int Rootfind(LGNMem mem, sunrealtype thi, sunrealtype ttol,
                    sunrealtype *trout, sunbooleantype *found)
{
  const int n = mem->rt.nrtfn;
  sunrealtype tlo = mem->rt.tlo, tmid, alph = SUN_RCONST(1.0), fracint, fracsub;
  sunbooleantype zroot, sgnchg, any;
  int i, imax = 0, side = 0, sideprev = -1, flag;

  sgnchg = SignChange(mem, mem->rt.ghi, &imax, &zroot);
  *found = sgnchg || zroot;
  if (sgnchg) {
    /* narrow the bracket [tlo, thi] of the sign change of g_imax */
    for (;;) {
      if (fabs(thi - tlo) <= ttol) break;
      /* Illinois: after two moves of the same end, weigh the other one */
      if (sideprev == side)
        alph = side == 2 ? alph * SUN_RCONST(2.0) : alph * SUN_RCONST(0.5);
      else
        alph = SUN_RCONST(1.0);
      tmid = thi - (thi - tlo) * mem->rt.ghi[imax] /
                       (mem->rt.ghi[imax] - alph * mem->rt.glo[imax]);
      /* not closer than ttol / 2 to either end */
      if (fabs(tmid - tlo) < SUN_RCONST(0.5) * ttol) {
        fracint = fabs(thi - tlo) / ttol;
        fracsub = fracint > SUN_RCONST(5.0) ? SUN_RCONST(0.1) : SUN_RCONST(0.5) / fracint;
        tmid    = tlo + fracsub * (thi - tlo);
      }
      if (fabs(thi - tmid) < SUN_RCONST(0.5) * ttol) {
        fracint = fabs(thi - tlo) / ttol;
        fracsub = fracint > SUN_RCONST(5.0) ? SUN_RCONST(0.1) : SUN_RCONST(0.5) / fracint;
        tmid    = thi - fracsub * (thi - tlo);
      }
      flag = EvalG(mem, tmid, mem->rt.grout);
      if (flag != LGN_SUCCESS) return flag;
      sideprev = side;
      sgnchg   = SignChange(mem, mem->rt.grout, &imax, &zroot);
      if (sgnchg) {
        /* a sign change in (tlo, tmid) */
        thi = tmid;
        memcpy(mem->rt.ghi, mem->rt.grout, (size_t)n * sizeof(sunrealtype));
        side = 1;
      } else if (zroot) {
        /* none in (tlo, tmid), but g_i = 0 at tmid: the root */
        thi = tmid;
        memcpy(mem->rt.ghi, mem->rt.grout, (size_t)n * sizeof(sunrealtype));
        break;
      } else {
        /* the sign change is in (tmid, thi) */
        tlo = tmid;
        memcpy(mem->rt.glo, mem->rt.grout, (size_t)n * sizeof(sunrealtype));
        side = 2;
      }
    }
  }
  *trout = thi;
  memcpy(mem->rt.grout, mem->rt.ghi, (size_t)n * sizeof(sunrealtype));
  any = SUNFALSE;
  for (i = 0; i < n; i++) {
    mem->rt.iroots[i] = 0;
    if (!*found || !mem->rt.gactive[i] || !DirectionOk(mem->rt.rootdir[i], mem->rt.glo[i]))
      continue;
    if (mem->rt.ghi[i] == SUN_RCONST(0.0) || mem->rt.glo[i] * mem->rt.ghi[i] < SUN_RCONST(0.0)) {
      mem->rt.iroots[i] = mem->rt.glo[i] > SUN_RCONST(0.0) ? -1 : 1;
      any               = SUNTRUE;
    }
  }
  /* A sign change seen at roundoff level (a g_i taken up at tlo + ttol,
   * around 0 within roundoff) can leave a bracket whose ends have one sign:
   * no g_i has a root there, so none is reported (LGN_ROOT_RETURN with no
   * rootsfound: fuzz finding 12); the search goes on from trout. */
  *found = *found && any;
  return LGN_SUCCESS;
}

/* =============================================================================
 * Checks: at the start and over (tlo, thi]
 * ===========================================================================*/

/* Root finding starts at t_n: g there; a g_i exactly 0 is inactive until
 * it moves away from 0. */
static int Start(LGNMem mem)
{
  int i, flag;
  mem->rt.tlo = mem->tn;
  flag = EvalG(mem, mem->tn, mem->rt.glo);
  if (flag != LGN_SUCCESS) return flag;
  for (i = 0; i < mem->rt.nrtfn; i++) {
    mem->rt.gactive[i] = mem->rt.glo[i] != SUN_RCONST(0.0);
    mem->rt.iroots[i]  = 0;
  }
  mem->rt.started = SUNTRUE;
  mem->rt.pending = SUNFALSE;
  mem->rt.first   = SUNTRUE;
  return LGN_SUCCESS;
}

/* Roots in (tlo, thi], tprev <= tlo < thi <= tn. Afterwards tlo is the root
 * found, or thi, and glo g there. */
static int Check(LGNMem mem, sunrealtype thi, sunbooleantype *found)
{
  const sunrealtype ttol = RootTol(mem);
  sunrealtype trout, tplus;
  sunbooleantype inactive = SUNFALSE;
  int i, flag;

  *found = SUNFALSE;
  for (i = 0; i < mem->rt.nrtfn; i++) inactive = inactive || !mem->rt.gactive[i];
  /* g_i zero at tlo: look a little later, and take it up if nonzero there */
  tplus = mem->rt.tlo + ttol;
  if (inactive && tplus < thi) {
    flag = EvalG(mem, tplus, mem->rt.ghi);
    if (flag != LGN_SUCCESS) return flag;
    for (i = 0; i < mem->rt.nrtfn; i++) {
      if (!mem->rt.gactive[i] && mem->rt.ghi[i] != SUN_RCONST(0.0)) {
        mem->rt.gactive[i] = SUNTRUE;
        mem->rt.glo[i]     = mem->rt.ghi[i];
      }
    }
  }
  flag = EvalG(mem, thi, mem->rt.ghi);
  if (flag == LGN_SUCCESS) flag = Rootfind(mem, thi, ttol, &trout, found);
  if (flag != LGN_SUCCESS) return flag;

  /* go on from the root (or thi); a g_i exactly 0 there waits */
  mem->rt.tlo = trout;
  memcpy(mem->rt.glo, mem->rt.grout, (size_t)mem->rt.nrtfn * sizeof(sunrealtype));
  inactive = SUNFALSE;
  for (i = 0; i < mem->rt.nrtfn; i++) {
    mem->rt.gactive[i] = mem->rt.glo[i] != SUN_RCONST(0.0);
    inactive        = inactive || !mem->rt.gactive[i];
  }
  if (mem->rt.first && inactive && !*found && !mem->rt.nowarn) {
    lgnProcessError(mem, LGN_WARNING, __LINE__, FUNC_SOLVE, __FILE__,
                    MSG_TIME "some root functions are still exactly 0 at the "
                    "end of the first step; they are ignored until they move "
                    "away from 0 (this warning is not repeated; "
                    "LGNSetNoInactiveRootWarn turns it off).", (double)thi);
  }
  mem->rt.first = SUNFALSE;
  return LGN_SUCCESS;
}

/* Check (tlo, thi]; a root: q, v at it, tret = the root, LGN_ROOT_RETURN. */
static int CheckAndReturn(LGNMem mem, sunrealtype thi, sunrealtype *tret,
                          N_Vector q, N_Vector v)
{
  sunbooleantype found = SUNFALSE;
  int flag = Check(mem, thi, &found);
  if (flag != LGN_SUCCESS || !found) return flag;
  flag = lgnAgree(mem, StateAt(mem, mem->rt.tlo, q, v));
  if (flag != LGN_SUCCESS) return flag;
  *tret           = mem->rt.tlo;
  mem->rt.pending = mem->rt.tlo < mem->tn;
  return LGN_ROOT_RETURN;
}

/* The end of the interval to check: t_n, or tout if LGN_NORMAL returns
 * there, inside the last step. */
static sunrealtype CheckEnd(LGNMem mem, sunrealtype tout, int itask)
{
  return (itask == LGN_NORMAL && tout < mem->tn) ? tout : mem->tn;
}

/* At the start of LGNSolve (before any step): start root finding at t_n,
 * or check what is left of the last step after a root or an output inside
 * it. LGN_SUCCESS: go on (or, *done, return tn: LGN_ONE_STEP after a root
 * with none left in its step, as IDA does); LGN_ROOT_RETURN: the output
 * is filled in; otherwise a failure, reported. */
int lgnRootSolveStart(LGNMem mem, sunrealtype tout, int itask,
                      sunrealtype *tret, N_Vector q, N_Vector v,
                      sunbooleantype *done)
{
  const sunbooleantype pending = mem->rt.pending;
  sunrealtype thi;
  int flag = LGN_SUCCESS;

  *done = SUNFALSE;
  if (!mem->rt.started) return Start(mem);
  mem->rt.pending = SUNFALSE;
  thi = CheckEnd(mem, tout, itask);
  if (mem->dense.valid && thi > mem->rt.tlo && mem->rt.tlo >= mem->dense.tprev) {
    flag = CheckAndReturn(mem, thi, tret, q, v);
    if (flag != LGN_SUCCESS) return flag;
  }
  if (pending && itask == LGN_ONE_STEP) {
    *tret = mem->tn;
    N_VScale(SUN_RCONST(1.0), mem->q, q);
    N_VScale(SUN_RCONST(1.0), mem->v, v);
    *done = SUNTRUE;
  }
  return LGN_SUCCESS;
}

/* After an accepted step: roots in (tlo, t_n] (up to tout for LGN_NORMAL).
 * LGN_SUCCESS: none; LGN_ROOT_RETURN: the output is filled in; otherwise a
 * failure, reported. */
int lgnRootAfterStep(LGNMem mem, sunrealtype tout, int itask,
                     sunrealtype *tret, N_Vector q, N_Vector v)
{
  sunrealtype thi;
  if (!mem->rt.started) {
    /* not started at this step's start (cannot happen through LGNSolve):
     * start at its end */
    return Start(mem);
  }
  thi = CheckEnd(mem, tout, itask);
  if (!(thi > mem->rt.tlo)) return LGN_SUCCESS;
  if (mem->rt.tlo < mem->dense.tprev) mem->rt.tlo = mem->dense.tprev; /* never outside the step */
  return CheckAndReturn(mem, thi, tret, q, v);
}

/* =============================================================================
 * Public functions
 * ===========================================================================*/

int LGNRootInit(void *lgn_mem, int nrtfn, LGNRootFn g)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  if (nrtfn < 0 || nrtfn > LGN_MAX_ROOTS) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "nrtfn = %d illegal: must lie in 0 ... %d (3 nrtfn "
              "reals are allocated).", nrtfn, LGN_MAX_ROOTS);
    return LGN_ILL_INPUT;
  }
  if (nrtfn > 0 && g == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "g = NULL illegal with nrtfn = %d root functions.",
              nrtfn);
    return LGN_ILL_INPUT;
  }
  if (nrtfn == 0) {
    lgnFreeRoots(mem); /* root finding off */
    return LGN_SUCCESS;
  }
  if (lgnAllocRoots(mem, nrtfn) != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return LGN_MEM_FAIL;
  }
  mem->rt.gfun = g; /* root finding starts at the next LGNSolve */
  return LGN_SUCCESS;
}

int LGNSetRootDirection(void *lgn_mem, int *rootdir)
{
  LGNMem mem;
  int i, flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  if (mem->rt.nrtfn == 0) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "Root finding is not initialised: call LGNRootInit with nrtfn > 0 first.");
    return LGN_ILL_INPUT;
  }
  if (rootdir == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "rootdir = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  for (i = 0; i < mem->rt.nrtfn; i++) {
    if (rootdir[i] < -1 || rootdir[i] > 1) {
      LGN_ERROR(mem, LGN_ILL_INPUT,
                "rootdir[%d] = %d illegal: use +1 (increasing), -1 "
                "(decreasing) or 0 (both).", i, rootdir[i]);
      return LGN_ILL_INPUT;
    }
  }
  memcpy(mem->rt.rootdir, rootdir, (size_t)mem->rt.nrtfn * sizeof(int));
  return LGN_SUCCESS;
}

int LGNSetNoInactiveRootWarn(void *lgn_mem)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  mem->rt.nowarn = SUNTRUE;
  return LGN_SUCCESS;
}

int LGNGetRootInfo(void *lgn_mem, int *rootsfound)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (rootsfound == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "rootsfound = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  if (mem->rt.nrtfn > 0)
    memcpy(rootsfound, mem->rt.iroots, (size_t)mem->rt.nrtfn * sizeof(int));
  return LGN_SUCCESS;
}

int LGNGetNumGEvals(void *lgn_mem, long int *ngevals)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (ngevals == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "ngevals = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  *ngevals = mem->rt.nge;
  return LGN_SUCCESS;
}
