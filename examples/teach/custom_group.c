/* -----------------------------------------------------------------------------
 * Lignum teaching example: a user-supplied Lie group.
 *
 * Shows: how to give Lignum a configuration space it does not have built in.
 * SO(2), the rotations of the plane, is written here as a custom group:
 * LGNGroup_NewEmpty(nq, nv) and its operations filled in by hand, with
 *
 *   q = (cos theta, sin theta)   (nq = 2, a unit complex number)
 *   v = omega                    (nv = 1)
 *   q o exp(w) = q * (cos w, sin w),   T(w) = 1,  T(w)^-1 = 1,  Tdot = 0
 *
 * (SO(2) is commutative, so its tangent operator is the identity). The
 * product R^2 x SO(2) with the built-in R^2 is a planar rigid body,
 * q = (x, y, cos theta, sin theta), v = (u_x, u_y, omega).
 *
 * Model: a planar pendulum, a rod of length 1 and mass 1 (J = 1/12 about its
 * centre) whose end, the body point s = (-1/2, 0), is pinned at the origin:
 *
 *   Phi(q) = x + R(theta) s = 0                              (2 rows)
 *   B(q)   = [ I_2 | R(theta) (-s_y, s_x)^T ]                  (2 x 3)
 *   Z(q)(v, v) = -R(theta) s omega^2
 *   M = diag(m, m, J),  g = (0, m 9.81, 0)  (g holds minus the weight)
 *
 * written by hand as callbacks; the stiffness and damping are left to
 * Lignum's difference quotients. It starts at rest 1 rad from hanging down.
 * Generalized-alpha (rho_inf = 0.9), index 3, fixed h = 1e-3, t in [0, 2].
 *
 * Output: t, theta, the centre (x, y), omega, the energy and |Phi|.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

/* ---------------------------------------------------------------------------
 * The group SO(2): every op returns 0 on success.
 * -------------------------------------------------------------------------*/

static int SO2ComposeExp(LGNGroup G, const sunrealtype *q, const sunrealtype *w,
                         sunrealtype *q_out)
{
  const sunrealtype c = cos(w[0]), s = sin(w[0]);
  const sunrealtype q0 = q[0], q1 = q[1]; /* q_out may alias q */
  (void)G;
  q_out[0] = q0 * c - q1 * s;
  q_out[1] = q0 * s + q1 * c;
  return 0;
}

/* T(w) = T(w)^-1 = 1: y = x */
static int SO2TangentApply(LGNGroup G, const sunrealtype *w, const sunrealtype *x,
                           sunrealtype *y)
{
  (void)G; (void)w;
  y[0] = x[0];
  return 0;
}

static int SO2TangentDotApply(LGNGroup G, const sunrealtype *w, const sunrealtype *wdot,
                              const sunrealtype *x, sunrealtype *y)
{
  (void)G; (void)w; (void)wdot; (void)x;
  y[0] = 0.0;
  return 0;
}

static int SO2TangentMatrix(LGNGroup G, const sunrealtype *w, sunrealtype *Tm,
                            sunindextype ld)
{
  (void)G; (void)w; (void)ld;
  Tm[0] = 1.0;
  return 0;
}

static int SO2Identity(LGNGroup G, sunrealtype *q)
{
  (void)G;
  q[0] = 1.0;
  q[1] = 0.0;
  return 0;
}

/* back onto the unit circle after round-off */
static int SO2Normalize(LGNGroup G, sunrealtype *q)
{
  const sunrealtype r = sqrt(q[0] * q[0] + q[1] * q[1]);
  (void)G;
  if (!(r > 0.0)) return -1;
  q[0] /= r;
  q[1] /= r;
  return 0;
}

static LGNGroup NewSO2(void)
{
  LGNGroup G = LGNGroup_NewEmpty(2, 1);
  if (G == NULL) return NULL;
  G->ops.compose_exp = SO2ComposeExp;
  G->ops.tangent_apply = SO2TangentApply;
  G->ops.tangent_inverse_apply = SO2TangentApply;
  G->ops.tangent_dot_apply = SO2TangentDotApply;
  G->ops.tangent_matrix = SO2TangentMatrix;
  G->ops.identity = SO2Identity;
  G->ops.normalize = SO2Normalize;
  G->ops.free_content = NULL; /* no content */
  return G;
}

/* ---------------------------------------------------------------------------
 * The pendulum on R^2 x SO(2)
 * -------------------------------------------------------------------------*/

static const sunrealtype MASS = 1.0, INERTIA = 1.0 / 12.0, GRAV = 9.81;
static const sunrealtype S[2] = {-0.5, 0.0}; /* the pinned end, body frame */

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  (void)t; (void)q; (void)ud;
  SM_ELEMENT_D(M, 0, 0) = MASS;
  SM_ELEMENT_D(M, 1, 1) = MASS;
  SM_ELEMENT_D(M, 2, 2) = INERTIA;
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  (void)t; (void)q; (void)v; (void)ud;
  NV_Ith_S(g, 0) = 0.0;
  NV_Ith_S(g, 1) = MASS * GRAV;
  NV_Ith_S(g, 2) = 0.0;
  return 0;
}

/* R s and R (J2 s), J2 s = (-s_y, s_x): the derivative of R s in theta */
static void Rs(N_Vector q, sunrealtype rs[2], sunrealtype drs[2])
{
  const sunrealtype c = NV_Ith_S(q, 2), s = NV_Ith_S(q, 3);
  rs[0] = c * S[0] - s * S[1];
  rs[1] = s * S[0] + c * S[1];
  drs[0] = -rs[1];
  drs[1] = rs[0];
}

static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  sunrealtype rs[2], drs[2];
  (void)t; (void)ud;
  Rs(q, rs, drs);
  NV_Ith_S(phi, 0) = NV_Ith_S(q, 0) + rs[0];
  NV_Ith_S(phi, 1) = NV_Ith_S(q, 1) + rs[1];
  return 0;
}

static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  sunrealtype rs[2], drs[2];
  (void)t; (void)ud;
  Rs(q, rs, drs);
  SM_ELEMENT_D(B, 0, 0) = 1.0;
  SM_ELEMENT_D(B, 1, 1) = 1.0;
  SM_ELEMENT_D(B, 0, 2) = drs[0];
  SM_ELEMENT_D(B, 1, 2) = drs[1];
  return 0;
}

static int Curvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  const sunrealtype w = NV_Ith_S(v, 2);
  sunrealtype rs[2], drs[2];
  (void)t; (void)ud;
  Rs(q, rs, drs);
  NV_Ith_S(z, 0) = -rs[0] * w * w;
  NV_Ith_S(z, 1) = -rs[1] * w * w;
  return 0;
}

static void Print(sunrealtype t, N_Vector q, N_Vector v, N_Vector phi)
{
  const sunrealtype *qd = N_VGetArrayPointer(q), *vd = N_VGetArrayPointer(v);
  const sunrealtype energy = 0.5 * MASS * (vd[0] * vd[0] + vd[1] * vd[1]) +
                             0.5 * INERTIA * vd[2] * vd[2] + MASS * GRAV * qd[1];
  Constr(t, q, phi, NULL);
  printf("%5.2f %11.6f %11.6f %11.6f %11.6f %14.8f %10.1e\n", t, atan2(qd[3], qd[2]), qd[0],
         qd[1], vd[2], energy, sqrt(N_VDotProd(phi, phi)));
}

int main(void)
{
  const sunrealtype theta0 = -0.5 * acos(-1.0) + 1.0;
  const sunrealtype h = 1e-3, dtout = 0.25, tend = 2.0;
  SUNContext ctx = NULL;
  LGNGroup R2 = NULL, SO2 = NULL, G = NULL, factors[2];
  N_Vector q = NULL, v = NULL, phi = NULL, y = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunrealtype t = 0.0, tout, rs[2], drs[2];
  long int nst = 0, nni = 0;
  int flag = 0;

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;

  /* the groups: R^2 built in, SO(2) ours, their product */
  R2 = LGNGroup_Rn(2);
  SO2 = NewSO2();
  factors[0] = R2;
  factors[1] = SO2;
  G = LGNGroup_Product(2, factors); /* nq = 4, nv = 3 */
  if (R2 == NULL || SO2 == NULL || G == NULL) return 1;

  /* initial state: the rod at theta0, its end at the origin, at rest */
  q = N_VNew_Serial(G->nq, ctx);
  v = N_VNew_Serial(G->nv, ctx);
  phi = N_VNew_Serial(2, ctx);
  NV_Ith_S(q, 2) = cos(theta0);
  NV_Ith_S(q, 3) = sin(theta0);
  Rs(q, rs, drs);
  NV_Ith_S(q, 0) = -rs[0];
  NV_Ith_S(q, 1) = -rs[1];
  N_VConst(0.0, v);

  mem = LGNCreate(ctx);
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, 2, Constr, ConstrJac);
  if (!flag) flag = LGNSetCurvatureFn(mem, Curvature);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  y = N_VNew_Serial(G->nv + 2, ctx);
  A = SUNDenseMatrix(G->nv + 2, G->nv + 2, ctx);
  LS = LGNLinSol_Dense(y, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepSize(mem, h);

  printf("Planar pendulum on R^2 x SO(2), SO(2) a user-supplied group,\n");
  printf("generalized-alpha(0.9), h = %.0e\n\n", h);
  printf("%5s %11s %11s %11s %11s %14s %10s\n", "t", "theta", "x", "y", "omega", "energy",
         "|Phi|");
  if (!flag) Print(t, q, v, phi);
  for (tout = dtout; !flag && tout <= tend + 0.5 * dtout; tout += dtout) {
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (!flag) Print(t, q, v, phi);
  }
  if (flag) fprintf(stderr, "custom_group: %s\n", LGNGetReturnFlagName(flag));

  LGNGetNumSteps(mem, &nst);
  LGNGetNumNewtonIters(mem, &nni);
  printf("\nsteps = %ld   Newton iterations = %ld\n", nst, nni);

  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(phi);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNGroup_Destroy(G); /* the product first, then its factors */
  LGNGroup_Destroy(SO2);
  LGNGroup_Destroy(R2);
  SUNContext_Free(&ctx);
  return flag ? 1 : 0;
}
