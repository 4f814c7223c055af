/* -----------------------------------------------------------------------------
 * Lignum benchmarks, the standard multibody suite: a problem of
 * suite_problem.h integrated with Lignum as a user would write it, on the
 * group R^n (LGNGroup_Rn), with the public API only (suite_run.h).
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>
#include <time.h>

#include <lignum/lignum.h>
#include <lignum/lignum_ls.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "suite_run.h"

/* ---- the model's callbacks (user data: the SuiteProblem) ------------------ */

static int Mass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  const SuiteProblem *p = ud;
  double Mr[SUITE_MAXN * SUITE_MAXN];
  int i, j;
  p->mass(t, N_VGetArrayPointer(q), Mr);
  for (i = 0; i < p->n; i++)
    for (j = 0; j < p->n; j++) SM_ELEMENT_D(M, i, j) = Mr[i * p->n + j];
  return 0;
}

static int Force(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  const SuiteProblem *p = ud;
  p->force(t, N_VGetArrayPointer(q), N_VGetArrayPointer(v), N_VGetArrayPointer(g));
  return 0;
}

static int Constraints(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  const SuiteProblem *p = ud;
  p->constraints(t, N_VGetArrayPointer(q), N_VGetArrayPointer(phi));
  return 0;
}

static int Jacobian(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  const SuiteProblem *p = ud;
  double Br[SUITE_MAXN * SUITE_MAXN];
  int i, j;
  p->jacobian(t, N_VGetArrayPointer(q), Br);
  for (i = 0; i < p->m; i++)
    for (j = 0; j < p->n; j++) SM_ELEMENT_D(B, i, j) = Br[i * p->n + j];
  return 0;
}

static int PhiT(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  const SuiteProblem *p = ud;
  p->phi_t(t, N_VGetArrayPointer(q), N_VGetArrayPointer(phit));
  return 0;
}

/* Silence Lignum's messages: a failed run is reported by its flag. */
static void Quiet(int code, const char *module, const char *function, const char *msg,
                  void *data)
{
  (void)code;
  (void)module;
  (void)function;
  (void)msg;
  (void)data;
}

/* ---- one run --------------------------------------------------------------- */

static int Setup(void *mem, const SuiteProblem *p, const SuiteLignumMethod *method,
                 double tol, LGNGroup G, N_Vector q, N_Vector v, SUNLinearSolver LS,
                 SUNMatrix A)
{
  int flag = LGNSetGroup(mem, G);
  if (flag == 0) flag = LGNSetErrHandlerFn(mem, Quiet, NULL);
  if (flag == 0) flag = LGNSetUserData(mem, (void *)p);
  if (flag == 0) flag = LGNSetMassFn(mem, Mass);
  if (flag == 0) flag = LGNSetForceFn(mem, Force);
  if (flag == 0) flag = LGNSetConstraints(mem, p->m, Constraints, Jacobian);
  if (flag == 0 && p->phi_t != NULL) flag = LGNSetConstraintTimeFn(mem, PhiT);
  if (flag == 0 && p->mass_constant) flag = LGNSetMassConstant(mem, SUNTRUE);
  if (flag == 0) flag = LGNInit(mem, 0.0, q, v);
  if (flag == 0) flag = LGNSetLinearSolver(mem, LS, A);
  if (flag == 0)
    flag = method->bdf_maxord > 0 ? LGNSetBDF(mem, method->bdf_maxord)
                                  : LGNSetGenAlpha(mem, method->rho_inf);
  if (flag == 0) flag = LGNSetConstraintIndex(mem, method->constraints);
  if (flag == 0) flag = LGNSetNewtonMode(mem, method->newton);
  if (flag == 0) flag = LGNSetStepControl(mem, LGN_STEP_ADAPTIVE);
  if (flag == 0) flag = LGNSStolerances(mem, tol, tol);
  if (flag == 0) flag = LGNSetStopTime(mem, p->t_end);
  if (flag == 0) flag = LGNSetMaxNumSteps(mem, -1);
  return flag;
}

int suite_lignum_run(const SuiteProblem *p, const SuiteLignumMethod *method, double tol,
                     SuiteResult *res)
{
  SUNContext ctx = NULL;
  LGNGroup G = NULL;
  N_Vector q = NULL, v = NULL, lam = NULL, y = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  const int n = p->n, m = p->m;
  const int na = n + (method->constraints == LGN_CONSTR_GGL ? 2 : 1) * m;
  double t = 0.0, e0 = 0.0;
  int flag = -100, i, k;
  const int nout = p->exact != NULL ? p->noutputs : 1;

  memset(res, 0, sizeof *res);
  res->flag = -100;
  res->err = res->err_v = res->mescd = res->energy_drift = NAN;
  if (n > SUITE_MAXN || m > SUITE_MAXN || SUNContext_Create(NULL, &ctx) != 0) return res->flag;
  G = LGNGroup_Rn(n);
  q = N_VNew_Serial(n, ctx);
  v = N_VNew_Serial(n, ctx);
  lam = N_VNew_Serial(m, ctx);
  y = N_VNew_Serial(na, ctx);
  A = SUNDenseMatrix(na, na, ctx);
  LS = (y != NULL && A != NULL) ? LGNLinSol_Dense(y, A, ctx) : NULL;
  mem = LGNCreate(ctx);
  if (G == NULL || q == NULL || v == NULL || lam == NULL || LS == NULL || mem == NULL) goto done;
  memcpy(N_VGetArrayPointer(q), p->q0, (size_t)n * sizeof(double));
  memcpy(N_VGetArrayPointer(v), p->v0, (size_t)n * sizeof(double));
  if (p->energy != NULL) e0 = p->energy(p->q0, p->v0);
  flag = Setup(mem, p, method, tol, G, q, v, LS, A);
  if (flag != 0) goto done;

  if (p->exact != NULL) res->err = res->energy_drift = 0.0;
  for (k = 1; k <= nout; k++) {
    const double tout = k == nout ? p->t_end : p->t_end * (double)k / (double)nout;
    const clock_t c0 = clock();
    flag = LGNSolve(mem, tout, &t, q, v, LGN_NORMAL);
    res->cpu += (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (flag == LGN_TSTOP_RETURN) flag = 0;
    if (flag != 0) break;
    if (p->exact != NULL) { /* IFToMM: the position error at every output */
      double qe[SUITE_MAXN], ve[SUITE_MAXN];
      const double *qq = N_VGetArrayPointer(q), *vv = N_VGetArrayPointer(v);
      p->exact(tout, qe, ve);
      for (i = 0; i < n; i++)
        if (!(fabs(qq[i] - qe[i]) <= res->err)) res->err = fabs(qq[i] - qe[i]);
      if (p->energy != NULL) {
        const double de = fabs(p->energy(qq, vv) - e0);
        if (!(de <= res->energy_drift)) res->energy_drift = de;
      }
    }
  }
  res->t = t;
  memcpy(res->q, N_VGetArrayPointer(q), (size_t)n * sizeof(double));
  memcpy(res->v, N_VGetArrayPointer(v), (size_t)n * sizeof(double));
  if (LGNGetMultipliers(mem, lam) == 0)
    memcpy(res->lambda, N_VGetArrayPointer(lam), (size_t)m * sizeof(double));
  {
    long int netf = 0, nncf = 0;
    LGNGetNumSteps(mem, &res->nsteps);
    LGNGetNumErrTestFails(mem, &netf);
    LGNGetNumNewtonConvFails(mem, &nncf);
    res->nrejected = netf + nncf; /* as IDA's netf + ncfn */
    LGNGetNumNewtonIters(mem, &res->nniters);
    LGNGetNumLinSolvSetups(mem, &res->nlu);
  }
  if (flag == 0 && fabs(t - p->t_end) > 1e-12 * (1.0 + p->t_end)) flag = -101;

done:
  res->flag = flag;
  if (flag == 0) suite_finish_result(p, res);
  else res->err = res->mescd = NAN;
  LGNFree(&mem);
  if (LS != NULL) SUNLinSolFree(LS);
  if (A != NULL) SUNMatDestroy(A);
  if (y != NULL) N_VDestroy(y);
  if (lam != NULL) N_VDestroy(lam);
  if (v != NULL) N_VDestroy(v);
  if (q != NULL) N_VDestroy(q);
  if (G != NULL) LGNGroup_Destroy(G);
  SUNContext_Free(&ctx);
  return res->flag;
}
