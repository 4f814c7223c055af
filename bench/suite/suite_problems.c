/* -----------------------------------------------------------------------------
 * Lignum benchmarks, the standard multibody suite: the problems (see
 * suite_problem.h), each written once as M, g, Phi, B (and Phi_t).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "suite_problem.h"

/* =============================================================================
 * Andrews' squeezing mechanism (Test Set for IVP Solvers, andrews.f; Hairer
 * and Wanner, Solving ODEs II, section VII.7): 7 rigid bodies in the plane,
 * q = (beta, Theta, gamma, Phi, delta, Omega, epsilon) the joint angles,
 * 6 loop-closure constraints, a motor torque mom and a spring c0; index 3,
 * t in [0, 0.03] s.
 * ===========================================================================*/

/* Parameters (andrews.f, common /andcom/). */
static const double m1 = .04325, m2 = .00365, m3 = .02373, m4 = .00706, m5 = .07050,
                    m6 = .00706, m7 = .05498;
static const double xa = -.06934, ya = -.00227, xb = -.03635, yb = .03273, xc = .014,
                    yc = .072, c0 = 4530.0;
static const double i1 = 2.194e-6, i2 = 4.410e-7, i3 = 5.255e-6, i4 = 5.667e-7, i5 = 1.169e-5,
                    i6 = 5.667e-7, i7 = 1.912e-5;
static const double d = 28e-3, da = 115e-4, e = 2e-2, ea = 1421e-5, rr = 7e-3, ra = 92e-5,
                    l0 = 7785e-5;
static const double ss = 35e-3, sa = 1874e-5, sb = 1043e-5, sc = 18e-3, sd = 2e-2,
                    ta = 2308e-5, tb = 916e-5;
static const double u = 4e-2, ua = 1228e-5, ub = 449e-5, zf = 2e-2, zt = 4e-2, fa = 1421e-5,
                    mom = 33e-3;

static void AndrewsMass(double t, const double *q, double *M)
{
  const double coth = cos(q[1]), siph = sin(q[3]), siom = sin(q[5]);
  const double ee = e - ea, zz = zf - fa;
  (void)t;
  memset(M, 0, 49 * sizeof(double));
  M[0 * 7 + 0] = m1 * ra * ra + m2 * (rr * rr - 2 * da * rr * coth + da * da) + i1 + i2;
  M[1 * 7 + 0] = M[0 * 7 + 1] = m2 * (da * da - da * rr * coth) + i2;
  M[1 * 7 + 1] = m2 * da * da + i2;
  M[2 * 7 + 2] = m3 * (sa * sa + sb * sb) + i3;
  M[3 * 7 + 3] = m4 * ee * ee + i4;
  M[4 * 7 + 3] = M[3 * 7 + 4] = m4 * (ee * ee + zt * ee * siph) + i4;
  M[4 * 7 + 4] = m4 * (zt * zt + 2 * zt * ee * siph + ee * ee) + m5 * (ta * ta + tb * tb) + i4 + i5;
  M[5 * 7 + 5] = m6 * zz * zz + i6;
  M[6 * 7 + 5] = M[5 * 7 + 6] = m6 * (zz * zz - u * zz * siom) + i6;
  M[6 * 7 + 6] = m6 * (zz * zz - 2 * u * zz * siom + u * u) + m7 * (ua * ua + ub * ub) + i6 + i7;
}

/* g = -f, f the applied and centrifugal forces of andrews.f (ff). */
static void AndrewsForce(double t, const double *q, const double *v, double *g)
{
  const double sith = sin(q[1]), coga = cos(q[2]), siga = sin(q[2]), coph = cos(q[3]);
  const double coom = cos(q[5]);
  const double bep = v[0], thp = v[1], php = v[3], dep = v[4], omp = v[5], epp = v[6];
  /* the spring between point D of body 3 and the fixed point C */
  const double xd = sd * coga + sc * siga + xb, yd = sd * siga - sc * coga + yb;
  const double lang = sqrt((xd - xc) * (xd - xc) + (yd - yc) * (yd - yc));
  const double force = -c0 * (lang - l0) / lang;
  const double fx = force * (xd - xc), fy = force * (yd - yc);
  (void)t;
  g[0] = -(mom - m2 * da * rr * thp * (thp + 2 * bep) * sith);
  g[1] = -(m2 * da * rr * bep * bep * sith);
  g[2] = -(fx * (sc * coga - sd * siga) + fy * (sd * coga + sc * siga));
  g[3] = -(m4 * zt * (e - ea) * dep * dep * coph);
  g[4] = -(-m4 * zt * (e - ea) * php * (php + 2 * dep) * coph);
  g[5] = -(-m6 * u * (zf - fa) * epp * epp * coom);
  g[6] = -(m6 * u * (zf - fa) * omp * (omp + 2 * epp) * coom);
}

static void AndrewsConstraints(double t, const double *q, double *phi)
{
  const double sibe = sin(q[0]), cobe = cos(q[0]), siga = sin(q[2]), coga = cos(q[2]);
  const double side = sin(q[4]), code = cos(q[4]), siep = sin(q[6]), coep = cos(q[6]);
  const double sibeth = sin(q[0] + q[1]), cobeth = cos(q[0] + q[1]);
  const double siphde = sin(q[3] + q[4]), cophde = cos(q[3] + q[4]);
  const double siomep = sin(q[5] + q[6]), coomep = cos(q[5] + q[6]);
  (void)t;
  phi[0] = rr * cobe - d * cobeth - ss * siga - xb;
  phi[1] = rr * sibe - d * sibeth + ss * coga - yb;
  phi[2] = rr * cobe - d * cobeth - e * siphde - zt * code - xa;
  phi[3] = rr * sibe - d * sibeth + e * cophde - zt * side - ya;
  phi[4] = rr * cobe - d * cobeth - zf * coomep - u * siep - xa;
  phi[5] = rr * sibe - d * sibeth - zf * siomep + u * coep - ya;
}

static void AndrewsJacobian(double t, const double *q, double *B)
{
  const double sibe = sin(q[0]), cobe = cos(q[0]), siga = sin(q[2]), coga = cos(q[2]);
  const double side = sin(q[4]), code = cos(q[4]), siep = sin(q[6]), coep = cos(q[6]);
  const double sibeth = sin(q[0] + q[1]), cobeth = cos(q[0] + q[1]);
  const double siphde = sin(q[3] + q[4]), cophde = cos(q[3] + q[4]);
  const double siomep = sin(q[5] + q[6]), coomep = cos(q[5] + q[6]);
  int k;
  (void)t;
  memset(B, 0, 42 * sizeof(double));
  for (k = 0; k < 3; k++) { /* the crank (beta, Theta) enters every loop */
    B[(2 * k) * 7 + 0] = -rr * sibe + d * sibeth;
    B[(2 * k) * 7 + 1] = d * sibeth;
    B[(2 * k + 1) * 7 + 0] = rr * cobe - d * cobeth;
    B[(2 * k + 1) * 7 + 1] = -d * cobeth;
  }
  B[0 * 7 + 2] = -ss * coga;
  B[1 * 7 + 2] = -ss * siga;
  B[2 * 7 + 3] = -e * cophde;
  B[2 * 7 + 4] = -e * cophde + zt * side;
  B[3 * 7 + 3] = -e * siphde;
  B[3 * 7 + 4] = -e * siphde - zt * code;
  B[4 * 7 + 5] = zf * siomep;
  B[4 * 7 + 6] = zf * siomep - u * coep;
  B[5 * 7 + 5] = -zf * coomep;
  B[5 * 7 + 6] = -zf * coomep - u * siep;
}

/* Initial values (andrews.f, init): consistent positions, at rest. */
static const double ANDREWS_Q0[7] = {
  -0.0617138900142764496358948458001, 0.0, 0.455279819163070380255912382449,
  0.222668390165885884674473185609, 0.487364979543842550225598953530,
  -0.222668390165885884674473185609, 1.23054744454982119249735015568};
static const double ANDREWS_V0[7] = {0, 0, 0, 0, 0, 0, 0};

/* Reference at t = 0.03 (andrews.f, solut: PSIDE at rtol = atol = 1e-14 on
 * a Cray C90): y1..7 positions, y8..14 velocities, y22..27 multipliers. */
static const double ANDREWS_Q_REF[7] = {
  0.1581077119629904e+2, -0.1575637105984298e+2, 0.4082224013073101e-1,
  -0.5347301163226948e+0, 0.5244099658805304e+0, 0.5347301163226948e+0,
  0.1048080741042263e+1};
static const double ANDREWS_V_REF[7] = {
  0.1139920302151208e+4, -0.1424379294994111e+4, 0.1103291221937134e+2,
  0.1929337464421385e+2, 0.5735699284790808e+0, -0.1929337464421385e+2,
  0.3231791658026955e+0};
static const double ANDREWS_LAMBDA_REF[6] = {
  0.1991753333731910e+3, -0.2975531228015052e+2, 0.2306654119098399e+2,
  0.3145271365475927e+2, 0.2264249232082739e+2, 0.1161740700019673e+2};

const SuiteProblem SUITE_ANDREWS = {
  "andrews", "Andrews' squeezing mechanism (Test Set), t = 0.03", 7, 6, 0.03,
  AndrewsMass, AndrewsForce, AndrewsConstraints, AndrewsJacobian, NULL, 0,
  ANDREWS_Q0, ANDREWS_V0, ANDREWS_Q_REF, ANDREWS_V_REF, ANDREWS_LAMBDA_REF,
  NULL, 0, NULL, 1e-9,
  "Test Set for IVP Solvers, andrews.f (PSIDE, tol 1e-14); positions good to ~1e-9"};

/* =============================================================================
 * The car axis (Test Set for IVP Solvers, caraxis.f; Schiehlen 1990): the
 * left and right wheel ends (xl, yl), (xr, yr) of an axis of length L on
 * springs, the left end on a bar through the origin, the right end's
 * support (xb, yb) = (sqrt(L^2 - yb^2), r sin(w t)) driven; masses
 * k = M eps^2 / 2, gravity g. Index 3, rheonomic, t in [0, 3].
 * Test Set: k y'' = f(y) + G^T lambda_TS, so g = -f and lambda = -lambda_TS.
 * ===========================================================================*/

static const double CA_EPS = 1e-2, CA_M = 10.0, CA_L = 1.0, CA_L0 = 0.5, CA_R = 0.1,
                    CA_W = 10.0, CA_G = 1.0;
#define CA_K (CA_M * CA_EPS * CA_EPS / 2.0)

/* The driven support point and its time derivative. */
static void CarSupport(double t, double *xb_, double *yb_, double *xbd, double *ybd)
{
  const double ybt = CA_R * sin(CA_W * t), ybdt = CA_R * CA_W * cos(CA_W * t);
  const double xbt = sqrt(CA_L * CA_L - ybt * ybt);
  *xb_ = xbt;
  *yb_ = ybt;
  *xbd = -ybt * ybdt / xbt;
  *ybd = ybdt;
}

static void CarMass(double t, const double *q, double *M)
{
  int i;
  (void)t;
  (void)q;
  memset(M, 0, 16 * sizeof(double));
  for (i = 0; i < 4; i++) M[i * 4 + i] = CA_K;
}

static void CarForce(double t, const double *q, const double *v, double *g)
{
  double xbt, ybt, xbd, ybd;
  const double xl = q[0], yl = q[1], xr = q[2], yr = q[3];
  const double Ll = sqrt(xl * xl + yl * yl);
  double Lr;
  (void)v;
  CarSupport(t, &xbt, &ybt, &xbd, &ybd);
  Lr = sqrt((xr - xbt) * (xr - xbt) + (yr - ybt) * (yr - ybt));
  g[0] = -((CA_L0 - Ll) * xl / Ll);
  g[1] = -((CA_L0 - Ll) * yl / Ll - CA_K * CA_G);
  g[2] = -((CA_L0 - Lr) * (xr - xbt) / Lr);
  g[3] = -((CA_L0 - Lr) * (yr - ybt) / Lr - CA_K * CA_G);
}

static void CarConstraints(double t, const double *q, double *phi)
{
  double xbt, ybt, xbd, ybd;
  CarSupport(t, &xbt, &ybt, &xbd, &ybd);
  phi[0] = xbt * q[0] + ybt * q[1];
  phi[1] = (q[0] - q[2]) * (q[0] - q[2]) + (q[1] - q[3]) * (q[1] - q[3]) - CA_L * CA_L;
}

static void CarJacobian(double t, const double *q, double *B)
{
  double xbt, ybt, xbd, ybd;
  const double dx = q[0] - q[2], dy = q[1] - q[3];
  CarSupport(t, &xbt, &ybt, &xbd, &ybd);
  B[0] = xbt;
  B[1] = ybt;
  B[2] = 0.0;
  B[3] = 0.0;
  B[4] = 2 * dx;
  B[5] = 2 * dy;
  B[6] = -2 * dx;
  B[7] = -2 * dy;
}

static void CarPhiT(double t, const double *q, double *phit)
{
  double xbt, ybt, xbd, ybd;
  CarSupport(t, &xbt, &ybt, &xbd, &ybd);
  phit[0] = xbd * q[0] + ybd * q[1];
  phit[1] = 0.0;
}

/* Initial values (caraxis.f, init). */
static const double CAR_Q0[4] = {0.0, CA_L0, CA_L, CA_L0};
static const double CAR_V0[4] = {-CA_L0 / CA_L, 0.0, -CA_L0 / CA_L, 0.0};

/* Reference at t = 3 (caraxis.f, solut). */
static const double CAR_Q_REF[4] = {
  0.4934557842755629e-001, 0.4969894602303324e+000, 0.1041742524885400e+001,
  0.3739110272652214e+000};
static const double CAR_V_REF[4] = {
  -0.7705836840321485e-001, 0.7446866596327776e-002, 0.1755681574942899e-001,
  0.7703410437794031e+000};
static const double CAR_LAMBDA_REF[2] = {
  0.4736886750784630e-002, 0.1104680411345730e-002}; /* -y9, -y10 */

const SuiteProblem SUITE_CAR_AXIS = {
  "caraxis", "car axis (Test Set), t = 3", 4, 2, 3.0,
  CarMass, CarForce, CarConstraints, CarJacobian, CarPhiT, 1,
  CAR_Q0, CAR_V0, CAR_Q_REF, CAR_V_REF, CAR_LAMBDA_REF,
  NULL, 0, NULL, 1e-10,
  "Test Set for IVP Solvers, caraxis.f (subroutine solut)"};

/* =============================================================================
 * IFToMM benchmark A01 (Gonzalez et al., library of computational
 * benchmark problems, lim.ii.udc.es/mbsbenchmark): a point mass of 1 kg on
 * a massless link of 1 m, gravity 9.81 N/kg along -y, released at rest
 * from the horizontal (x = +1, y = 0), 2000 s. Criterion: the position
 * error of the mass at 4000 output steps (every 0.5 s) at most 1e-3 m
 * (high precision; 1e-1 low). Cartesian coordinates, Phi = (x^2 + y^2 - L^2)/2.
 * Exact solution: with phi the angle from the downward vertical and
 * u = K - w0 t, sin(phi/2) = k sn(u), k = sin(pi/4), w0 = sqrt(g/L), so
 * x = 2 L k sn dn, y = -L (1 - 2 k^2 sn^2), phi' = -2 k w0 cn.
 * ===========================================================================*/

#define PD_G 9.81
#define PD_L 1.0

static void PendulumMass(double t, const double *q, double *M)
{
  (void)t;
  (void)q;
  M[0] = 1.0;
  M[1] = 0.0;
  M[2] = 0.0;
  M[3] = 1.0;
}

static void PendulumForce(double t, const double *q, const double *v, double *g)
{
  (void)t;
  (void)q;
  (void)v;
  g[0] = 0.0;
  g[1] = PD_G; /* M v' = (0, -m g) - B^T lambda */
}

static void PendulumConstraints(double t, const double *q, double *phi)
{
  (void)t;
  phi[0] = 0.5 * (q[0] * q[0] + q[1] * q[1] - PD_L * PD_L);
}

static void PendulumJacobian(double t, const double *q, double *B)
{
  (void)t;
  B[0] = q[0];
  B[1] = q[1];
}

static void PendulumExact(double t, double *q, double *v)
{
  const double k = sqrt(0.5), w0 = sqrt(PD_G / PD_L), K = suite_elliptic_k(k);
  double sn, cn, dn, c, s, phid;
  suite_jacobi(K - w0 * t, k, &sn, &cn, &dn);
  s = 2 * k * sn * dn;         /* sin(phi) */
  c = 1.0 - 2 * k * k * sn * sn; /* cos(phi) */
  phid = -2 * k * w0 * cn;
  q[0] = PD_L * s;
  q[1] = -PD_L * c;
  v[0] = PD_L * c * phid;
  v[1] = PD_L * s * phid;
}

static double PendulumEnergy(const double *q, const double *v)
{
  return 0.5 * (v[0] * v[0] + v[1] * v[1]) + PD_G * q[1];
}

static const double PD_Q0[2] = {PD_L, 0.0};
static const double PD_V0[2] = {0.0, 0.0};
const SuiteProblem SUITE_PENDULUM = {
  "pendulum", "IFToMM A01 simple pendulum, t in [0, 2000]", 2, 1, 2000.0,
  PendulumMass, PendulumForce, PendulumConstraints, PendulumJacobian, NULL, 1,
  PD_Q0, PD_V0, NULL, NULL, NULL,
  PendulumExact, 4000, PendulumEnergy, 1e-12,
  "exact solution in Jacobi elliptic functions (AGM)"};

const SuiteProblem *suite_problem(const char *name)
{
  if (name == NULL) return NULL;
  if (strcmp(name, "andrews") == 0) return &SUITE_ANDREWS;
  if (strcmp(name, "caraxis") == 0) return &SUITE_CAR_AXIS;
  if (strcmp(name, "pendulum") == 0) return &SUITE_PENDULUM;
  return NULL;
}

double suite_mixed_error(const SuiteProblem *p, const double *q)
{
  double err = 0.0;
  int i;
  for (i = 0; i < p->n; i++) {
    const double ei = fabs(q[i] - p->q_ref[i]) / (1.0 + fabs(p->q_ref[i]));
    if (!(ei <= err)) err = ei; /* NaN propagates */
  }
  return err;
}

double suite_mixed_error_v(const SuiteProblem *p, const double *v)
{
  double err = 0.0;
  int i;
  if (p->v_ref == NULL) return NAN;
  for (i = 0; i < p->n; i++) {
    const double ei = fabs(v[i] - p->v_ref[i]) / (1.0 + fabs(p->v_ref[i]));
    if (!(ei <= err)) err = ei;
  }
  return err;
}

/* =============================================================================
 * Jacobi elliptic functions (Abramowitz and Stegun 16.4, 17.6)
 * ===========================================================================*/

double suite_elliptic_k(double k)
{
  double a = 1.0, b = sqrt(1.0 - k * k);
  int i;
  for (i = 0; i < 40 && fabs(a - b) > 1e-16 * a; i++) {
    const double an = 0.5 * (a + b);
    b = sqrt(a * b);
    a = an;
  }
  return 2.0 * atan(1.0) / a; /* pi / (2 a) */
}

void suite_jacobi(double arg, double k, double *sn, double *cn, double *dn)
{
  double a[32], c[32], b, phi;
  const double K4 = 4.0 * suite_elliptic_k(k);
  int n = 0, i;
  double x = fmod(arg, K4); /* period 4K for sn and cn, 2K for dn */
  if (x > 0.5 * K4) x -= K4;
  if (x < -0.5 * K4) x += K4;
  a[0] = 1.0;
  b = sqrt(1.0 - k * k);
  c[0] = k;
  while (fabs(c[n]) > 1e-17 && n < 31) { /* descending AGM, 16.4.2 */
    a[n + 1] = 0.5 * (a[n] + b);
    c[n + 1] = 0.5 * (a[n] - b);
    b = sqrt(a[n] * b);
    n++;
  }
  phi = ldexp(a[n] * x, n); /* phi_N = 2^N a_N u, then 16.4.3 backwards */
  for (i = n; i > 0; i--) {
    phi = 0.5 * (phi + asin(c[i] / a[i] * sin(phi)));
    if (i == 1) { /* dn = sqrt(1 - k^2 sn^2) > 0 (A&S 16.9.2; for real u) */
      *sn = sin(phi);
      *cn = cos(phi);
      *dn = sqrt(1.0 - k * k * *sn * *sn);
      return;
    }
  }
  *sn = sin(x); /* k = 0 */
  *cn = cos(x);
  *dn = 1.0;
}
