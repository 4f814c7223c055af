/* -----------------------------------------------------------------------------
 * Lignum teaching example: the torque-free symmetric top on SO(3) against its
 * analytic solution.
 *
 * Shows: how to check an integrator against an exact solution. A single
 * rigid body turning freely, so its configuration is a rotation alone: the
 * group SO(3) (q = unit quaternion, v = Omega, the body angular velocity),
 * no constraints, M = J and g = Omega x J Omega. With J = diag(J1, J1, J3)
 * the motion is known in closed form,
 *
 *   Omega(t) = (cos nu t W1 - sin nu t W2, sin nu t W1 + cos nu t W2, W3),
 *   R(t)     = exp(t pi~ / J1) R0 exp(-t nu e3~),
 *   nu = W3 (J3 - J1)/J1,  pi = R0 J Omega0,
 *
 * and the rotation error |log(p_ref^-1 p)| is measured with Lignum's
 * quaternion helpers (LGNQuaternionFromRotationVector, LGNQuaternionMultiply,
 * LGNRotationVectorFromQuaternion). Generalized-alpha (rho_inf = 0.9) with
 * simplified and exact kinematics (LGNSetKinematics), fixed steps
 * h = 1e-3 / 2^j, j = 0..3, t in [0, 1].
 *
 * Output: for each method and h, the errors in R and Omega at t = 1, the
 * observed order and Newton iterations per step, then the least-squares
 * order; the program fails (exit 1) unless both converge with order
 * 2.0 +- 0.1. Option --quick: one short run (for valgrind).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

static const double J[3]      = {0.234375, 0.234375, 0.46875};
static const double OMEGA0[3] = {1.0, -2.0, 150.0};
static const double PSI0[3]   = {0.3, -0.2, 0.1}; /* R0 = exp(PSI0~) */

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  int i;
  (void)t; (void)q; (void)ud;
  for (i = 0; i < 3; i++) SM_ELEMENT_D(M, i, i) = J[i];
  return 0;
}

/* g = Omega x J Omega (gyroscopic term) */
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const double *W = N_VGetArrayPointer(v);
  double *gg = N_VGetArrayPointer(g);
  (void)t; (void)q; (void)ud;
  gg[0] = W[1] * J[2] * W[2] - W[2] * J[1] * W[1];
  gg[1] = W[2] * J[0] * W[0] - W[0] * J[2] * W[2];
  gg[2] = W[0] * J[1] * W[1] - W[1] * J[0] * W[0];
  return 0;
}

/* Analytic solution at time t: quaternion p and body angular velocity W. */
static void Exact(double t, double p[4], double W[3])
{
  const double nu = OMEGA0[2] * (J[2] - J[0]) / J[0];
  double p0[4], R0[9], JW[3], pi[3], a[3], b[3], pa[4], pb[4];
  int i;
  LGNQuaternionFromRotationVector(PSI0, p0);
  LGNQuaternionToRotation(p0, R0);
  for (i = 0; i < 3; i++) JW[i] = J[i] * OMEGA0[i];
  for (i = 0; i < 3; i++) pi[i] = R0[3 * i] * JW[0] + R0[3 * i + 1] * JW[1] + R0[3 * i + 2] * JW[2];
  for (i = 0; i < 3; i++) a[i] = t * pi[i] / J[0];
  b[0] = b[1] = 0.0;
  b[2] = -t * nu;
  LGNQuaternionFromRotationVector(a, pa);
  LGNQuaternionFromRotationVector(b, pb);
  LGNQuaternionMultiply(pa, p0, p);
  LGNQuaternionMultiply(p, pb, p);
  W[0] = cos(nu * t) * OMEGA0[0] - sin(nu * t) * OMEGA0[1];
  W[1] = sin(nu * t) * OMEGA0[0] + cos(nu * t) * OMEGA0[1];
  W[2] = OMEGA0[2];
}

/* Rotation error |log(p_ref^{-1} p)| and velocity error at t_end. */
static int Run(int kinematics, double h, double t_end, double *err_rot,
               double *err_omega, double *newton_per_step)
{
  SUNContext ctx = NULL;
  LGNGroup G = LGNGroup_SO3();
  N_Vector q = NULL, v = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  double t = 0.0, pref[4], Wref[3], pinv[4], d[4], phi[3];
  long int nst = 0, nni = 0;
  int flag = SUNContext_Create(NULL, &ctx), i;

  if (flag != 0 || G == NULL) return -1;
  q = N_VNew_Serial(4, ctx);
  v = N_VNew_Serial(3, ctx);
  A = SUNDenseMatrix(3, 3, ctx);
  LS = LGNLinSol_Dense(v, A, ctx);
  mem = LGNCreate(ctx);
  LGNQuaternionFromRotationVector(PSI0, N_VGetArrayPointer(q));
  memcpy(N_VGetArrayPointer(v), OMEGA0, sizeof OMEGA0);

  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetKinematics(mem, kinematics);
  if (!flag) flag = LGNSetStepSize(mem, h);
  if (!flag) flag = LGNSStolerances(mem, 1e-12, 1e-12);
  if (!flag) flag = LGNSolve(mem, t_end, &t, q, v, LGN_NORMAL);
  if (!flag) {
    Exact(t, pref, Wref);
    pinv[0] = pref[0];
    for (i = 1; i < 4; i++) pinv[i] = -pref[i];
    LGNQuaternionMultiply(pinv, N_VGetArrayPointer(q), d);
    LGNRotationVectorFromQuaternion(d, phi);
    *err_rot = sqrt(phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2]);
    *err_omega = 0.0;
    for (i = 0; i < 3; i++)
      *err_omega += pow(N_VGetArrayPointer(v)[i] - Wref[i], 2);
    *err_omega = sqrt(*err_omega);
    LGNGetNumSteps(mem, &nst);
    LGNGetNumNewtonIters(mem, &nni);
    *newton_per_step = nst > 0 ? (double)nni / (double)nst : 0.0;
  } else {
    fprintf(stderr, "torque_free_top: run failed with %s\n", LGNGetReturnFlagName(flag));
  }
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return flag;
}

int main(int argc, char **argv)
{
  const char *names[2] = {"LGGalpha(0.9)", "mod. LGGalpha(0.9)"};
  const int kin[2] = {LGN_KINEMATICS_SIMPLIFIED, LGN_KINEMATICS_EXACT};
  const int quick = (argc > 1 && !strcmp(argv[1], "--quick"));
  const int nh = quick ? 1 : 4;
  int ok = 1, k, j;

  printf("Torque-free symmetric top on SO(3), t_end = 1 s, vs analytic solution\n\n");
  printf("%-20s %10s %12s %12s %8s %8s\n", "method", "h", "err_rot",
         "err_omega", "order_R", "newton");
  for (k = 0; k < 2; k++) {
    double err[4], erw[4], nps = 0.0;
    for (j = 0; j < nh; j++) {
      double h = 1e-3 / pow(2.0, j);
      if (Run(kin[k], h, quick ? 0.01 : 1.0, &err[j], &erw[j], &nps) != 0) return 1;
      if (j == 0)
        printf("%-20s %10.3e %12.4e %12.4e %8s %8.2f\n", names[k], h, err[j], erw[j], "", nps);
      else
        printf("%-20s %10.3e %12.4e %12.4e %8.3f %8.2f\n", names[k], h, err[j], erw[j],
               log(err[j - 1] / err[j]) / log(2.0), nps);
    }
    if (!quick) {
      /* least-squares slope of log(err) against log(h) */
      double sx = 0, sy = 0, sxx = 0, sxy = 0, order;
      for (j = 0; j < nh; j++) {
        double x = log(1e-3 / pow(2.0, j)), y = log(err[j]);
        sx += x; sy += y; sxx += x * x; sxy += x * y;
      }
      order = (nh * sxy - sx * sy) / (nh * sxx - sx * sx);
      printf("%-20s fitted order in R: %.3f\n", names[k], order);
      if (fabs(order - 2.0) > 0.1) {
        printf("FAIL: order %.3f is not 2.0 +- 0.1\n", order);
        ok = 0;
      }
      if (!(err[nh - 1] < 1e-3)) {
        printf("FAIL: error %.3e at the smallest h is not below 1e-3\n", err[nh - 1]);
        ok = 0;
      }
    }
  }
  printf("\n%s\n", ok ? "PASSED" : "FAILED");
  return ok ? 0 : 1;
}
