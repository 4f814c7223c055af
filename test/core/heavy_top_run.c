/* -----------------------------------------------------------------------------
 * The heavy top runs of test_ggl and test_ggl_newmark (heavy_top_run.h).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>

#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "heavy_top_run.h"

int RunCreate(Run *r, SUNContext ctx, int index, int n)
{
  const sunrealtype J[3] = {0.234375, 0.46875, 0.234375}, grav[3] = {0, 0, -9.81};
  const sunrealtype s[3] = {0, -1, 0}, o[3] = {0, 0, 0};
  const sunrealtype Om[3] = {0, 150, -4.61538}, X[3] = {0, 1, 0};
  sunrealtype *q, *v;
  int flag;
  memset(r, 0, sizeof *r);
  r->ctx = ctx;
  r->G   = LGNGroup_R3xSO3();
  r->bodies = LGNBodies_Create(r->G);
  r->joints = LGNJoints_Create(r->G);
  r->model  = LGNModel_Create(r->bodies, r->joints);
  LGNBodies_SetPrincipalInertia(r->bodies, 0, 15.0, J);
  LGNBodies_SetGravity(r->bodies, grav);
  LGNJoints_AddSpherical(r->joints, 0, s, LGN_GROUND, o); /* x - R X = 0 */
  r->q = N_VNew_Serial(7, ctx);
  r->v = N_VNew_Serial(6, ctx);
  r->lambda = N_VNew_Serial(3, ctx);
  r->phi = N_VNew_Serial(3, ctx);
  r->B = SUNDenseMatrix(3, 6, ctx);
  q = N_VGetArrayPointer(r->q);
  v = N_VGetArrayPointer(r->v);
  q[0] = X[0]; q[1] = X[1]; q[2] = X[2];
  q[3] = 1; q[4] = q[5] = q[6] = 0;
  v[0] = Om[1] * X[2] - Om[2] * X[1];
  v[1] = Om[2] * X[0] - Om[0] * X[2];
  v[2] = Om[0] * X[1] - Om[1] * X[0];
  v[3] = Om[0]; v[4] = Om[1]; v[5] = Om[2];
  r->y   = N_VNew_Serial(n, ctx);
  r->A   = SUNDenseMatrix(n, n, ctx);
  r->LS  = LGNLinSol_Dense(r->y, r->A, ctx);
  r->mem = LGNCreate(ctx);
  /* the step's own values (q_n, v_n, vdot_n, lambda_n): not the consistent,
   * projected outputs (LGNSetConsistentOutputs, LGNSetProjectOutputs) */
  LGNSetConsistentOutputs(r->mem, SUNFALSE);
  LGNSetProjectOutputs(r->mem, LGN_PROJECT_NONE);
  flag = LGNModel_Attach(r->model, r->mem);
  if (!flag) flag = LGNInit(r->mem, 0.0, r->q, r->v);
  if (!flag) flag = LGNSetLinearSolver(r->mem, r->LS, r->A);
  if (!flag) flag = LGNSetConstraintIndex(r->mem, index);
  return flag;
}

void RunFree(Run *r)
{
  LGNFree(&r->mem);
  SUNLinSolFree(r->LS);
  SUNMatDestroy(r->A);
  SUNMatDestroy(r->B);
  N_VDestroy(r->y);
  N_VDestroy(r->q);
  N_VDestroy(r->v);
  N_VDestroy(r->lambda);
  N_VDestroy(r->phi);
  LGNModel_Destroy(&r->model);
  LGNJoints_Destroy(&r->joints);
  LGNBodies_Destroy(&r->bodies);
  LGNGroup_Destroy(r->G);
}

void Violations(Run *r, double *phi, double *bv)
{
  sunrealtype w[3];
  int i, j;
  LGNJoints_Residual(r->joints, 0.0, r->q, r->phi);
  LGNJoints_Jacobian(r->joints, 0.0, r->q, r->B);
  *phi = *bv = 0;
  for (i = 0; i < 3; i++) {
    w[i] = 0;
    for (j = 0; j < 6; j++) w[i] += SM_ELEMENT_D(r->B, i, j) * NV_Ith_S(r->v, j);
    *phi = fmax(*phi, fabs(NV_Ith_S(r->phi, i)));
    *bv  = fmax(*bv, fabs(w[i]));
  }
}

/* The joint's constraint is x - R X = 0, the reference's X - R^T x =
 * -R^T (x - R X): the same constraint forces B^T lambda with
 * lambda = -R lambda_ref. */
void Errors(Run *r, const LGNRefHeavyTop *ref, double e[3])
{
  const sunrealtype *q = N_VGetArrayPointer(r->q), *v = N_VGetArrayPointer(r->v);
  const sunrealtype *l = N_VGetArrayPointer(r->lambda);
  int i, j;
  e[0] = e[1] = e[2] = 0;
  for (i = 0; i < 3; i++) {
    double lr = 0;
    for (j = 0; j < 3; j++) lr -= ref->R[3 * i + j] * ref->lambda[j];
    e[0] = fmax(e[0], fabs(q[i] - ref->x[i]));
    e[1] = fmax(e[1], fmax(fabs(v[i] - ref->u[i]), fabs(v[3 + i] - ref->Omega[i])));
    e[2] = fmax(e[2], fabs(l[i] - lr));
  }
}

double Fit(const double *x, const double *y, int n)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int i;
  for (i = 0; i < n; i++) {
    const double a = log(x[i]), b = log(y[i]);
    sx += a; sy += b; sxx += a * a; sxy += a * b;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}
