/* -----------------------------------------------------------------------------
 * Lignum study: the BDF local error estimate against the true local error on
 * the heavy top (R^3 x SO(3), the body and joint helpers, as test_bdf).
 *
 * One BDF step of order k and size h from an exact history: q, v, lambda at
 * t_n - j h (j = 0 ... k + 1) from the ARKODE reference (Fehlberg 8, about
 * 1e-13). The step's chart coordinate x_{n+1} = log(q_n^{-1} q_{n+1}) is
 * compared with the reference's, log(q_n^{-1} q_ref(t_{n+1})): the true
 * local error of the positions (and v_{n+1} - v_ref of the velocities),
 * and the estimate of lgn_bdf.c,
 *
 *   LTE_k = (x_{n+1} - x_pred) / (c0 psi_{k+1}),
 *
 * in the inf-norm and in the error test's WRMS norm (weights 1/(tol + tol
 * |x_{n+1}|)), over several h and several t_n (the largest ratio); the
 * same for h (v_{n+1} - v_ref) and h LTE_k of the velocities (WRMS). The
 * step uses Lignum's internal step function lgnBDFStep (linked with
 * lignum_internal): a program to run by hand, not a test.
 *
 *   bdf_lte [--tol T]   the local error table
 *   bdf_lte --sweep     error control: error against tol, maxord 4 and 5
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_group.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "lgn_impl.h"
#include "lgn_reference.h"

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Top;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Top *)ud)->bodies);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Top *)ud)->bodies);
}
static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                     SUNMatrix K, void *ud)
{
  Top *top = (Top *)ud;
  if (LGNBodies_StiffnessFn(t, q, v, vdot, lambda, K, top->bodies)) return -1;
  return LGNJoints_Stiffness(top->joints, t, q, lambda, K) ? -1 : 0;
}
static int Damping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  return LGNBodies_DampingFn(t, q, v, C, ((Top *)ud)->bodies);
}
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Top *)ud)->joints, t, q, phi) ? -1 : 0;
}
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Top *)ud)->joints, t, q, B) ? -1 : 0;
}
static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  return LGNJoints_Curvature(((Top *)ud)->joints, t, q, v, z) ? -1 : 0;
}

typedef struct {
  SUNContext ctx;
  LGNGroup G;
  Top top;
  N_Vector q, v, y;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
} Run;

static int RunCreateBase(Run *r, SUNContext ctx, int k, double tol)
{
  const sunrealtype J[3] = {0.234375, 0.46875, 0.234375}, grav[3] = {0, 0, -9.81};
  const sunrealtype s[3] = {0, -1, 0}, o[3] = {0, 0, 0};
  const sunrealtype Om[3] = {0, 150, -4.61538}, X[3] = {0, 1, 0};
  sunrealtype *q, *v;
  int flag;
  memset(r, 0, sizeof *r);
  r->ctx = ctx;
  r->G   = LGNGroup_R3xSO3();
  r->top.bodies = LGNBodies_Create(r->G);
  r->top.joints = LGNJoints_Create(r->G);
  LGNBodies_SetPrincipalInertia(r->top.bodies, 0, 15.0, J);
  LGNBodies_SetGravity(r->top.bodies, grav);
  LGNJoints_AddSpherical(r->top.joints, 0, s, LGN_GROUND, o);
  r->q = N_VNew_Serial(7, ctx);
  r->v = N_VNew_Serial(6, ctx);
  q = N_VGetArrayPointer(r->q);
  v = N_VGetArrayPointer(r->v);
  q[0] = X[0]; q[1] = X[1]; q[2] = X[2];
  q[3] = 1; q[4] = q[5] = q[6] = 0;
  v[0] = Om[1] * X[2] - Om[2] * X[1];
  v[1] = Om[2] * X[0] - Om[0] * X[2];
  v[2] = Om[0] * X[1] - Om[1] * X[0];
  v[3] = Om[0]; v[4] = Om[1]; v[5] = Om[2];
  r->y   = N_VNew_Serial(9, ctx);
  r->A   = SUNDenseMatrix(9, 9, ctx);
  r->LS  = LGNLinSol_Dense(r->y, r->A, ctx);
  r->mem = LGNCreate(ctx);
  flag = LGNSetGroup(r->mem, r->G);
  if (!flag) flag = LGNSetUserData(r->mem, &r->top);
  if (!flag) flag = LGNSetMassFn(r->mem, Mass);
  if (!flag) flag = LGNSetForceFn(r->mem, Force);
  if (!flag) flag = LGNSetMassConstant(r->mem, SUNTRUE);
  if (!flag) flag = LGNSetConstraints(r->mem, 3, Constr, ConstrJac);
  if (!flag) flag = LGNSetStiffnessFn(r->mem, Stiffness);
  if (!flag) flag = LGNSetDampingFn(r->mem, Damping);
  if (!flag) flag = LGNSetCurvatureFn(r->mem, Curvature);
  if (!flag) flag = LGNInit(r->mem, 0.0, r->q, r->v);
  if (!flag) flag = LGNSetLinearSolver(r->mem, r->LS, r->A);
  if (!flag) flag = LGNSetBDF(r->mem, k);
  if (!flag) flag = LGNSStolerances(r->mem, tol, tol);
  return flag;
}

/* The run of the local error study: one tiny step, everything allocated
 * and set up. */
static int RunCreate(Run *r, SUNContext ctx, int k, double tol)
{
  sunrealtype t;
  int flag = RunCreateBase(r, ctx, k, tol);
  if (!flag) flag = LGNSetStepSize(r->mem, 1e-6);
  if (!flag) flag = LGNSolve(r->mem, 1.0, &t, r->q, r->v, LGN_ONE_STEP);
  return flag;
}

static void RunFree(Run *r)
{
  LGNFree(&r->mem);
  SUNLinSolFree(r->LS);
  SUNMatDestroy(r->A);
  N_VDestroy(r->y);
  N_VDestroy(r->q);
  N_VDestroy(r->v);
  LGNJoints_Destroy(&r->top.joints);
  LGNBodies_Destroy(&r->top.bodies);
  LGNGroup_Destroy(r->G);
}

/* q = (x, p), v = (u, Omega), lambda = -R lambda_ref (Phi = x - R X here,
 * X - R^T x there: only the Newton start) */
static void FromRef(const LGNRefHeavyTop *s, sunrealtype *q, sunrealtype *v, sunrealtype *l)
{
  int i;
  for (i = 0; i < 3; i++) {
    q[i]     = s->x[i];
    v[i]     = s->u[i];
    v[3 + i] = s->Omega[i];
    if (l != NULL)
      l[i] = -(s->R[3 * i] * s->lambda[0] + s->R[3 * i + 1] * s->lambda[1] +
               s->R[3 * i + 2] * s->lambda[2]);
  }
  for (i = 0; i < 4; i++) q[3 + i] = s->p[i];
}

typedef struct {
  double true_x, est_x;   /* inf-norms of the position local error, estimate */
  double true_w, est_w;   /* WRMS (error-test weights)                      */
  double true_v;          /* inf-norm of the velocity local error           */
  double hdv_w;           /* WRMS of h (v_{n+1} - v_ref)                     */
  double estp_w;          /* WRMS of the projected estimate (the error test) */
  double estv_w;          /* WRMS of the projected h LTE of the velocities    */
} LteResult;

/* One step of order k and size h from the exact history at t_n. */
static int OneStep(SUNContext ctx, int k, double h, double tn, double tol, LteResult *res)
{
  LGNRefHeavyTop ref[LGN_BDF_MAXHIST + 1];
  double times[LGN_BDF_MAXHIST + 1];
  const int np = k + 2; /* history points: order k + 2 for the estimates */
  Run r;
  LGNMem mem;
  sunrealtype x1[6], xr[6], qr[7], vr[6], e[6], est[6], estp[6], w;
  int j, i, flag;

  for (j = 0; j < np; j++) times[j] = tn - (np - 1 - j) * h;
  times[np] = tn + h;
  if (lgnref_heavy_top(times, np + 1, ref, LGNREF_FEHLBERG_8) != 0) return -1;
  flag = RunCreate(&r, ctx, k, tol);
  if (flag) return flag;
  mem = (LGNMem)r.mem;
  /* the state at t_n and the history t_{n-j} = t_n - j h */
  for (j = 0; j < np; j++) {
    const LGNRefHeavyTop *s = &ref[np - 1 - j];
    mem->bdf.t[j] = s->t;
    FromRef(s, mem->bdf.q + j * mem->nq, mem->bdf.v + j * mem->nv,
            mem->bdf.l + j * mem->m);
  }
  FromRef(&ref[np - 1], lgnData(mem->q), lgnData(mem->v), lgnData(mem->lambda));
  mem->tn          = tn;
  mem->bdf.nhist   = np;
  mem->bdf.chart_t = NAN;
  mem->bdf.order   = k;
  flag = lgnBDFStep(mem, h);
  if (flag) {
    RunFree(&r);
    return flag;
  }
  /* x_{n+1} and the reference in the chart of q_n (bdf_q + nq after the push) */
  mem->G->ops.compose_log(mem->G, mem->bdf.q + mem->nq, lgnData(mem->q), x1);
  FromRef(&ref[np], qr, vr, NULL);
  mem->G->ops.compose_log(mem->G, mem->bdf.q + mem->nq, qr, xr);
  memset(res, 0, sizeof *res);
  for (i = 0; i < 6; i++) {
    e[i]   = x1[i] - xr[i];
    est[i] = (x1[i] - mem->bdf.xpred[i]) / (mem->bdf.c0 * (k + 1) * h);
    w      = 1.0 / (tol + tol * fabs(x1[i]));
    res->true_x = fmax(res->true_x, fabs(e[i]));
    res->est_x  = fmax(res->est_x, fabs(est[i]));
    res->true_v = fmax(res->true_v, fabs(lgnData(mem->v)[i] - vr[i]));
    res->true_w += e[i] * w * e[i] * w / 6.0;
    res->est_w  += est[i] * w * est[i] * w / 6.0;
    res->hdv_w  += pow(h * (lgnData(mem->v)[i] - vr[i]) * w, 2) / 6.0;
  }
  /* the estimate as the error test sees it: projected on the constraints'
   * tangent space (lgnErrorNorm, with the step's factorised matrix) */
  {
    LGNStepCoeffs c;
    sunrealtype nrm;
    memset(&c, 0, sizeof c);
    c.h = h; c.t1 = tn + h;
    c.gamma_p = mem->bdf.c0; c.beta_p = mem->bdf.c0 * mem->bdf.c0;
    c.scale = 1.0 / c.beta_p; c.hmat = 1.0 / mem->bdf.c0; c.beta_n = c.scale / (h * h);
    memcpy(mem->ec.ele, est, sizeof est);
    lgnErrorNorm(mem, &c, x1, SUN_RCONST(1.0), &nrm);
    memcpy(estp, mem->ec.ele, sizeof estp);
    res->estp_w = nrm;
    /* the velocities' h LTE_k, the same way */
    for (i = 0; i < 6; i++)
      mem->ec.ele[i] = h * (lgnData(mem->v)[i] - mem->bdf.vpred[i]) / (mem->bdf.c0 * (k + 1) * h);
    lgnErrorNorm(mem, &c, x1, SUN_RCONST(1.0), &nrm);
    res->estv_w = nrm;
  }
  if (getenv("LTE_VERBOSE") != NULL) {
    printf("   k %d h %.2e t %.2f\n    estp:", k, h, tn);
    for (i = 0; i < 6; i++) printf(" %10.2e", estp[i]);
    printf("\n");
    printf("    true:");
    for (i = 0; i < 6; i++) printf(" %10.2e", e[i]);
    printf("\n    est: ");
    for (i = 0; i < 6; i++) printf(" %10.2e", est[i]);
    printf("\n    dv:  ");
    for (i = 0; i < 6; i++) printf(" %10.2e", lgnData(mem->v)[i] - vr[i]);
    printf("\n");
  }
  res->true_w = sqrt(res->true_w);
  res->hdv_w  = sqrt(res->hdv_w);
  res->est_w  = sqrt(res->est_w);
  RunFree(&r);
  return 0;
}

/* --sweep: error control to t = 1, maxord 4 and 5, tol 1e-4 ... 1e-10:
 * the error of the centre of mass against the reference, steps, Newton
 * iterations, error test failures, milliseconds, and the fitted exponent
 * of error against tol over 1e-5 ... 1e-10. */
static int Sweep(SUNContext ctx)
{
  const double tols[7] = {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  const double t_end = 1.0;
  LGNRefHeavyTop ref;
  int k, i, j;
  if (lgnref_heavy_top(&t_end, 1, &ref, LGNREF_FEHLBERG_8) != 0) return 1;
  printf("%6s %6s %10s %7s %8s %6s %8s  %s\n", "maxord", "tol", "error", "steps", "newton",
         "etf", "ms", "steps at orders 1-5");
  for (k = 4; k <= 5; k++) {
    double err[7];
    for (i = 0; i < 7; i++) {
      Run r;
      sunrealtype t;
      long int nst = 0, nni = 0, netf = 0, nord[6] = {0};
      clock_t c0 = clock();
      int flag = RunCreateBase(&r, ctx, k, tols[i]);
      double ms;
      if (!flag) flag = LGNSetStepControl(r.mem, LGN_STEP_ADAPTIVE);
      if (!flag) flag = LGNSetStopTime(r.mem, t_end);
      if (!flag) flag = LGNSolve(r.mem, t_end, &t, r.q, r.v, LGN_NORMAL);
      if (flag == LGN_TSTOP_RETURN) flag = LGN_SUCCESS;
      ms = 1e3 * (double)(clock() - c0) / CLOCKS_PER_SEC;
      err[i] = HUGE_VAL;
      if (!flag) {
        const sunrealtype *q = N_VGetArrayPointer(r.q);
        err[i] = 0.0;
        for (j = 0; j < 3; j++) err[i] = fmax(err[i], fabs(q[j] - ref.x[j]));
      }
      LGNGetNumSteps(r.mem, &nst);
      LGNGetNumNewtonIters(r.mem, &nni);
      LGNGetNumErrTestFails(r.mem, &netf);
      LGNGetNumStepsAtOrder(r.mem, nord);
      printf("%6d %6.0e %10.3e %7ld %8ld %6ld %8.1f  %ld %ld %ld %ld %ld\n", k, tols[i], err[i],
             nst, nni, netf, ms, nord[1], nord[2], nord[3], nord[4], nord[5]);
      RunFree(&r);
    }
    {
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      for (i = 1; i < 7; i++) {
        const double a = log(tols[i]), b = log(err[i]);
        sx += a; sy += b; sxx += a * a; sxy += a * b;
      }
      printf("maxord %d: error ~ tol^%.3f (tol 1e-5 ... 1e-10)\n", k,
             (6 * sxy - sx * sy) / (6 * sxx - sx * sx));
    }
  }
  return 0;
}

int main(int argc, char **argv)
{
  SUNContext ctx;
  const double hs[6] = {4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4};
  const double tns[4] = {0.2, 0.45, 0.7, 0.95};
  double tol = 1e-12;
  int k, ih, it;
  if (argc == 3 && !strcmp(argv[1], "--tol")) tol = atof(argv[2]);
  SUNContext_Create(NULL, &ctx);
  if (argc == 5 && !strcmp(argv[1], "--trace")) { /* --trace maxord tol t_end */
    Run r;
    sunrealtype t = 0, hl = 0;
    long int nst = 0;
    int ko = 0, flag = RunCreateBase(&r, ctx, atoi(argv[2]), atof(argv[3]));
    const double te = atof(argv[4]);
    if (!flag) flag = LGNSetStepControl(r.mem, LGN_STEP_ADAPTIVE);
    if (!flag) flag = LGNSetStopTime(r.mem, te);
    while (!flag && t < te) {
      flag = LGNSolve(r.mem, te, &t, r.q, r.v, LGN_ONE_STEP);
      if (flag == LGN_TSTOP_RETURN) flag = 0;
      LGNGetLastStep(r.mem, &hl);
      LGNGetLastOrder(r.mem, &ko);
      LGNGetNumSteps(r.mem, &nst);
      {
        long int etf = 0, ncf = 0;
        LGNGetNumErrTestFails(r.mem, &etf);
        LGNGetNumNewtonConvFails(r.mem, &ncf);
        printf("%5ld t %.10f h %.3e k %d etf %ld ncf %ld\n", nst, t, hl, ko, etf, ncf);
      }
    }
    RunFree(&r);
    SUNContext_Free(&ctx);
    return flag;
  }
  if (argc == 2 && !strcmp(argv[1], "--sweep")) {
    int ret = Sweep(ctx);
    SUNContext_Free(&ctx);
    return ret;
  }
  printf("BDF local error on the heavy top: one step from the exact history\n"
         "(t_n = 0.2, 0.45, 0.7, 0.95; inf-norms, largest over t_n; WRMS with\n"
         "weights 1/(%g (1 + |x|)))\n\n", tol);
  printf("%2s %9s %10s %10s %7s %10s %10s %7s %10s %7s %10s\n", "k", "h", "true |dx|",
         "est |dx|", "ratio", "true wrms", "est wrms", "ratio", "proj wrms", "ratio", "|dv|");
  printf("%2s %9s %10s %10s\n", "", "", "true h dv", "est h dv");
  for (k = 3; k <= 5; k++) {
    for (ih = 0; ih < 6; ih++) {
      double tx = 0, ex = 0, tw = 0, ew = 0, tv = 0, rx = 0, rw = 0, pw = 0, rp = 0;
      double hv = 0, hve = 0;
      for (it = 0; it < 4; it++) {
        LteResult res;
        int flag = OneStep(ctx, k, hs[ih], tns[it], tol, &res);
        if (flag) {
          printf("k %d h %g t %g: flag %d\n", k, hs[ih], tns[it], flag);
          continue;
        }
        tx = fmax(tx, res.true_x);
        ex = fmax(ex, res.est_x);
        tw = fmax(tw, res.true_w);
        ew = fmax(ew, res.est_w);
        tv = fmax(tv, res.true_v);
        rx = fmax(rx, res.true_x / res.est_x);
        rw = fmax(rw, res.true_w / res.est_w);
        pw = fmax(pw, res.estp_w);
        rp = fmax(rp, res.true_w / res.estp_w);
        hv = fmax(hv, res.hdv_w);
        hve = fmax(hve, res.estv_w);
      }
      printf("%2d %9.2e %10.3e %10.3e %7.2f %10.3e %10.3e %7.2f %10.3e %7.2f %10.3e\n", k,
             hs[ih], tx, ex, rx, tw, ew, rw, pw, rp, tv);
      printf("%2s %9s %10.3e %10.3e (WRMS)\n", "", "", hv, hve);
    }
  }
  SUNContext_Free(&ctx);
  return 0;
}
