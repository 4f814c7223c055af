/* -----------------------------------------------------------------------------
 * A planar slider-crank built in C on the model object (lignum_model.h) and
 * the planar sets (lignum_planar.h), the reference of the Python package's
 * PlanarMultibody (test_planar.py compares bit for bit):
 *
 *   planar_ref [se2|r2xso2]
 *
 * Bodies on (G)^3, G = SE(2) or R^2 x SO(2): crank (length 1, mass 1,
 * J = 1/12) revolute to the ground at the origin and to the rod (length 3,
 * mass 3, J = 9/4) at its tip; the rod revolute to the slider (mass 2,
 * J = 0.1), which slides along the x axis (planar prismatic, angle locked
 * at 0). A spring (k = 50, c = 0.5, rest length 2) pulls the slider
 * towards (6, 0); a rotational spring-damper (kr = 2, cr = 0.1, rest
 * angle 0.3) acts between the ground and the crank; gravity (0, -9.81).
 * Crank at 45 degrees, everything at rest (consistent). Generalized-alpha
 * (rho_inf = 0.9), index 3, fixed h = 1e-3; prints "t q[0..8] v[0..8]
 * lambda[0..7]" at t = k/10, k = 1..10, as C99 hexadecimal floats (%a).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_model.h>
#include <lignum/lignum_planar.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

int main(int argc, char **argv)
{
  const char *group = argc > 1 ? argv[1] : "se2";
  const sunrealtype L1 = 1.0, L2 = 3.0, a = 0.25 * acos(-1.0);
  const sunrealtype o[2] = {0.0, 0.0}, ex[2] = {1.0, 0.0};
  const sunrealtype crank_lo[2] = {-0.5 * L1, 0.0}, crank_hi[2] = {0.5 * L1, 0.0};
  const sunrealtype rod_lo[2] = {-0.5 * L2, 0.0}, rod_hi[2] = {0.5 * L2, 0.0};
  const sunrealtype anchor[2] = {6.0, 0.0}, gvec[3] = {0.0, -9.81, 0.0};
  sunrealtype bx, by, cx, *qd, t = 0.0;
  SUNContext ctx = NULL;
  LGNGroup factors[3] = {NULL, NULL, NULL}, G = NULL;
  LGNBodies bodies = NULL;
  LGNJoints joints = NULL;
  LGNModel md = NULL;
  N_Vector q = NULL, v = NULL, lam = NULL, y = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  sunindextype m = 0, i;
  int flag = 0, k, se2 = strcmp(group, "se2") == 0;

  if (!se2 && strcmp(group, "r2xso2") != 0) {
    fprintf(stderr, "usage: planar_ref [se2|r2xso2]\n");
    return 2;
  }
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  for (k = 0; k < 3; k++) factors[k] = se2 ? LGNGroup_SE2() : LGNGroup_R2xSO2();
  G = LGNGroup_Product(3, factors);
  bodies = LGNBodies_Create(G);
  joints = LGNJoints_Create(G);
  flag = LGNBodies_SetPlanarMass(bodies, 0, 1.0, L1 * L1 / 12.0);
  if (!flag) flag = LGNBodies_SetPlanarMass(bodies, 1, 3.0, 3.0 * L2 * L2 / 12.0);
  if (!flag) flag = LGNBodies_SetPlanarMass(bodies, 2, 2.0, 0.1);
  if (!flag) flag = LGNBodies_SetGravity(bodies, gvec);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(joints, LGN_GROUND, o, 0, crank_lo);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(joints, 0, crank_hi, 1, rod_lo);
  if (!flag) flag = LGNJoints_AddPlanarRevolute(joints, 1, rod_hi, 2, o);
  if (!flag) flag = LGNJoints_AddPlanarPrismatic(joints, LGN_GROUND, o, ex, 2, o, 0.0);
  if (!flag) flag = LGNBodies_AddPlanarSpringDamper(bodies, 2, o, LGN_GROUND, anchor, 50.0, 0.5,
                                                    2.0);
  if (!flag) flag = LGNBodies_AddPlanarRotationalSpringDamper(bodies, LGN_GROUND, 0, 2.0, 0.1,
                                                              0.3);
  md = LGNModel_Create(bodies, joints);
  m = LGNModel_NumConstraints(md);
  q = N_VNew_Serial(9, ctx);
  v = N_VNew_Serial(9, ctx);
  lam = N_VNew_Serial(m, ctx);
  y = N_VNew_Serial(9 + m, ctx);
  A = SUNDenseMatrix(9 + m, 9 + m, ctx);
  LS = LGNLinSol_Dense(y, A, ctx);
  mem = LGNCreate(ctx);
  if (flag || !md || !q || !v || !lam || !LS || !mem) flag = -1;
  if (!flag) {
    /* crank tip B, slider C on the x axis at distance L2 from B */
    bx = L1 * cos(a);
    by = L1 * sin(a);
    cx = bx + sqrt(L2 * L2 - by * by);
    qd = N_VGetArrayPointer(q);
    qd[0] = 0.5 * bx; qd[1] = 0.5 * by; qd[2] = a;
    qd[3] = 0.5 * (bx + cx); qd[4] = 0.5 * by; qd[5] = atan2(-by, cx - bx);
    qd[6] = cx; qd[7] = 0.0; qd[8] = 0.0;
    N_VConst(0.0, v);
    flag = LGNModel_Attach(md, mem);
  }
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetStepSize(mem, 1e-3);
  if (!flag) flag = LGNSetMaxNumSteps(mem, 100000);
  for (k = 1; !flag && k <= 10; k++) {
    flag = LGNSolve(mem, 0.1 * k, &t, q, v, LGN_NORMAL);
    if (!flag) flag = LGNGetMultipliers(mem, lam);
    if (!flag) {
      printf("%a", t);
      for (i = 0; i < 9; i++) printf(" %a", NV_Ith_S(q, i));
      for (i = 0; i < 9; i++) printf(" %a", NV_Ith_S(v, i));
      for (i = 0; i < m; i++) printf(" %a", NV_Ith_S(lam, i));
      printf("\n");
    }
  }
  LGNFree(&mem);
  LGNModel_Destroy(&md);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(lam);
  N_VDestroy(q);
  N_VDestroy(v);
  LGNJoints_Destroy(&joints);
  LGNBodies_Destroy(&bodies);
  LGNGroup_Destroy(G);
  for (k = 0; k < 3; k++) LGNGroup_Destroy(factors[k]);
  SUNContext_Free(&ctx);
  return flag ? 1 : 0;
}
