/* Events (root finding): LGNRootInit, LGNSetRootDirection, LGNGetRootInfo,
 * LGNGetNumGEvals and LGN_ROOT_RETURN, in both step modes (fixed and
 * adaptive) and with LGN_NORMAL and LGN_ONE_STEP.
 *
 * Models on R^1 with exact solutions:
 *   - a falling ball, z'' = -grav: z(t) = z0 + v0 t - grav t^2 / 2. The
 *     Newmark / generalized-alpha steps and the cubic Hermite dense output
 *     reproduce this quadratic exactly (up to round-off), so the event time
 *     measures the root finding alone: |t_root - t*| <= 1e-10 is asserted
 *     (about 1e-15 is seen, the Illinois tolerance 100 eps (|t| + |h|));
 *   - a spring, z'' = -z: the located root is a root of the interpolated
 *     solution, |z(t_root)| <= 1e-12 |v(t_root)|.
 * Asserted: the event time and state, rootsfound, direction filtering, two
 * roots in one step found in order (and two at the same time together), a
 * root exactly at a step end found once, g exactly 0 at the start not
 * reported, LGN_ONE_STEP returning the step end after a root, LGN_NORMAL
 * never reporting a root beyond tout before tout, LGNReInit after the
 * impact with the velocity reversed (restitution e) giving the next
 * impacts at the analytic times, nrtfn = 0 turning root finding off, the
 * warning for a g_i identically 0, and bad input and a failing root
 * function (flag and a message naming the argument). */
#include <string.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "test_util.h"

#define GRAV 9.81
#define PI 3.14159265358979323846
#define TOL_EVENT 1e-10

/* ---- error capture ---- */
static int last_code, nwarn;
static char last_msg[512];

static void Capture(int code, const char *mod, const char *fn, const char *msg, void *d)
{
  (void)mod; (void)fn; (void)d;
  last_code = code;
  if (code == LGN_WARNING) nwarn++;
  snprintf(last_msg, sizeof last_msg, "%s", msg);
}

/* ---- model and root functions ---- */
typedef enum { BALL, SPRING } ModelKind;
typedef enum {
  G_Z,          /* g = z                                   */
  G_Z_LEVEL,    /* g = z - level                           */
  G_TWO_LEVELS, /* g = (z - level, z - level2)             */
  G_SAME_TIME,  /* g = (z - level, 2 (z - level))          */
  G_TIME,       /* g = t - level (a time event)            */
  G_ZERO,       /* g = (z - level, 0): one g_i always 0    */
  G_FAIL,       /* returns fail_ret for t > level          */
  G_NAN         /* NaN for t > level                       */
} RootKind;

typedef struct {
  ModelKind model;
  RootKind root;
  double level, level2;
  int fail_ret;
} Problem;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = 1.0;
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  Problem *p = (Problem *)ud;
  (void)t; (void)v;
  N_VGetArrayPointer(g)[0] = p->model == BALL ? GRAV : N_VGetArrayPointer(q)[0];
  return 0;
}

static int Stiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                     N_Vector lambda, SUNMatrix K, void *ud)
{
  Problem *p = (Problem *)ud;
  (void)t; (void)q; (void)v; (void)vdot; (void)lambda;
  SM_ELEMENT_D(K, 0, 0) = p->model == BALL ? 0.0 : 1.0;
  return 0;
}

static int Roots(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *gout, void *ud)
{
  Problem *p = (Problem *)ud;
  const double z = N_VGetArrayPointer(q)[0];
  (void)v;
  switch (p->root) {
  case G_Z:          gout[0] = z; break;
  case G_Z_LEVEL:    gout[0] = z - p->level; break;
  case G_TWO_LEVELS: gout[0] = z - p->level; gout[1] = z - p->level2; break;
  case G_SAME_TIME:  gout[0] = z - p->level; gout[1] = 2.0 * (z - p->level); break;
  case G_TIME:       gout[0] = t - p->level; break;
  case G_ZERO:       gout[0] = z - p->level; gout[1] = 0.0; break;
  case G_FAIL:
    if (t > p->level) return p->fail_ret;
    gout[0] = z;
    break;
  case G_NAN:        gout[0] = t > p->level ? NAN : z; break;
  }
  return 0;
}

/* ---- set-up ---- */
typedef struct {
  SUNContext ctx;
  LGNGroup G;
  N_Vector q, v, tmpl;
  SUNMatrix A;
  SUNLinearSolver LS;
  void *mem;
  Problem p;
} Fixture;

typedef enum { FIXED, ADAPTIVE } Mode;

/* A ball (or spring) from (z0, v0) at t0; fixed step h or error control. */
static void Setup(Fixture *f, ModelKind model, double z0, double v0, Mode mode, double h)
{
  memset(f, 0, sizeof *f);
  SUNContext_Create(NULL, &f->ctx);
  f->p.model = model;
  f->G = LGNGroup_Rn(1);
  f->q = N_VNew_Serial(1, f->ctx);
  f->v = N_VNew_Serial(1, f->ctx);
  f->tmpl = N_VNew_Serial(1, f->ctx);
  f->A = SUNDenseMatrix(1, 1, f->ctx);
  f->LS = SUNLinSol_Dense(f->tmpl, f->A, f->ctx);
  f->mem = LGNCreate(f->ctx);
  LGNSetErrHandlerFn(f->mem, Capture, NULL);
  LGNSetGroup(f->mem, f->G);
  LGNSetUserData(f->mem, &f->p);
  LGNSetMassFn(f->mem, Mass);
  LGNSetForceFn(f->mem, Force);
  LGNSetStiffnessFn(f->mem, Stiffness);
  N_VGetArrayPointer(f->q)[0] = z0;
  N_VGetArrayPointer(f->v)[0] = v0;
  LGNInit(f->mem, 0.0, f->q, f->v);
  LGNSetLinearSolver(f->mem, f->LS, f->A);
  if (mode == FIXED) {
    LGNSetStepSize(f->mem, h);
  } else {
    LGNSetStepControl(f->mem, LGN_STEP_ADAPTIVE);
    LGNSStolerances(f->mem, 1e-8, 1e-8);
    if (h > 0) LGNSetMaxStep(f->mem, h);
  }
}

static void Teardown(Fixture *f)
{
  LGNFree(&f->mem);
  SUNLinSolFree(f->LS);
  SUNMatDestroy(f->A);
  N_VDestroy(f->q);
  N_VDestroy(f->v);
  N_VDestroy(f->tmpl);
  LGNGroup_Destroy(f->G);
  SUNContext_Free(&f->ctx);
}

static double Z(Fixture *f) { return N_VGetArrayPointer(f->q)[0]; }
static double V(Fixture *f) { return N_VGetArrayPointer(f->v)[0]; }

/* Solve towards tout until a root (LGN_ROOT_RETURN), tout or a failure.
 * With LGN_ONE_STEP: steps until one of these. */
static int SolveTo(Fixture *f, double tout, int itask, double *t)
{
  int flag;
  for (;;) {
    flag = LGNSolve(f->mem, tout, t, f->q, f->v, itask);
    if (flag != LGN_SUCCESS || itask == LGN_NORMAL || *t >= tout) return flag;
  }
}

static const char *ModeName(Mode m) { return m == FIXED ? "fixed" : "adaptive"; }
static const char *TaskName(int itask) { return itask == LGN_NORMAL ? "NORMAL" : "ONE_STEP"; }

static double max_event_err = 0.0; /* the largest |t_root - t*| seen */

static void CheckEvent(double t, double texact, const char *what, Mode mode, int itask)
{
  const double err = fabs(t - texact);
  if (err > max_event_err) max_event_err = err;
  CHECK(err <= TOL_EVENT, "%s (%s, %s): t = %.17g, exact %.17g, error %.3g",
        what, ModeName(mode), TaskName(itask), t, texact, err);
}

/* ---- the falling ball: one impact, state there, rootsfound ---- */
static void TestImpact(Mode mode, int itask, double h)
{
  Fixture f;
  const double z0 = 10.0, ts = sqrt(2.0 * z0 / GRAV);
  double t = 0.0;
  int flag, rf[1] = {7};
  long int nge = 0;
  Setup(&f, BALL, z0, 0.0, mode, h);
  f.p.root = G_Z;
  CHECK(LGNRootInit(f.mem, 1, Roots) == LGN_SUCCESS, "LGNRootInit");
  flag = SolveTo(&f, 5.0, itask, &t);
  CHECK(flag == LGN_ROOT_RETURN, "impact: flag %s", LGNGetReturnFlagName(flag));
  CheckEvent(t, ts, "impact time", mode, itask);
  CHECK(fabs(Z(&f)) <= 1e-9 && fabs(V(&f) + GRAV * ts) <= 1e-9,
        "state at the impact (%s): z = %g, v = %.15g (exact %.15g)", ModeName(mode),
        Z(&f), V(&f), -GRAV * ts);
  CHECK(LGNGetRootInfo(f.mem, rf) == LGN_SUCCESS && rf[0] == -1, "rootsfound = %d", rf[0]);
  CHECK(LGNGetNumGEvals(f.mem, &nge) == LGN_SUCCESS && nge > 2 && nge < 200,
        "g evaluations: %ld", nge);
  /* the integrator's state is at the step's end, behind or at the root */
  {
    double tcur = -1.0;
    LGNGetCurrentTime(f.mem, &tcur);
    CHECK(tcur >= t, "internal time %.17g >= root %.17g", tcur, t);
  }
  /* after the impact the ball falls on (no ReInit): no further root */
  flag = SolveTo(&f, 3.0, itask, &t);
  CHECK(flag == LGN_SUCCESS && t >= 3.0 - 1e-12 && Z(&f) < 0.0,
        "on to t = 3 without another root (%s, t = %g)", LGNGetReturnFlagName(flag), t);
  Teardown(&f);
}

/* ---- direction filtering: a ball thrown up crosses z = 2 twice ---- */
static void TestDirection(Mode mode, int itask, double h)
{
  Fixture f;
  const double v0 = 10.0, lev = 2.0, d = sqrt(v0 * v0 - 2.0 * GRAV * lev);
  const double tup = (v0 - d) / GRAV, tdown = (v0 + d) / GRAV;
  double t;
  int flag, dir, rf[1];
  for (dir = -1; dir <= 1; dir++) {
    int rootdir[1];
    rootdir[0] = dir;
    Setup(&f, BALL, 0.0, v0, mode, h);
    f.p.root  = G_Z_LEVEL;
    f.p.level = lev;
    LGNRootInit(f.mem, 1, Roots);
    CHECK(LGNSetRootDirection(f.mem, rootdir) == LGN_SUCCESS, "LGNSetRootDirection");
    if (dir >= 0) {
      flag = SolveTo(&f, 2.5, itask, &t);
      LGNGetRootInfo(f.mem, rf);
      CHECK(flag == LGN_ROOT_RETURN && rf[0] == 1, "dir %d: the rise (%s, rf %d)", dir,
            LGNGetReturnFlagName(flag), rf[0]);
      CheckEvent(t, tup, "rising through z = 2", mode, itask);
    }
    if (dir <= 0) {
      flag = SolveTo(&f, 2.5, itask, &t);
      LGNGetRootInfo(f.mem, rf);
      CHECK(flag == LGN_ROOT_RETURN && rf[0] == -1, "dir %d: the fall (%s, rf %d)", dir,
            LGNGetReturnFlagName(flag), rf[0]);
      CheckEvent(t, tdown, "falling through z = 2", mode, itask);
    }
    flag = SolveTo(&f, 2.5, itask, &t);
    CHECK(flag == LGN_SUCCESS && fabs(t - 2.5) < 1e-12 + (itask == LGN_ONE_STEP ? 1.0 : 0.0),
          "dir %d: no other root up to t = 2.5 (%s)", dir, LGNGetReturnFlagName(flag));
    Teardown(&f);
  }
}

/* ---- two roots in one step, in order; two at the same time, together ---- */
static void TestTwoInOneStep(Mode mode, int itask)
{
  Fixture f;
  const double z0 = 10.0, t1 = sqrt(2.0 * (z0 - 1.0) / GRAV), t2 = sqrt(2.0 * (z0 - 0.9) / GRAV);
  double t, tcur1, tcur2;
  int flag, rf[2];
  /* large steps: both crossings (t = 1.3546, 1.3621) lie in one step */
  Setup(&f, BALL, z0, 0.0, mode, 0.5);
  f.p.root = G_TWO_LEVELS;
  f.p.level = 1.0;
  f.p.level2 = 0.9;
  LGNRootInit(f.mem, 2, Roots);
  flag = SolveTo(&f, 1.45, itask, &t);
  LGNGetRootInfo(f.mem, rf);
  LGNGetCurrentTime(f.mem, &tcur1);
  CHECK(flag == LGN_ROOT_RETURN && rf[0] == -1 && rf[1] == 0,
        "first of two: %s, rf = (%d, %d)", LGNGetReturnFlagName(flag), rf[0], rf[1]);
  CheckEvent(t, t1, "first of two roots", mode, itask);
  flag = SolveTo(&f, 1.45, itask, &t);
  LGNGetRootInfo(f.mem, rf);
  LGNGetCurrentTime(f.mem, &tcur2);
  CHECK(flag == LGN_ROOT_RETURN && rf[0] == 0 && rf[1] == -1,
        "second of two: %s, rf = (%d, %d)", LGNGetReturnFlagName(flag), rf[0], rf[1]);
  CheckEvent(t, t2, "second of two roots", mode, itask);
  CHECK(tcur1 == tcur2 && tcur1 > t2, "both in one step (the step ends at %g, %g)", tcur1, tcur2);
  if (itask == LGN_ONE_STEP) {
    /* IDA: the step's end, not returned because of the roots, comes next */
    flag = LGNSolve(f.mem, 1.45, &t, f.q, f.v, LGN_ONE_STEP);
    CHECK(flag == LGN_SUCCESS && t == tcur2, "ONE_STEP then returns the step end %g (t = %g, %s)",
          tcur2, t, LGNGetReturnFlagName(flag));
  } else {
    flag = SolveTo(&f, 1.45, itask, &t);
    CHECK(flag == LGN_SUCCESS && t == 1.45, "then tout (t = %.17g, %s)", t,
          LGNGetReturnFlagName(flag));
  }
  Teardown(&f);

  /* the same root of two functions: one return, both reported */
  Setup(&f, BALL, z0, 0.0, mode, 0.5);
  f.p.root = G_SAME_TIME;
  f.p.level = 1.0;
  LGNRootInit(f.mem, 2, Roots);
  flag = SolveTo(&f, 2.0, itask, &t);
  LGNGetRootInfo(f.mem, rf);
  CHECK(flag == LGN_ROOT_RETURN && rf[0] == -1 && rf[1] == -1,
        "two functions, one root: %s, rf = (%d, %d)", LGNGetReturnFlagName(flag), rf[0], rf[1]);
  CheckEvent(t, t1, "a root of two functions", mode, itask);
  flag = SolveTo(&f, 2.0, itask, &t);
  CHECK(flag == LGN_SUCCESS, "and no second return (%s at %g)", LGNGetReturnFlagName(flag), t);
  Teardown(&f);
}

/* ---- a root exactly at a step end (and at tout), and g = 0 at the start ---- */
static void TestRootAtStepEnd(int itask)
{
  Fixture f;
  double t;
  int flag, nroot = 0, rf[1];
  /* g = t - 0.5 with h = 0.125: exactly 0 at the end of the fourth step */
  Setup(&f, BALL, 10.0, 0.0, FIXED, 0.125);
  f.p.root = G_TIME;
  f.p.level = 0.5;
  LGNRootInit(f.mem, 1, Roots);
  for (;;) {
    flag = SolveTo(&f, 1.0, itask, &t);
    if (flag != LGN_ROOT_RETURN) break;
    nroot++;
    LGNGetRootInfo(f.mem, rf);
    CHECK(t == 0.5 && rf[0] == 1, "the root at the step end: t = %.17g, rf = %d", t, rf[0]);
  }
  CHECK(nroot == 1 && flag == LGN_SUCCESS && t == 1.0,
        "found once (%d times), then t = 1 (%s, %s)", nroot, LGNGetReturnFlagName(flag),
        TaskName(itask));
  Teardown(&f);

  /* tout at the root: LGN_ROOT_RETURN there, then not again */
  if (itask == LGN_NORMAL) {
    Setup(&f, BALL, 10.0, 0.0, FIXED, 0.125);
    f.p.root = G_TIME;
    f.p.level = 0.5;
    LGNRootInit(f.mem, 1, Roots);
    flag = LGNSolve(f.mem, 0.5, &t, f.q, f.v, LGN_NORMAL);
    CHECK(flag == LGN_ROOT_RETURN && t == 0.5, "tout at the root: %s at %.17g",
          LGNGetReturnFlagName(flag), t);
    flag = LGNSolve(f.mem, 0.5, &t, f.q, f.v, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS && t == 0.5, "the same tout again: %s at %.17g",
          LGNGetReturnFlagName(flag), t);
    flag = LGNSolve(f.mem, 1.0, &t, f.q, f.v, LGN_NORMAL);
    CHECK(flag == LGN_SUCCESS && t == 1.0, "then t = 1: %s", LGNGetReturnFlagName(flag));
    Teardown(&f);
  }

  /* g = t exactly 0 at the start: not a root */
  Setup(&f, BALL, 10.0, 0.0, FIXED, 0.125);
  f.p.root = G_TIME;
  f.p.level = 0.0;
  LGNRootInit(f.mem, 1, Roots);
  nwarn = 0;
  flag = SolveTo(&f, 1.0, itask, &t);
  CHECK(flag == LGN_SUCCESS && t == 1.0 && nwarn == 0,
        "g = 0 at the start is no root (%s, %d warnings)", LGNGetReturnFlagName(flag), nwarn);
  Teardown(&f);

  /* a state event at a step end: z = 0 at t = 0.5 in exact arithmetic */
  Setup(&f, BALL, 0.5 * GRAV * 0.25, 0.0, FIXED, 0.125);
  f.p.root = G_Z;
  LGNRootInit(f.mem, 1, Roots);
  nroot = 0;
  for (;;) {
    flag = SolveTo(&f, 1.0, itask, &t);
    if (flag != LGN_ROOT_RETURN) break;
    nroot++;
    CHECK(fabs(t - 0.5) <= TOL_EVENT, "the impact at the step end: t = %.17g", t);
  }
  CHECK(nroot == 1 && flag == LGN_SUCCESS, "the impact at a step end found once (%d)", nroot);
  Teardown(&f);
}

/* ---- g exactly 0 at the start and a root in the first step: a ball
 * thrown up from z = 0 lands again at 2 v0 / grav inside one large step
 * (g at the start is not a root, the landing is) ---- */
static void TestZeroStartRootInFirstStep(Mode mode, int itask)
{
  Fixture f;
  const double v0 = 1.0, tl = 2.0 * v0 / GRAV;
  double t;
  int flag, rf[1];
  Setup(&f, BALL, 0.0, v0, mode, 0.5);
  if (mode == ADAPTIVE) LGNSetInitStep(f.mem, 0.5);
  f.p.root = G_Z;
  LGNRootInit(f.mem, 1, Roots);
  flag = SolveTo(&f, 0.5, itask, &t);
  LGNGetRootInfo(f.mem, rf);
  CHECK(flag == LGN_ROOT_RETURN && rf[0] == -1,
        "landing in the first step (%s, %s): %s at %g, rf %d", ModeName(mode), TaskName(itask),
        LGNGetReturnFlagName(flag), t, rf[0]);
  CheckEvent(t, tl, "landing in the first step", mode, itask);
  Teardown(&f);
}

/* ---- a bouncing ball: LGNReInit at each impact with v -> -e v ---- */
static void TestBounce(Mode mode, int itask, double h)
{
  Fixture f;
  const double z0 = 10.0, e = 0.8, t1 = sqrt(2.0 * z0 / GRAV);
  double t, texact = t1, dt = 2.0 * e * t1;
  int flag, k;
  long int nge = 0;
  Setup(&f, BALL, z0, 0.0, mode, h);
  f.p.root = G_Z;
  LGNRootInit(f.mem, 1, Roots);
  for (k = 0; k < 4; k++) {
    flag = SolveTo(&f, 20.0, itask, &t);
    CHECK(flag == LGN_ROOT_RETURN, "bounce %d: %s", k, LGNGetReturnFlagName(flag));
    CheckEvent(t, texact, "impact after a bounce", mode, itask);
    /* the velocity reversed, z exactly 0 (so g = 0 at the new start) */
    N_VGetArrayPointer(f.q)[0] = 0.0;
    N_VGetArrayPointer(f.v)[0] = -e * V(&f);
    CHECK(LGNReInit(f.mem, t, f.q, f.v) == LGN_SUCCESS, "LGNReInit");
    LGNGetNumGEvals(f.mem, &nge);
    CHECK(nge == 0, "LGNReInit restarts the g count (%ld)", nge);
    texact += dt;
    dt *= e;
  }
  Teardown(&f);
}

/* ---- root of the interpolated solution: a spring z'' = -z ---- */
static void TestSpring(Mode mode, int itask, double h)
{
  Fixture f;
  double t;
  int flag, k;
  Setup(&f, SPRING, 1.0, 0.0, mode, h);
  f.p.root = G_Z;
  LGNRootInit(f.mem, 1, Roots);
  for (k = 0; k < 3; k++) {
    double z, vz;
    flag = SolveTo(&f, 10.0, itask, &t);
    z  = Z(&f);
    vz = V(&f);
    CHECK(flag == LGN_ROOT_RETURN && fabs(z) <= 1e-12 * fabs(vz),
          "spring root %d (%s, %s): t = %.15g, z = %.3g, v = %.3g", k, ModeName(mode),
          TaskName(itask), t, z, vz);
    /* the integration error, not the root finding, sets the distance to
     * (2k+1) pi / 2 */
    CHECK(fabs(t - (2 * k + 1) * PI / 2) <= 1e-2, "spring root %d near %g: %g", k,
          (2 * k + 1) * PI / 2, t);
  }
  Teardown(&f);
}

/* ---- LGN_NORMAL with outputs inside a step: never a root beyond tout ---- */
static void TestOutputsInsideStep(void)
{
  Fixture f;
  const double z0 = 10.0, ts = sqrt(2.0 * z0 / GRAV);
  double t = 0.0, tout, tlast = 0.0;
  int flag, nroot = 0;
  Setup(&f, BALL, z0, 0.0, ADAPTIVE, 0.0); /* exact steps: h doubles */
  f.p.root = G_Z;
  LGNRootInit(f.mem, 1, Roots);
  for (tout = 0.01; tout <= 2.0; tout += 0.01) {
    for (;;) {
      flag = LGNSolve(f.mem, tout, &t, f.q, f.v, LGN_NORMAL);
      CHECK(t >= tlast && t <= tout + 1e-14, "outputs in order: %.17g after %.17g (tout %g)", t,
            tlast, tout);
      tlast = t;
      if (flag != LGN_ROOT_RETURN) break;
      nroot++;
      CheckEvent(t, ts, "impact between outputs", ADAPTIVE, LGN_NORMAL);
    }
    if (flag != LGN_SUCCESS) break;
  }
  CHECK(nroot == 1 && flag == LGN_SUCCESS, "one impact among 200 outputs (%d, %s)", nroot,
        LGNGetReturnFlagName(flag));
  Teardown(&f);
}

/* ---- off, warning, bad input and failures ---- */
static void TestMisc(void)
{
  Fixture f;
  double t;
  int flag, rd[2] = {0, 0}, rf[2];
  long int nge;

  /* nrtfn = 0: off */
  Setup(&f, BALL, 10.0, 0.0, FIXED, 0.01);
  f.p.root = G_Z;
  LGNRootInit(f.mem, 1, Roots);
  CHECK(LGNRootInit(f.mem, 0, NULL) == LGN_SUCCESS, "nrtfn = 0 with g NULL");
  flag = LGNSolve(f.mem, 2.0, &t, f.q, f.v, LGN_NORMAL);
  LGNGetNumGEvals(f.mem, &nge);
  CHECK(flag == LGN_SUCCESS && t == 2.0 && nge == 0, "root finding off: %s, %ld g evals",
        LGNGetReturnFlagName(flag), nge);
  CHECK(LGNSetRootDirection(f.mem, rd) == LGN_ILL_INPUT && strstr(last_msg, "LGNRootInit"),
        "LGNSetRootDirection without root finding: '%s'", last_msg);
  Teardown(&f);

  /* a g_i identically 0: one warning, or none with LGNSetNoInactiveRootWarn */
  {
    int quiet;
    for (quiet = 0; quiet <= 1; quiet++) {
      Setup(&f, BALL, 10.0, 0.0, FIXED, 0.01);
      f.p.root = G_ZERO;
      f.p.level = 5.0;
      LGNRootInit(f.mem, 2, Roots);
      if (quiet) LGNSetNoInactiveRootWarn(f.mem);
      nwarn = 0;
      flag = SolveTo(&f, 2.0, LGN_NORMAL, &t);
      LGNGetRootInfo(f.mem, rf);
      CHECK(flag == LGN_ROOT_RETURN && rf[0] == -1 && rf[1] == 0 &&
                nwarn == (quiet ? 0 : 1),
            "g_2 = 0 ignored (%s, rf = (%d, %d), %d warnings, quiet %d)",
            LGNGetReturnFlagName(flag), rf[0], rf[1], nwarn, quiet);
      Teardown(&f);
    }
  }

  /* LGNInit again after LGNRootInit: root finding kept, from the new state */
  Setup(&f, BALL, 10.0, 0.0, FIXED, 0.01);
  f.p.root = G_Z;
  LGNRootInit(f.mem, 1, Roots);
  flag = LGNSolve(f.mem, 0.5, &t, f.q, f.v, LGN_NORMAL);
  N_VGetArrayPointer(f.q)[0] = 5.0;
  N_VGetArrayPointer(f.v)[0] = 0.0;
  CHECK(flag == LGN_SUCCESS && LGNInit(f.mem, 1.0, f.q, f.v) == LGN_SUCCESS, "LGNInit again");
  flag = LGNSolve(f.mem, 5.0, &t, f.q, f.v, LGN_NORMAL);
  CHECK(flag == LGN_ROOT_RETURN && fabs(t - 1.0 - sqrt(10.0 / GRAV)) <= TOL_EVENT,
        "after LGNInit again: impact at %.17g (%s)", t, LGNGetReturnFlagName(flag));
  Teardown(&f);

  /* bad input */
  Setup(&f, BALL, 10.0, 0.0, FIXED, 0.01);
  CHECK(LGNRootInit(NULL, 1, Roots) == LGN_MEM_NULL, "LGNRootInit(NULL)");
  CHECK(LGNSetRootDirection(NULL, rd) == LGN_MEM_NULL, "LGNSetRootDirection(NULL)");
  CHECK(LGNSetNoInactiveRootWarn(NULL) == LGN_MEM_NULL, "LGNSetNoInactiveRootWarn(NULL)");
  CHECK(LGNGetRootInfo(NULL, rf) == LGN_MEM_NULL, "LGNGetRootInfo(NULL)");
  CHECK(LGNGetNumGEvals(NULL, &nge) == LGN_MEM_NULL, "LGNGetNumGEvals(NULL)");
  CHECK(LGNRootInit(f.mem, -1, Roots) == LGN_ILL_INPUT && strstr(last_msg, "nrtfn"),
        "nrtfn < 0: '%s'", last_msg);
  CHECK(LGNRootInit(f.mem, 2, NULL) == LGN_ILL_INPUT && strstr(last_msg, "g = NULL"),
        "g NULL: '%s'", last_msg);
  f.p.root = G_TWO_LEVELS;
  CHECK(LGNRootInit(f.mem, 2, Roots) == LGN_SUCCESS, "LGNRootInit(2)");
  CHECK(LGNSetRootDirection(f.mem, NULL) == LGN_ILL_INPUT && strstr(last_msg, "rootdir"),
        "rootdir NULL: '%s'", last_msg);
  rd[1] = 2;
  CHECK(LGNSetRootDirection(f.mem, rd) == LGN_ILL_INPUT && strstr(last_msg, "rootdir[1]"),
        "rootdir[1] = 2: '%s'", last_msg);
  CHECK(LGNGetRootInfo(f.mem, NULL) == LGN_ILL_INPUT && strstr(last_msg, "rootsfound"),
        "rootsfound NULL: '%s'", last_msg);
  CHECK(LGNGetNumGEvals(f.mem, NULL) == LGN_ILL_INPUT && strstr(last_msg, "ngevals"),
        "ngevals NULL: '%s'", last_msg);
  CHECK(strcmp(LGNGetReturnFlagName(LGN_ROOT_RETURN), "LGN_ROOT_RETURN") == 0 &&
            strcmp(LGNGetReturnFlagName(LGN_RTFUNC_FAIL), "LGN_RTFUNC_FAIL") == 0,
        "flag names");
  Teardown(&f);

  /* calls before LGNInit */
  {
    SUNContext ctx;
    void *mem;
    SUNContext_Create(NULL, &ctx);
    mem = LGNCreate(ctx);
    LGNSetErrHandlerFn(mem, Capture, NULL);
    CHECK(LGNRootInit(mem, 1, Roots) == LGN_NO_MALLOC && strstr(last_msg, "LGNInit"),
          "LGNRootInit before LGNInit: '%s'", last_msg);
    CHECK(LGNSetRootDirection(mem, rd) == LGN_NO_MALLOC && strstr(last_msg, "LGNInit"),
          "LGNSetRootDirection before LGNInit: '%s'", last_msg);
    CHECK(LGNGetRootInfo(mem, rf) == LGN_SUCCESS, "LGNGetRootInfo before LGNInit: nothing");
    CHECK(LGNGetNumGEvals(mem, &nge) == LGN_SUCCESS && nge == 0, "no g evaluations");
    LGNFree(&mem);
    SUNContext_Free(&ctx);
  }

  /* a failing root function: recoverable, fatal, at the start, NaN */
  {
    const int rets[3] = {1, -1, -1};
    const double after[3] = {0.3, 0.3, -1.0};
    int k, mode;
    for (mode = FIXED; mode <= ADAPTIVE; mode++) {
      for (k = 0; k < 4; k++) {
        Setup(&f, BALL, 10.0, 0.0, (Mode)mode, 0.01);
        f.p.root = k < 3 ? G_FAIL : G_NAN;
        f.p.level = k < 3 ? after[k] : 0.3;
        f.p.fail_ret = k < 3 ? rets[k] : 0;
        LGNRootInit(f.mem, 1, Roots);
        last_msg[0] = '\0';
        flag = LGNSolve(f.mem, 2.0, &t, f.q, f.v, LGN_NORMAL);
        CHECK(flag == LGN_RTFUNC_FAIL && strstr(last_msg, "root function") &&
                  t <= 0.3 + 0.5 && t >= (k == 2 ? 0.0 : 0.3),
              "failing g %d (%s): %s at t = %g, '%s'", k, ModeName((Mode)mode),
              LGNGetReturnFlagName(flag), t, last_msg);
        /* still usable: root finding off, on to t = 2 */
        LGNRootInit(f.mem, 0, NULL);
        flag = LGNSolve(f.mem, 2.0, &t, f.q, f.v, LGN_NORMAL);
        CHECK(flag == LGN_SUCCESS, "usable after the failure: %s", LGNGetReturnFlagName(flag));
        Teardown(&f);
      }
    }
  }
}

int main(void)
{
  int mode, itask;
  for (mode = FIXED; mode <= ADAPTIVE; mode++) {
    for (itask = LGN_NORMAL; itask <= LGN_ONE_STEP; itask++) {
      TestImpact((Mode)mode, itask, mode == FIXED ? 0.01 : 0.0);
      TestImpact((Mode)mode, itask, mode == FIXED ? 0.037 : 0.05);
      TestDirection((Mode)mode, itask, mode == FIXED ? 0.01 : 0.0);
      TestTwoInOneStep((Mode)mode, itask);
      TestBounce((Mode)mode, itask, mode == FIXED ? 0.01 : 0.0);
      TestSpring((Mode)mode, itask, mode == FIXED ? 0.01 : 0.0);
      TestZeroStartRootInFirstStep((Mode)mode, itask);
    }
  }
  TestRootAtStepEnd(LGN_NORMAL);
  TestRootAtStepEnd(LGN_ONE_STEP);
  TestOutputsInsideStep();
  TestMisc();
  printf("largest event-time error (falling ball, exact dense output): %.3g s\n",
         max_event_err);
  return test_summary("test_roots");
}
