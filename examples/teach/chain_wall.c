/* -----------------------------------------------------------------------------
 * Lignum teaching example: a chain hitting a wall (impacts on a constrained
 * system).
 *
 * Shows: an event (LGNRootInit) finds the contact, LGNApplyImpact gives the
 * velocity after the impact from the impulse saddle-point problem
 *
 *   M (v+ - v-) + B^T Lambda + G^T P = 0,  B v+ = 0,  G v+ = -e G v-
 *
 * (for one degree of freedom this is v+ = -e v-; for a chain, reversing v
 * would break B v = 0), and the integration goes on from there. The
 * contact row G is the tip's gap from the wall, LGNJoints_PointPlaneContact.
 *
 * Five rods (1 m, 1 kg) on spherical joints hang from the origin, turned out
 * by -0.5 rad in the x-y plane (the tip at x = -2.4), and swing under
 * gravity (0, -9.81, 0) towards the wall x = 1.2, with a push out of the
 * plane. Generalized-alpha with error
 * control (rtol = atol = 1e-6: per unit step), restitution e = 0.8, t in [0, 2].
 * Output: each impact (time, the tip's normal velocity before and after, the
 * kinetic energy before and after), then t, the tip (x, y, z), the energy.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_model.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#define NB 5 /* rods */

static const sunrealtype Tip[3]  = {0.0, -0.5, 0.0};  /* the last rod's lower end */
static const sunrealtype Wall[3] = {-1.0, 0.0, 0.0};  /* n: the gap -x + 1.2 >= 0 */
static const sunrealtype WallD   = -1.2;

/* the event: the tip's gap to the wall */
static int Gap(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *gout, void *ud)
{
  sunrealtype row[6 * NB];
  (void)t; (void)v;
  return LGNJoints_PointPlaneContact(LGNModel_GetJoints((LGNModel)ud), q, NB - 1, Tip, Wall, WallD, gout,
                                     row) ? -1 : 0;
}

/* the contact row G (1 x nv, dense) */
static int Contact(sunrealtype t, N_Vector q, SUNMatrix G, void *ud)
{
  sunrealtype row[6 * NB], gap;
  int k;
  (void)t;
  if (LGNJoints_PointPlaneContact(LGNModel_GetJoints((LGNModel)ud), q, NB - 1, Tip, Wall, WallD, &gap, row))
    return -1;
  for (k = 0; k < 6 * NB; k++) SM_ELEMENT_D(G, 0, k) = row[k];
  return 0;
}

/* the tip's normal velocity n . v_tip = G v */
static sunrealtype NormalVelocity(LGNModel md, N_Vector q, N_Vector v)
{
  sunrealtype row[6 * NB], gap, s = 0.0;
  int k;
  LGNJoints_PointPlaneContact(LGNModel_GetJoints(md), q, NB - 1, Tip, Wall, WallD, &gap, row);
  for (k = 0; k < 6 * NB; k++) s += row[k] * N_VGetArrayPointer(v)[k];
  return s;
}

static sunrealtype Kinetic(LGNModel md, N_Vector q, N_Vector v)
{
  sunrealtype kin, pot;
  LGNBodies_Energy(LGNModel_GetBodies(md), q, v, &kin, &pot);
  return kin;
}

static void Print(LGNModel md, sunrealtype t, N_Vector q, N_Vector v)
{
  const sunrealtype *qk = N_VGetArrayPointer(q) + 7 * (NB - 1);
  sunrealtype R[9], kin, pot;
  LGNQuaternionToRotation(qk + 3, R);
  LGNBodies_Energy(LGNModel_GetBodies(md), q, v, &kin, &pot);
  printf("%5.2f %10.6f %10.6f %10.6f %12.6f\n", t, qk[0] + R[1] * Tip[1],
         qk[1] + R[4] * Tip[1], qk[2] + R[7] * Tip[1], kin + pot);
}

int main(void)
{
  const sunrealtype th = -0.5, e = 0.8, tol = 1e-6, tend = 2.0, dtout = 0.25;
  const sunrealtype gvec[3] = {0.0, -9.81, 0.0}, J[3] = {1.0 / 12, 0.002, 1.0 / 12};
  const sunrealtype top[3] = {0.0, 0.5, 0.0}, bottom[3] = {0.0, -0.5, 0.0}, O[3] = {0, 0, 0};
  SUNContext ctx = NULL;
  LGNGroup body = NULL, G = NULL, factors[NB];
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel md = NULL;
  N_Vector q = NULL, v = NULL, y = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunrealtype t = 0.0, tout, *qd, *vd, vn_before, kin_before;
  sunindextype m, n;
  long int nst = 0;
  int flag = 0, k, i, impacts = 0, dir[1] = {-1};

  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body = LGNGroup_R3xSO3();
  for (k = 0; k < NB; k++) factors[k] = body;
  G = LGNGroup_Product(NB, factors);
  bodies = LGNBodies_Create(G);
  joints = LGNJoints_Create(G);
  md = LGNModel_Create(bodies, joints);
  q  = N_VNew_Serial(G->nq, ctx);
  v  = N_VNew_Serial(G->nv, ctx);
  qd = N_VGetArrayPointer(q);
  vd = N_VGetArrayPointer(v);

  /* rods along their body y axes, turned by th about z (the chain points
   * along (sin th, -cos th, 0)); joints at the ends */
  for (k = 0; !flag && k < NB; k++) {
    const sunrealtype c[3] = {(k + 0.5) * sin(th), -(k + 0.5) * cos(th), 0.0};
    for (i = 0; i < 3; i++) qd[7 * k + i] = c[i];
    qd[7 * k + 3] = cos(0.5 * th); qd[7 * k + 4] = 0.0; qd[7 * k + 5] = 0.0;
    qd[7 * k + 6] = sin(0.5 * th);
    flag = LGNBodies_SetPrincipalInertia(bodies, k, 1.0, J);
    if (!flag)
      flag = k == 0 ? LGNJoints_AddSpherical(joints, LGN_GROUND, O, 0, top)
                    : LGNJoints_AddSpherical(joints, k - 1, bottom, k, top);
  }
  if (!flag) flag = LGNBodies_SetGravity(bodies, gvec);
  m = LGNJoints_NumConstraints(joints); /* 15 */
  n = G->nv + m;
  /* a push out of the plane, made consistent by LGNCalcIC */
  N_VConst(0.0, v);
  for (k = 0; k < NB; k++) vd[6 * k + 2] = 0.3 * (k + 1);

  mem = LGNCreate(ctx);
  if (!flag) flag = LGNModel_Attach(md, mem);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  y  = N_VNew_Serial(n, ctx);
  A  = SUNDenseMatrix(n, n, ctx);
  LS = LGNLinSol_Dense(y, A, ctx);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (!flag) flag = LGNSStolerances(mem, tol, tol);
  if (!flag) flag = LGNRootInit(mem, 1, Gap);
  if (!flag) flag = LGNSetRootDirection(mem, dir); /* approaching the wall */
  if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_V);
  if (!flag) flag = LGNGetConsistentIC(mem, q, v);

  printf("A chain of %d rods hitting the wall x = 1.2, restitution e = %.1f\n\n", NB, e);
  printf("%5s %10s %10s %10s %12s\n", "t", "tip_x", "tip_y", "tip_z", "energy");
  if (!flag) Print(md, t, q, v);
  for (tout = dtout; !flag && tout <= tend + 0.5 * dtout;) {
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    if (flag == LGN_ROOT_RETURN) { /* the tip at the wall: q, v at the root */
      vn_before  = NormalVelocity(md, q, v);
      kin_before = Kinetic(md, q, v);
      flag = LGNReInit(mem, t, q, v); /* the state at the root */
      if (!flag) flag = LGNApplyImpact(mem, 1, Contact, e, v, NULL);
      if (!flag)
        printf("impact %d at t = %.6f: tip velocity towards the wall %.6f -> %.6f, "
               "kinetic energy %.6f -> %.6f\n", ++impacts, t, -vn_before,
               -NormalVelocity(md, q, v), kin_before, Kinetic(md, q, v));
      continue;
    }
    if (!flag) Print(md, t, q, v);
    tout += dtout;
  }
  if (flag) fprintf(stderr, "chain_wall: %s\n", LGNGetReturnFlagName(flag));
  LGNGetNumSteps(mem, &nst);
  printf("impacts: %d, steps since the last one: %ld\n", impacts, nst);

  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNModel_Destroy(&md); /* after LGNFree */
  LGNJoints_Destroy(&joints);
  LGNBodies_Destroy(&bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
  return flag ? 1 : 0;
}
