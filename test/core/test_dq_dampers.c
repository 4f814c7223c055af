/* -----------------------------------------------------------------------------
 * Lignum test: the sparse path's coloured difference quotients of C_t (and
 * K_t) with force elements between jointed bodies.
 *
 * A chain of 6 bodies (R^3 x SO(3)) on spherical joints with rotational
 * spring-dampers beside every joint, swinging and twisting from a start
 * off the straight line (LGNCalcIC projects it), integrated without
 * LGNSetStiffnessFn / LGNSetDampingFn, so that Lignum forms K_t and C_t by
 * difference quotients: by columns on the dense path (LGNLinSol_Dense), by
 * column colours on the sparse one (KLU). The two must give the same
 * trajectory (1e-10) with the same Newton iterations, at index 3 and 2.
 * Before this test C_t's colouring pattern left out the bodies coupled by
 * joints, the dampers' coupling entries were mixed into other columns, and
 * the KLU run failed to converge at the first step.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lignum/lignum.h>
#include <lignum/lignum_bodies.h>
#include <lignum/lignum_joints.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "test_util.h"

#define NB 6

typedef struct {
  LGNBodies bodies;
  LGNJoints joints;
} Model;

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  return LGNBodies_MassFn(t, q, M, ((Model *)ud)->bodies);
}
static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  return LGNBodies_ForceFn(t, q, v, g, ((Model *)ud)->bodies);
}
static int Constr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  return LGNJoints_Residual(((Model *)ud)->joints, t, q, phi) ? -1 : 0;
}
static int ConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  return LGNJoints_Jacobian(((Model *)ud)->joints, t, q, B) ? -1 : 0;
}

typedef struct {
  double q[7 * NB];
  long int nni;
  int flag;
} Result;

static void Run(LGNGroup G, Model *md, int sparse, int index, SUNContext ctx, Result *res)
{
  const sunindextype nv = G->nv, m = LGNJoints_NumConstraints(md->joints);
  N_Vector q = N_VNew_Serial(G->nq, ctx), v = N_VNew_Serial(nv, ctx);
  N_Vector y = N_VNew_Serial(nv + m, ctx);
  SUNMatrix A = sparse ? SUNSparseMatrix(nv + m, nv + m, 1, CSC_MAT, ctx)
                       : SUNDenseMatrix(nv + m, nv + m, ctx);
  SUNLinearSolver LS = sparse ? SUNLinSol_KLU(y, A, ctx) : LGNLinSol_Dense(y, A, ctx);
  void *mem = LGNCreate(ctx);
  sunrealtype t = 0.0, *qd = N_VGetArrayPointer(q), *vd = N_VGetArrayPointer(v);
  int k, flag;
  N_VConst(0.0, q);
  N_VConst(0.0, v);
  for (k = 0; k < NB; k++) { /* along x, bent a little, spinning */
    qd[7 * k]     = k + 0.5;
    qd[7 * k + 1] = 0.02 * sin(1.0 + k);
    qd[7 * k + 3] = 1.0;
    vd[6 * k + 2] = 0.3 * cos(0.5 * k);
    vd[6 * k + 3] = 2.0 * sin(1.0 + 0.7 * k);
  }
  flag = LGNSetGroup(mem, G);
  if (!flag) flag = LGNSetUserData(mem, md);
  if (!flag) flag = LGNSetMassFn(mem, Mass);
  if (!flag) flag = LGNSetForceFn(mem, Force);
  if (!flag) flag = LGNSetConstraints(mem, m, Constr, ConstrJac);
  if (!flag) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (!flag) flag = LGNInit(mem, 0.0, q, v);
  if (!flag) flag = LGNSetLinearSolver(mem, LS, A);
  if (!flag) flag = LGNSetGenAlpha(mem, 0.9);
  if (!flag) flag = LGNSetConstraintIndex(mem, index);
  if (!flag) flag = LGNSetStepSize(mem, 2e-3);
  if (!flag) flag = LGNSStolerances(mem, 1e-11, 1e-11);
  if (!flag) flag = LGNCalcIC(mem, LGN_IC_PROJECT_QV);
  if (!flag) flag = LGNSolve(mem, 0.2, &t, q, v, LGN_NORMAL);
  res->flag = flag;
  memcpy(res->q, qd, sizeof res->q);
  LGNGetNumNewtonIters(mem, &res->nni);
  LGNFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(y);
  N_VDestroy(q);
  N_VDestroy(v);
}

int main(void)
{
  const sunrealtype J[3] = {0.01, 0.1, 0.1}, gvec[3] = {0.0, 0.0, -9.81};
  const sunrealtype origin[3] = {0.0, 0.0, 0.0}, left[3] = {-0.5, 0.0, 0.0},
                    right[3] = {0.5, 0.0, 0.0};
  SUNContext ctx = NULL;
  LGNGroup body, G, factors[NB];
  Model md;
  Result dense, sparse;
  int k, i, index, flag = 0;
  if (SUNContext_Create(NULL, &ctx) != 0) return 1;
  body = LGNGroup_R3xSO3();
  for (k = 0; k < NB; k++) factors[k] = body;
  G         = LGNGroup_Product(NB, factors);
  md.bodies = LGNBodies_Create(G);
  md.joints = LGNJoints_Create(G);
  flag      = LGNBodies_SetGravity(md.bodies, gvec);
  for (k = 0; k < NB && !flag; k++) {
    flag = LGNBodies_SetPrincipalInertia(md.bodies, k, 1.0 + 0.2 * k, J);
    if (!flag)
      flag = k == 0 ? LGNJoints_AddSpherical(md.joints, LGN_GROUND, origin, 0, left)
                    : LGNJoints_AddSpherical(md.joints, k - 1, right, k, left);
    if (!flag && k > 0)
      flag = LGNBodies_AddRotationalSpringDamper(md.bodies, k - 1, k, 20.0, 2.0, NULL);
  }
  CHECK(flag == 0, "model set-up");
  for (index = LGN_CONSTR_INDEX2; index <= LGN_CONSTR_INDEX3 && !flag; index++) {
    double d = 0.0;
    Run(G, &md, 0, index, ctx, &dense);
    Run(G, &md, 1, index, ctx, &sparse);
    CHECK(dense.flag == 0 && sparse.flag == 0, "index %d: flags %d (dense), %d (KLU)",
          index == LGN_CONSTR_INDEX3 ? 3 : 2, dense.flag, sparse.flag);
    for (i = 0; i < 7 * NB; i++) d = fmax(d, fabs(dense.q[i] - sparse.q[i]));
    CHECK(d < 1e-10, "index %d: KLU and dense differ by %g at t = 0.2",
          index == LGN_CONSTR_INDEX3 ? 3 : 2, d);
    CHECK(dense.nni == sparse.nni, "index %d: Newton iterations %ld (dense), %ld (KLU)",
          index == LGN_CONSTR_INDEX3 ? 3 : 2, dense.nni, sparse.nni);
    printf("index %d: |KLU - dense| = %.3g, Newton iterations %ld / %ld\n",
           index == LGN_CONSTR_INDEX3 ? 3 : 2, d, dense.nni, sparse.nni);
  }
  LGNJoints_Destroy(&md.joints);
  LGNBodies_Destroy(&md.bodies);
  LGNGroup_Destroy(G);
  LGNGroup_Destroy(body);
  SUNContext_Free(&ctx);
  return test_summary("test_dq_dampers");
}
