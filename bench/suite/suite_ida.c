/* -----------------------------------------------------------------------------
 * Lignum benchmarks, the standard multibody suite: a problem of
 * suite_problem.h integrated with SUNDIALS IDA in its best form for these
 * problems, the index-2 DAE with IDASetId and IDASetSuppressAlg (or the
 * stabilised index-2 GGL form), dense LU with IDA's difference-quotient
 * Jacobian, maxord 5 (suite_run.h). The same equations as the
 * Lignum driver, from the same model functions.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <string.h>
#include <time.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "suite_run.h"

/* y = (q, v, lambda[, mu]): offsets */
#define OQ 0
#define OV(p) ((p)->n)
#define OL(p) (2 * (p)->n)
#define OM(p) (2 * (p)->n + (p)->m)

typedef struct {
  const SuiteProblem *p;
  int ggl; /* 1: GGL, y = (q, v, lambda, mu); 0: index 2, y = (q, v, lambda) */
} IdaData;

/* The residual (suite_run.h): index 2, or GGL with Phi = 0 and mu. */
static int Residual(sunrealtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *ud)
{
  const SuiteProblem *p = ((const IdaData *)ud)->p;
  const int ggl = ((const IdaData *)ud)->ggl;
  const int n = p->n, m = p->m;
  const double *y = N_VGetArrayPointer(yy), *d = N_VGetArrayPointer(yp);
  const double *q = y + OQ, *v = y + OV(p), *lam = y + OL(p), *mu = ggl ? y + OM(p) : lam;
  const double *qd = d + OQ, *vd = d + OV(p);
  double *r = N_VGetArrayPointer(rr);
  double M[SUITE_MAXN * SUITE_MAXN], B[SUITE_MAXN * SUITE_MAXN], g[SUITE_MAXN];
  double phit[SUITE_MAXN];
  int i, j;
  p->mass(t, q, M);
  p->force(t, q, v, g);
  p->jacobian(t, q, B);
  for (i = 0; i < n; i++) {
    double bmu = 0.0, blam = 0.0, mvd = 0.0;
    for (j = 0; j < m; j++) {
      if (ggl) bmu += B[j * n + i] * mu[j];
      blam += B[j * n + i] * lam[j];
    }
    for (j = 0; j < n; j++) mvd += M[i * n + j] * vd[j];
    r[OQ + i] = qd[i] - v[i] - bmu;      /* q' = v + B^T mu          */
    r[OV(p) + i] = mvd + g[i] + blam;    /* M v' + g + B^T lambda = 0 */
  }
  if (ggl) p->constraints(t, q, r + OL(p)); /* Phi = 0                 */
  if (p->phi_t != NULL) p->phi_t(t, q, phit);
  for (j = 0; j < m; j++) {              /* B v + Phi_t = 0           */
    double bv = p->phi_t != NULL ? phit[j] : 0.0;
    for (i = 0; i < n; i++) bv += B[j * n + i] * v[i];
    r[(ggl ? OM(p) : OL(p)) + j] = bv;
  }
  return 0;
}

static void Quiet(int code, const char *module, const char *function, char *msg, void *data)
{
  (void)code;
  (void)module;
  (void)function;
  (void)msg;
  (void)data;
}

int suite_ida_run(const SuiteProblem *p, double tol, int maxord, int form, SuiteResult *res)
{
  IdaData data;
  SUNContext ctx = NULL;
  N_Vector yy = NULL, yp = NULL, id = NULL;
  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  void *mem = NULL;
  const int n = p->n, m = p->m, N = 2 * n + (form == SUITE_IDA_GGL ? 2 : 1) * m;
  const int nout = p->exact != NULL ? p->noutputs : 1;
  double t = 0.0, e0 = 0.0, *y, *d;
  int flag = -100, i, k;

  memset(res, 0, sizeof *res);
  res->flag = -100;
  res->err = res->err_v = res->mescd = res->energy_drift = NAN;
  data.p = p;
  data.ggl = form == SUITE_IDA_GGL;
  if (n > SUITE_MAXN || m > SUITE_MAXN || SUNContext_Create(NULL, &ctx) != 0) return res->flag;
  yy = N_VNew_Serial(N, ctx);
  yp = N_VNew_Serial(N, ctx);
  id = N_VNew_Serial(N, ctx);
  A = SUNDenseMatrix(N, N, ctx);
  LS = (yy != NULL && A != NULL) ? SUNLinSol_Dense(yy, A, ctx) : NULL;
  mem = IDACreate(ctx);
  if (yp == NULL || id == NULL || LS == NULL || mem == NULL) goto done;

  /* consistent initial values: q' = v, (v', lambda) from the saddle point */
  y = N_VGetArrayPointer(yy);
  d = N_VGetArrayPointer(yp);
  N_VConst(0.0, yy);
  N_VConst(0.0, yp);
  memcpy(y + OQ, p->q0, (size_t)n * sizeof(double));
  memcpy(y + OV(p), p->v0, (size_t)n * sizeof(double));
  memcpy(d + OQ, p->v0, (size_t)n * sizeof(double));
  if (suite_consistent_acceleration(p, 0.0, p->q0, p->v0, d + OV(p), y + OL(p)) != 0) goto done;
  for (i = 0; i < N; i++) NV_Ith_S(id, i) = i < OL(p) ? 1.0 : 0.0;
  if (p->energy != NULL) e0 = p->energy(p->q0, p->v0);

  flag = IDAInit(mem, Residual, 0.0, yy, yp);
  if (flag == 0) flag = IDASetErrHandlerFn(mem, Quiet, NULL);
  if (flag == 0) flag = IDASStolerances(mem, tol, tol);
  if (flag == 0) flag = IDASetUserData(mem, &data);
  if (flag == 0) flag = IDASetId(mem, id);
  if (flag == 0) flag = IDASetSuppressAlg(mem, SUNTRUE);
  if (flag == 0) flag = IDASetStopTime(mem, p->t_end);
  if (flag == 0) flag = IDASetMaxNumSteps(mem, 100000000L);
  if (flag == 0 && maxord > 0) flag = IDASetMaxOrd(mem, maxord);
  if (flag == 0) flag = IDASetLinearSolver(mem, LS, A);
  if (flag != 0) goto done;

  if (p->exact != NULL) res->err = res->energy_drift = 0.0;
  for (k = 1; k <= nout; k++) {
    const double tout = k == nout ? p->t_end : p->t_end * (double)k / (double)nout;
    const clock_t c0 = clock();
    flag = IDASolve(mem, tout, &t, yy, yp, IDA_NORMAL);
    res->cpu += (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (flag == IDA_TSTOP_RETURN) flag = 0;
    if (flag != 0) break;
    if (p->exact != NULL) {
      double qe[SUITE_MAXN], ve[SUITE_MAXN];
      p->exact(tout, qe, ve);
      for (i = 0; i < n; i++)
        if (!(fabs(y[OQ + i] - qe[i]) <= res->err)) res->err = fabs(y[OQ + i] - qe[i]);
      if (p->energy != NULL) {
        const double de = fabs(p->energy(y + OQ, y + OV(p)) - e0);
        if (!(de <= res->energy_drift)) res->energy_drift = de;
      }
    }
  }
  res->t = t;
  memcpy(res->q, y + OQ, (size_t)n * sizeof(double));
  memcpy(res->v, y + OV(p), (size_t)n * sizeof(double));
  memcpy(res->lambda, y + OL(p), (size_t)m * sizeof(double));
  {
    long int nst = 0, netf = 0, nncf = 0, nni = 0, nlu = 0;
    IDAGetNumSteps(mem, &nst);
    IDAGetNumErrTestFails(mem, &netf);
    IDAGetNumNonlinSolvConvFails(mem, &nncf);
    IDAGetNumNonlinSolvIters(mem, &nni);
    IDAGetNumLinSolvSetups(mem, &nlu);
    res->nsteps = nst;
    res->nrejected = netf + nncf;
    res->nniters = nni;
    res->nlu = nlu;
  }
  if (flag == 0 && fabs(t - p->t_end) > 1e-12 * (1.0 + p->t_end)) flag = -101;

done:
  res->flag = flag;
  if (flag == 0) suite_finish_result(p, res);
  else res->err = res->mescd = NAN;
  IDAFree(&mem);
  if (LS != NULL) SUNLinSolFree(LS);
  if (A != NULL) SUNMatDestroy(A);
  if (id != NULL) N_VDestroy(id);
  if (yp != NULL) N_VDestroy(yp);
  if (yy != NULL) N_VDestroy(yy);
  SUNContext_Free(&ctx);
  return res->flag;
}
