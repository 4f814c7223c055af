/* -----------------------------------------------------------------------------
 * Lignum teaching example: a pendulum bouncing on a stop.
 *
 * Shows: events. A root function g(t, q, v) (LGNRootInit), its direction
 * (LGNSetRootDirection), LGNSolve returning LGN_ROOT_RETURN at the root
 * (LGNGetRootInfo), a jump of the velocity there and the restart with
 * LGNReInit; error control (LGN_STEP_ADAPTIVE, LGNSStolerances) and the
 * counters LGNGetNumSteps, LGNGetNumGEvals.
 *
 * A rod (a slender cylinder: mass 1 kg, length 1 m, radius 0.02 m) on
 * R^3 x SO(3), hinged at one end to the ground by a revolute joint with
 * axis z (lignum_joints.h: five constraints), swings in the x-y plane under
 * gravity (0, -9.81, 0). It is released at rest at 60 degrees from the
 * downward vertical; a stop at the vertical (the plane x = 0) lets it swing
 * only on the side x > 0. The impact is an event: the root of
 *
 *   g(t, q, v) = x of the centre of mass, decreasing (LGNSetRootDirection -1).
 *
 * At each LGN_ROOT_RETURN the velocity is reversed with the restitution
 * coefficient e (v -> -e v: every velocity of the hinged rod is
 * proportional to its angular velocity, so this is Newton's law of
 * restitution at the stop and keeps B v = 0) and the integration restarts
 * there with LGNReInit; root finding restarts with it.
 *
 * Self-checks (exit status), against an independent computation: the
 * physical pendulum theta'' = -w0^2 sin(theta), w0^2 = m g (L/2) / I_pivot,
 * takes a quarter period T(theta_0)/4 to the first impact and a half period
 * T(theta_k)/2 between impacts, T(a) = 4 K(sin(a/2)) / w0 with the complete
 * elliptic integral K (arithmetic-geometric mean); each impact keeps e^2 of
 * the energy above the rest position, so 1 - cos(theta_{k+1}) =
 * e^2 (1 - cos(theta_k)). Error control bounds the error per unit step
 * (user guide section 8.1), so the global error goes with tol: the impact
 * times must agree to 300 tol s (47 - 67 tol are seen from tol = 1e-5 to
 * 1e-8, 5.3e-5 s at tol = 1e-6), the energy after each flight with the
 * energy after the last impact and the energy ratios between impacts with
 * e^2 to 100 tol (11 - 14 tol are seen), and every root must be the stop,
 * approached from x > 0.
 *
 * Output: for each impact, its time and the exact one, the energy before and
 * after it and the ratio to the previous one (e^2), the steps taken; then
 * the largest deviations and the counters.
 * Options: --e <restitution> (default 0.7), --bounces <n> (default 8),
 * --tol <rtol = atol> (default 1e-6), --quick (3 bounces, for valgrind).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_joints.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#define MASS  1.0
#define LEN   1.0
#define RAD   0.02
#define GRAV  9.81

typedef struct {
  double J[3]; /* principal moments, body frame: rod along body x */
  LGNJoints joints;
} Pendulum;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  Pendulum *p = (Pendulum *)ud;
  int i;
  (void)t; (void)q;
  for (i = 0; i < 3; i++) {
    SM_ELEMENT_D(M, i, i)         = MASS;
    SM_ELEMENT_D(M, 3 + i, 3 + i) = p->J[i];
  }
  return 0;
}

/* g = (weight, Omega x J Omega): M vdot + g + B^T lambda = 0 */
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  Pendulum *p = (Pendulum *)ud;
  const double *W = N_VGetArrayPointer(v) + 3, *J = p->J;
  double *gg = N_VGetArrayPointer(g);
  (void)t; (void)q;
  gg[0] = 0.0;
  gg[1] = MASS * GRAV;
  gg[2] = 0.0;
  gg[3] = W[1] * J[2] * W[2] - W[2] * J[1] * W[1];
  gg[4] = W[2] * J[0] * W[0] - W[0] * J[2] * W[2];
  gg[5] = W[0] * J[1] * W[1] - W[1] * J[0] * W[0];
  return 0;
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Pendulum *)ud)->joints, t, q, phi);
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Pendulum *)ud)->joints, t, q, B);
}

/* The event: the centre of mass reaches the plane of the stop, x = 0. */
static int Stop(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *gout, void *ud)
{
  (void)t; (void)v; (void)ud;
  gout[0] = N_VGetArrayPointer(q)[0];
  return 0;
}

/* Energy above the rest position (centre of mass at y = -L/2). */
static double Energy(const Pendulum *p, N_Vector q, N_Vector v)
{
  const double *x = N_VGetArrayPointer(q), *u = N_VGetArrayPointer(v);
  double E = 0.5 * MASS * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  int i;
  for (i = 0; i < 3; i++) E += 0.5 * p->J[i] * u[3 + i] * u[3 + i];
  return E + MASS * GRAV * (x[1] + 0.5 * LEN);
}

/* ---- the independent computation: the physical pendulum ---- */

/* Complete elliptic integral of the first kind K(k) = pi / (2 AGM(1, k')). */
static double EllipticK(double k)
{
  double a = 1.0, b = sqrt(1.0 - k * k), an;
  int it;
  for (it = 0; it < 40 && fabs(a - b) > 1e-15 * a; it++) { /* quadratic: a few */
    an = 0.5 * (a + b);
    b  = sqrt(a * b);
    a  = an;
  }
  return acos(-1.0) / (2.0 * a);
}

/* The period of the pendulum with amplitude amp. */
static double Period(double amp, double w0)
{
  return 4.0 * EllipticK(sin(0.5 * amp)) / w0;
}

static int Check(int ok, const char *what)
{
  if (!ok) fprintf(stderr, "FAILED: %s\n", what);
  return ok ? 0 : 1;
}

int main(int argc, char **argv)
{
  const double pi = acos(-1.0), theta0 = pi / 3.0;
  double e = 0.7, tol = 1e-6, Ipivot, w0, t = 0.0, texact, amp = theta0, Eb_prev = 0.0;
  double Ebefore, Eafter, Eprev, max_dt = 0.0, max_dE = 0.0, *qd;
  const double sa[3] = {-0.5 * LEN, 0.0, 0.0}, zero[3] = {0.0, 0.0, 0.0};
  const double axis[3] = {0.0, 0.0, 1.0}, rotvec[3] = {0.0, 0.0, theta0 - 0.5 * pi};
  int nbounce = 8, k, i, flag, fails = 0, rootdir[1] = {-1}, rootsfound[1];
  long int nst = 0, nge = 0, nst_total = 0, nge_total = 0;
  SUNContext ctx = NULL;
  LGNGroup G = NULL;
  N_Vector q = NULL, v = NULL, tmpl = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  Pendulum p;
  sunindextype m;

  for (i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--e") == 0 && i + 1 < argc) {
      e = atof(argv[++i]);
    } else if (strcmp(argv[i], "--bounces") == 0 && i + 1 < argc) {
      nbounce = atoi(argv[++i]);
    } else if (strcmp(argv[i], "--tol") == 0 && i + 1 < argc) {
      tol = atof(argv[++i]);
    } else if (strcmp(argv[i], "--quick") == 0) {
      nbounce = 3;
    } else {
      fprintf(stderr, "usage: %s [--e <restitution in (0, 1]>] [--bounces <n>] [--tol <rtol = atol>] [--quick]\n",
              argv[0]);
      return 2;
    }
  }
  if (!(e > 0.0 && e <= 1.0) || nbounce < 1) {
    fprintf(stderr, "e must lie in (0, 1] and bounces be >= 1\n");
    return 2;
  }

  /* the rod: along body x, hinged at body (-L/2, 0, 0) to the origin */
  p.J[0] = 0.5 * MASS * RAD * RAD;
  p.J[1] = p.J[2] = MASS * (3.0 * RAD * RAD + LEN * LEN) / 12.0;
  Ipivot = p.J[2] + MASS * 0.25 * LEN * LEN;
  w0     = sqrt(MASS * GRAV * 0.5 * LEN / Ipivot);

  SUNContext_Create(NULL, &ctx);
  G = LGNGroup_R3xSO3();
  p.joints = LGNJoints_Create(G);
  LGNJoints_AddRevolute(p.joints, 0, sa, axis, LGN_GROUND, zero, axis);
  m = LGNJoints_NumConstraints(p.joints);

  /* released at rest at theta0: centre of mass at (L/2)(sin, -cos, 0),
   * body x along it (a rotation about z by theta0 - pi/2) */
  q  = N_VNew_Serial(7, ctx);
  v  = N_VNew_Serial(6, ctx);
  qd = N_VGetArrayPointer(q);
  qd[0] = 0.5 * LEN * sin(theta0);
  qd[1] = -0.5 * LEN * cos(theta0);
  qd[2] = 0.0;
  LGNQuaternionFromRotationVector(rotvec, qd + 3);
  N_VConst(0.0, v);

  mem = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, &p);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  tmpl = N_VNew_Serial(6 + m, ctx);
  A    = SUNDenseMatrix(6 + m, 6 + m, ctx);
  LS   = LGNLinSol_Dense(tmpl, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, tol, tol);
  /* events: the stop, approached from x > 0 only */
  if (!flag) flag = LGNRootInit(mem, 1, Stop);
  if (!flag) flag = LGNSetRootDirection(mem, rootdir);
  if (flag) {
    fprintf(stderr, "set-up failed: %s\n", LGNGetReturnFlagName(flag));
    return 1;
  }

  Eprev  = Energy(&p, q, v);
  texact = Period(amp, w0) / 4.0;
  printf("Pendulum bouncing on a stop: restitution e = %g, released at %g deg\n", e,
         theta0 * 180.0 / pi);
  printf("%6s %18s %18s %10s %12s %12s %10s %6s\n", "bounce", "t impact", "t exact",
         "|dt|", "E before", "E after", "E/E_prev", "steps");
  for (k = 1; k <= nbounce; k++) {
    flag = LGNSolve(mem, 100.0, &t, q, v, LGN_NORMAL);
    if (flag != LGN_ROOT_RETURN) {
      fprintf(stderr, "bounce %d: LGNSolve returned %s at t = %g\n", k,
              LGNGetReturnFlagName(flag), t);
      fails++;
      break;
    }
    LGNGetRootInfo(mem, rootsfound);
    fails += Check(rootsfound[0] == -1, "the root is the stop, approached from x > 0");
    LGNGetNumSteps(mem, &nst);
    LGNGetNumGEvals(mem, &nge);
    nst_total += nst;
    nge_total += nge;
    /* the impact: v -> -e v, and on from there */
    Ebefore = Energy(&p, q, v);
    N_VScale(-e, v, v);
    Eafter = Energy(&p, q, v);
    flag   = LGNReInit(mem, t, q, v);
    fails += Check(flag == LGN_SUCCESS, "LGNReInit at the impact");

    max_dt = fmax(max_dt, fabs(t - texact));
    max_dE = fmax(max_dE, fabs(Ebefore / Eprev - 1.0)); /* no loss in flight */
    if (k > 1) max_dE = fmax(max_dE, fabs(Eafter / Eprev - e * e));
    printf("%6d %18.12f %18.12f %10.2e %12.8f %12.8f %10.8f %6ld\n", k, t, texact,
           fabs(t - texact), Ebefore, Eafter, k > 1 ? Ebefore / Eb_prev : 1.0, nst);
    Eprev   = Eafter;
    Eb_prev = Ebefore;
    /* the next swing: out to the amplitude of the energy left, and back */
    amp     = acos(1.0 - e * e * (1.0 - cos(amp)));
    texact += Period(amp, w0) / 2.0;
  }
  printf("largest |t - t_exact| = %.2e s, largest |energy ratio - e^2| (and loss in "
         "flight) = %.2e\n", max_dt, max_dE);
  printf("%ld steps, %ld root function evaluations\n", nst_total, nge_total);
  /* error per unit step: the global error goes with tol (47 - 67 tol s in
   * the times, 11 - 14 tol in the energy ratios are seen from tol = 1e-5
   * to 1e-8) */
  fails += Check(max_dt <= 300.0 * tol, "impact times within 300 tol s of the physical pendulum's");
  fails += Check(max_dE <= 100.0 * tol,
                 "energy ratios e^2 (no loss in flight) within 100 tol");

  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  N_VDestroy(tmpl);
  LGNJoints_Destroy(&p.joints);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  printf("%s\n", fails == 0 ? "bouncing_pendulum: OK" : "bouncing_pendulum: FAILED");
  return fails == 0 ? 0 : 1;
}
