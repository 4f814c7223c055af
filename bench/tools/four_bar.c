/* -----------------------------------------------------------------------------
 * Lignum study tool: a closed-loop four-bar linkage with revolute joints.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Crank AB, coupler BC and rocker DC, solid cylinders of radius 0.02 m and
 * 1 kg per metre, ground pivots A = (0,0,0) and D = (1,0,0), moving in the
 * x-y plane under gravity (0, -9.81, 0), released at rest with the crank at
 * 60 degrees. Joints (lignum_joints.h):
 *   A  ground-crank    revolute  (axis z)
 *   B  crank-coupler   revolute  (axis z)
 *   C  coupler-rocker  spherical
 *   D  rocker-ground   universal (rocker axis in the plane, ground axis z)
 * 18 - (5 + 5 + 3 + 4) = 1 degree of freedom with independent constraints
 * (an all-revolute spatial four-bar would have 3 redundant ones and a
 * singular iteration matrix). The body frames have e3 along the link and e1
 * along z, so the revolute axes are body e1.
 *
 * Self-checks (exit status): the run succeeds, |Phi| stays at round-off,
 * the motion stays planar (z of every centre of mass and the tilt of every
 * body axis e1 out of z below 1e-10), the crank really turns (more than
 * 1e-3 rad), Newmark
 * (beta = 1/4, gamma = 1/2) keeps the energy to 1e-3 relative, and dense,
 * KLU CSC and KLU CSR give the same state to round-off (to the Newton
 * tolerance at index 2, whose D_q(B v) is a difference quotient).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/rigid_bodies.h"

/* Place link k from point P to point Q (in the x-y plane). */
static void PlaceLink(RigidSystem *sys, int k, const double P[3], const double Q[3])
{
  double u[3], x[3], R[9], L;
  int i;
  for (i = 0; i < 3; i++) u[i] = Q[i] - P[i];
  L = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (i = 0; i < 3; i++) {
    u[i] /= L;
    x[i] = 0.5 * (P[i] + Q[i]);
  }
  /* columns: e1 = z, e2 = u x z... chosen so that e1 x e2 = e3 = u */
  R[0] = 0.0; R[1] = u[1];  R[2] = u[0];
  R[3] = 0.0; R[4] = -u[0]; R[5] = u[1];
  R[6] = 1.0; R[7] = 0.0;   R[8] = 0.0;
  rigid_set_cylinder(sys, k, L, L, 0.02);
  rigid_place(sys, k, x, R);
}

static RigidSystem *FourBar(RigidFormulation formulation, SUNContext ctx, double len[3])
{
  const double pi = acos(-1.0), L1 = 0.3, L2 = 1.0, L3 = 0.8;
  const double A[3] = {0, 0, 0}, D[3] = {1.0, 0, 0}, z[3] = {0, 0, 1}, e1[3] = {1, 0, 0};
  const double e2[3] = {0, 1, 0};
  double B[3], C[3], d, a, hgt, mid[3], s[3];
  RigidSystem *sys = rigid_create(3, formulation, ctx);
  int i;
  if (sys == NULL) return NULL;
  sys->gravity[0] = 0.0;
  sys->gravity[1] = -9.81;
  sys->gravity[2] = 0.0;
  B[0] = L1 * cos(pi / 3);
  B[1] = L1 * sin(pi / 3);
  B[2] = 0.0;
  /* C: intersection of |C - B| = L2 and |C - D| = L3, upper branch */
  d   = sqrt((D[0] - B[0]) * (D[0] - B[0]) + (D[1] - B[1]) * (D[1] - B[1]));
  a   = (L2 * L2 - L3 * L3 + d * d) / (2 * d);
  hgt = sqrt(L2 * L2 - a * a);
  for (i = 0; i < 3; i++) mid[i] = B[i] + a * (D[i] - B[i]) / d;
  C[0] = mid[0] - hgt * (D[1] - B[1]) / d;
  C[1] = mid[1] + hgt * (D[0] - B[0]) / d;
  C[2] = 0.0;
  PlaceLink(sys, 0, A, B);
  PlaceLink(sys, 1, B, C);
  PlaceLink(sys, 2, D, C);
  len[0] = L1;
  len[1] = L2;
  len[2] = L3;
  /* joints, points in the body frames (link from -L/2 to +L/2 along e3) */
  s[0] = s[1] = 0.0;
  s[2] = -0.5 * L1;
  LGNJoints_AddRevolute(sys->joints, LGN_GROUND, A, z, 0, s, e1);
  {
    const double sb[3] = {0, 0, 0.5 * L1}, sc[3] = {0, 0, -0.5 * L2};
    LGNJoints_AddRevolute(sys->joints, 0, sb, e1, 1, sc, e1);
  }
  {
    const double sc[3] = {0, 0, 0.5 * L2}, sr[3] = {0, 0, 0.5 * L3};
    LGNJoints_AddSpherical(sys->joints, 1, sc, 2, sr);
  }
  {
    const double sd[3] = {0, 0, -0.5 * L3};
    LGNJoints_AddUniversal(sys->joints, 2, sd, e2, LGN_GROUND, D, z);
  }
  return sys;
}

/* Largest out-of-plane deviation: z of the centres of mass and the z
 * deviation of each body's e1 (which must stay along z). */
static double OutOfPlane(const double *q)
{
  double dev = 0.0, R[9];
  int k;
  for (k = 0; k < 3; k++) {
    LGNQuaternionToRotation(q + 7 * k + 3, R);
    dev = fmax(dev, fabs(q[7 * k + 2]));
    dev = fmax(dev, fmax(fabs(R[0]), fabs(R[3]))); /* e1 = (R00, R10, R20) */
  }
  return dev;
}

static double CrankAngle(const double *q)
{
  double R[9];
  LGNQuaternionToRotation(q + 3, R);
  return atan2(R[5], R[2]); /* direction of e3 in the plane */
}

int main(int argc, char **argv)
{
  RigidRunOptions opt;
  RigidFormulation formulation = RB_R3XSO3;
  RigidRunResult res[3] = {{0}, {0}, {0}};
  RigidSystem *sys;
  SUNContext ctx;
  double len[3], angle0, same_tol, phi_tol;
  int i, s, status = 0, index3;

  rigid_default_run_options(&opt);
  opt.method = 0; /* Newmark, beta = 1/4, gamma = 1/2: no numerical damping */
  opt.t_end  = 2.0;
  for (i = 1; i < argc; i++) {
    int r = rigid_parse_option(argc, argv, &i, &opt, &formulation);
    if (r == 1) continue;
    fprintf(stderr, "four_bar: bad option or value: %s\nusage: %s\n", argv[i], argv[0]);
    rigid_print_usage(stderr);
    return 2;
  }
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  sys = FourBar(formulation, ctx, len);
  if (sys == NULL) return 1;
  angle0 = CrankAngle(N_VGetArrayPointer(sys->q0));
  /* Dense and sparse build the same iteration matrix, hence the same
   * iterates to round-off, except at index 2, where D_q(B v) is a difference
   * quotient taken column by column (dense) or by column colours (sparse):
   * then the solutions agree to the Newton tolerance. */
  index3   = opt.constraints == LGN_CONSTR_INDEX3;
  /* |Phi| at index 3: full Newton ends far inside its tolerance (quadratic
   * convergence), so Phi is at round-off. Modified Newton's last correction
   * only satisfies the stop test, |delta sigma| <= h (atol + rtol |v|)
   * ~ 1e-11 (defaults 1e-8, |v| < 1 m/s or rad/s here); B has entries of
   * order 1, so Phi is of that order. Index 2 lets Phi drift. */
  phi_tol = !index3 ? 1e-4 : (opt.newton == LGN_NEWTON_MODIFIED ? 1e-10 : 1e-12);
  same_tol = index3 ? 1e-10 : 1e-8;

  printf("four-bar (RRSU) on %s, %s, index %d, h = %g, t in [0, %g], %d constraints\n",
         formulation == RB_SE3 ? "SE(3)^3" : "(R^3 x SO(3))^3",
         opt.method == 1 ? "generalized-alpha" : "Newmark", opt.constraints, opt.h,
         opt.t_end, (int)LGNJoints_NumConstraints(sys->joints));
  for (s = 0; s < 3; s++) {
    int flag;
    double plane, turn;
    opt.solver = (RigidSolver)s;
    if (!rigid_solver_available(opt.solver)) continue;
    flag  = rigid_run(sys, &opt, &res[s]);
    plane = res[s].q != NULL ? OutOfPlane(res[s].q) : 1.0;
    turn  = res[s].q != NULL ? CrankAngle(res[s].q) - angle0 : 0.0;
    printf("%-8s flag %s  steps %ld  Newton/step %.2f  max |Phi| %.2e  out of plane %.2e\n"
           "         crank turned %.6f rad  energy %.10g -> %.10g  max |E - E0|/|E0| %.2e\n",
           rigid_solver_name(opt.solver), LGNGetReturnFlagName(flag), res[s].nsteps,
           res[s].nsteps > 0 ? (double)res[s].nni / res[s].nsteps : 0.0, res[s].max_phi,
           plane, turn, res[s].energy0, res[s].energy,
           res[s].max_drift / fabs(res[s].energy0));
    /* index 2 lets Phi drift (only B v = 0 is enforced) */
    if (flag != LGN_SUCCESS || !(res[s].max_phi < phi_tol) || !(plane < 1e-10) ||
        !(fabs(turn) > 1e-3 * fmin(1.0, opt.t_end)) ||
        (opt.method == 0 && !(res[s].max_drift < 1e-3 * fabs(res[s].energy0))))
      status = 1;
    if (s > 0 && res[s].q != NULL && res[0].q != NULL) {
      double d = 0.0;
      int k;
      for (k = 0; k < 21; k++) d = fmax(d, fabs(res[s].q[k] - res[0].q[k]));
      printf("         |q - q(dense)|_max = %.2e (must be < %.0e)\n", d, same_tol);
      if (!(d < same_tol)) status = 1;
    }
  }
  for (s = 0; s < 3; s++) rigid_result_free(&res[s]);
  printf("%s\n", status == 0 ? "PASSED" : "FAILED");
  rigid_free(&sys);
  SUNContext_Free(&ctx);
  return status;
}
