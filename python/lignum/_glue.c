/* -----------------------------------------------------------------------------
 * The C side of the Python package (see _glue.h): model callbacks, the
 * record's life cycle, error capture.
 * SPDX-License-Identifier: BSD-3-Clause
 * ---------------------------------------------------------------------------*/
#include "_glue.h"

#include <lignum/lignum_model.h>
#include <lignum/lignum_planar.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- error capture: Lignum's handlers write here instead of stderr ---- */

static void CopyText(char *dst, size_t len, const char *src)
{
  size_t n = src ? strlen(src) : 0;
  if (n >= len) n = len - 1;
  if (n) memcpy(dst, src, n);
  dst[n] = '\0';
}

static void GlueErrHandler(int error_code, const char *module,
                           const char *function, const char *msg, void *eh_data)
{
  LGNPySystem *sys = (LGNPySystem *)eh_data;
  (void)module;
  if (error_code == LGN_WARNING) { /* kept for Python's warnings module */
    size_t used = strlen(sys->warnings), room = sizeof(sys->warnings) - used;
    if (room > 2) {
      if (used) { sys->warnings[used++] = '\n'; room--; }
      CopyText(sys->warnings + used, room, msg);
    }
    sys->nwarnings++;
    return;
  }
  sys->err_code = error_code;
  CopyText(sys->err_function, sizeof(sys->err_function), function);
  CopyText(sys->err_msg, sizeof(sys->err_msg), msg);
}

void LGNPy_ClearError(LGNPySystem *sys)
{
  if (!sys) return;
  sys->err_code = 0;
  sys->err_function[0] = sys->err_msg[0] = '\0';
  sys->nwarnings = 0;
  sys->warnings[0] = '\0';
}

/* ---- a multibody model: the model object of lignum_model.h installs the
 * body and joint sets' callbacks; C calls Python only for the user force ---- */

/* g_u = -f, f the applied force of a Python function (g_u arrives zeroed
 * and the model adds it to the bodies' g: g - f, as LGNModel_SetUserForce
 * documents). */
static int GlueUserForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  int flag = lgnpy_vec_cb(sys->handle, LGNPY_CB_APPLIED, t, N_VGetArrayPointer(q),
                          N_VGetArrayPointer(v), N_VGetArrayPointer(g));
  if (flag) return flag;
  N_VScale(-1.0, g, g);
  return 0;
}

/* K_u = dg_u/dq = -df/dq and C_u = dg_u/dv = -df/dv from the Python
 * functions (the dense matrix arrives zeroed, the model adds it). */
static int NegatedAppliedJacobian(LGNPySystem *sys, int which, sunrealtype t, N_Vector q,
                                  N_Vector v, SUNMatrix D)
{
  sunrealtype *d = SUNDenseMatrix_Data(D);
  sunindextype i, n = SUNDenseMatrix_LData(D);
  int flag = lgnpy_mat_cb(sys->handle, which, t, N_VGetArrayPointer(q), N_VGetArrayPointer(v),
                          NULL, NULL, d);
  if (flag) return flag;
  for (i = 0; i < n; i++) d[i] = -d[i];
  return 0;
}

static int GlueUserStiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                             N_Vector lambda, SUNMatrix K, void *ud)
{
  (void)vdot;
  (void)lambda;
  return NegatedAppliedJacobian((LGNPySystem *)ud, LGNPY_CB_APPLIED_DQ, t, q, v, K);
}

static int GlueUserDamping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  return NegatedAppliedJacobian((LGNPySystem *)ud, LGNPY_CB_APPLIED_DV, t, q, v, C);
}

/* The model is the integrator's user data: the record is the model's. */
static int GlueModelRoot(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *gout, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)LGNModel_GetUserData((LGNModel)ud);
  return lgnpy_vec_cb(sys->handle, LGNPY_CB_ROOT, t, N_VGetArrayPointer(q),
                      N_VGetArrayPointer(v), gout);
}

/* ---- a model of Python functions: forwarders to Python ---- */

static int GlueMass(sunrealtype t, N_Vector q, SUNMatrix M, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  return lgnpy_mat_cb(sys->handle, LGNPY_CB_MASS, t, N_VGetArrayPointer(q), NULL, NULL,
                      NULL, SUNDenseMatrix_Data(M));
}

static int GlueForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  return lgnpy_vec_cb(sys->handle, LGNPY_CB_FORCE, t, N_VGetArrayPointer(q),
                      N_VGetArrayPointer(v), N_VGetArrayPointer(g));
}

static int GlueConstr(sunrealtype t, N_Vector q, N_Vector phi, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  return lgnpy_vec_cb(sys->handle, LGNPY_CB_CONSTR, t, N_VGetArrayPointer(q), NULL,
                      N_VGetArrayPointer(phi));
}

static int GlueConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  return lgnpy_mat_cb(sys->handle, LGNPY_CB_JAC, t, N_VGetArrayPointer(q), NULL, NULL,
                      NULL, SUNDenseMatrix_Data(B));
}

static int GlueCurvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  return lgnpy_vec_cb(sys->handle, LGNPY_CB_CURVATURE, t, N_VGetArrayPointer(q),
                      N_VGetArrayPointer(v), N_VGetArrayPointer(z));
}

static int GlueConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  return lgnpy_vec_cb(sys->handle, LGNPY_CB_CONSTR_TIME, t, N_VGetArrayPointer(q), NULL,
                      N_VGetArrayPointer(phit));
}

static int GlueStiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot,
                         N_Vector lambda, SUNMatrix K, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  return lgnpy_mat_cb(sys->handle, LGNPY_CB_STIFFNESS, t, N_VGetArrayPointer(q),
                      N_VGetArrayPointer(v), N_VGetArrayPointer(vdot),
                      lambda ? N_VGetArrayPointer(lambda) : NULL, SUNDenseMatrix_Data(K));
}

static int GlueDamping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  return lgnpy_mat_cb(sys->handle, LGNPY_CB_DAMPING, t, N_VGetArrayPointer(q),
                      N_VGetArrayPointer(v), NULL, NULL, SUNDenseMatrix_Data(C));
}

static int GlueRoot(sunrealtype t, N_Vector q, N_Vector v, sunrealtype *gout, void *ud)
{
  LGNPySystem *sys = (LGNPySystem *)ud;
  return lgnpy_vec_cb(sys->handle, LGNPY_CB_ROOT, t, N_VGetArrayPointer(q),
                      N_VGetArrayPointer(v), gout);
}

/* ---- drivers: time laws in C, or a Python function ---- */

static int GlueDrive(sunrealtype t, sunrealtype f[3], void *data)
{
  LGNPyDrive *d = (LGNPyDrive *)data;
  const sunrealtype *c = d->c;
  switch (d->kind) {
  case LGNPY_DRIVE_POLYNOMIAL:
    f[0] = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
    f[1] = c[1] + t * (2.0 * c[2] + 3.0 * t * c[3]);
    f[2] = 2.0 * c[2] + 6.0 * t * c[3];
    return 0;
  case LGNPY_DRIVE_HARMONIC: /* c0 + c1 sin(c2 t + c3) */
    f[0] = c[0] + c[1] * sin(c[2] * t + c[3]);
    f[1] = c[1] * c[2] * cos(c[2] * t + c[3]);
    f[2] = -c[1] * c[2] * c[2] * sin(c[2] * t + c[3]);
    return 0;
  default:
    return lgnpy_drive_cb(d->sys->handle, d->index, t, f);
  }
}

/* ---- life cycle ---- */

LGNPySystem *LGNPy_Create(void *handle)
{
  LGNPySystem *sys = (LGNPySystem *)calloc(1, sizeof(*sys));
  if (!sys) return NULL;
  if (SUNContext_Create(NULL, &sys->ctx) != 0) {
    free(sys);
    return NULL;
  }
  sys->handle = handle;
  return sys;
}

void LGNPy_Free(LGNPySystem *sys)
{
  int k;
  if (!sys) return;
  LGNFree(&sys->mem);
  if (sys->LS) SUNLinSolFree(sys->LS);
  if (sys->A) SUNMatDestroy(sys->A);
  if (sys->y) N_VDestroy(sys->y);
  if (sys->q) N_VDestroy(sys->q); /* the data belong to Python's arrays */
  if (sys->v) N_VDestroy(sys->v);
  if (sys->vdot) N_VDestroy(sys->vdot);
  if (sys->lambda) N_VDestroy(sys->lambda);
  LGNModel_Destroy(&sys->model); /* after LGNFree, before its sets */
  LGNJoints_Destroy(&sys->joints);
  LGNBodies_Destroy(&sys->bodies);
  for (k = 0; k < sys->ndrives; k++) free(sys->drives[k]);
  if (sys->G) LGNGroup_Destroy(sys->G);
  for (k = 0; k < sys->nfactors; k++) LGNGroup_Destroy(sys->factors[k]);
  SUNContext_Free(&sys->ctx);
  free(sys);
}

/* kind: LGNPY_GROUP_* (0 R^n, 1 SO(3), 2 R^3 x SO(3), 3 SE(3), 4 SE(2),
 * 5 R^2 x SO(2)). */
int LGNPy_AddGroupFactor(LGNPySystem *sys, int kind, int64_t n)
{
  LGNGroup F = NULL;
  if (!sys || sys->G) return LGN_ILL_INPUT;
  if (sys->nfactors >= (int)(sizeof(sys->factors) / sizeof(sys->factors[0])))
    return LGN_ILL_INPUT;
  switch (kind) {
  case 0: F = n > 0 ? LGNGroup_Rn((sunindextype)n) : NULL; break;
  case 1: F = LGNGroup_SO3(); break;
  case 2: F = LGNGroup_R3xSO3(); break;
  case 3: F = LGNGroup_SE3(); break;
  case LGNPY_GROUP_SE2: F = LGNGroup_SE2(); break;
  case LGNPY_GROUP_R2XSO2: F = LGNGroup_R2xSO2(); break;
  default: return LGN_ILL_INPUT;
  }
  if (!F) return kind == 0 && n <= 0 ? LGN_ILL_INPUT : LGN_MEM_FAIL;
  sys->factors[sys->nfactors++] = F;
  return LGN_SUCCESS;
}

/* The configuration group: the single factor itself, or their product. */
static int BuildGroup(LGNPySystem *sys)
{
  if (sys->nfactors < 1) return LGN_ILL_INPUT;
  if (sys->nfactors == 1) { /* used as it is: moved out of the factor list */
    sys->G = sys->factors[0];
    sys->nfactors = 0;
  } else {
    sys->G = LGNGroup_Product(sys->nfactors, sys->factors);
    if (!sys->G) return LGN_MEM_FAIL;
  }
  sys->nq = sys->G->nq;
  sys->nv = sys->G->nv;
  return LGN_SUCCESS;
}

/* nbodies rigid bodies, one factor of kind `group` each (R^3 x SO(3) as the
 * examples, or a planar group), their body and joint sets and the model
 * object on them (lignum_model.h), whose user data is this record. */
int LGNPy_MultibodyInit(LGNPySystem *sys, int nbodies, int group)
{
  int k, flag;
  if (!sys || sys->G || nbodies < 1 || nbodies > 64) return LGN_ILL_INPUT;
  if (group != LGNPY_GROUP_R3XSO3 && group != LGNPY_GROUP_SE2 && group != LGNPY_GROUP_R2XSO2)
    return LGN_ILL_INPUT;
  for (k = 0; k < nbodies; k++)
    if ((flag = LGNPy_AddGroupFactor(sys, group, 0))) return flag;
  if ((flag = BuildGroup(sys))) return flag;
  sys->planar = group != LGNPY_GROUP_R3XSO3;
  sys->bodies = LGNBodies_Create(sys->G);
  sys->joints = LGNJoints_Create(sys->G);
  if (!sys->bodies || !sys->joints) return LGN_MEM_FAIL;
  LGNBodies_SetErrHandlerFn(sys->bodies, GlueErrHandler, sys);
  LGNJoints_SetErrHandlerFn(sys->joints, GlueErrHandler, sys);
  sys->model = LGNModel_Create(sys->bodies, sys->joints);
  if (!sys->model) return LGN_MEM_FAIL;
  LGNModel_SetErrHandlerFn(sys->model, GlueErrHandler, sys);
  return LGNModel_SetUserData(sys->model, sys);
}

int LGNPy_PythonModelInit(LGNPySystem *sys, int64_t m, int pyflags)
{
  int flag;
  if (!sys || sys->G || m < 0) return LGN_ILL_INPUT;
  if ((flag = BuildGroup(sys))) return flag;
  sys->python_model = 1;
  sys->pyflags = pyflags;
  sys->m = (sunindextype)m;
  return LGN_SUCCESS;
}

/* The Python applied force as the model's user force, with its Jacobians
 * df/dq, df/dv when given (without one, the model leaves all of K_t or C_t
 * to Lignum's difference quotients, lignum_model.h). */
int LGNPy_SetAppliedForce(LGNPySystem *sys, int on, int has_dq, int has_dv)
{
  if (!sys || !sys->model || sys->mem || (!on && (has_dq || has_dv))) return LGN_ILL_INPUT;
  sys->applied_force = on != 0;
  return LGNModel_SetUserForce(sys->model, on ? GlueUserForce : NULL,
                               has_dq ? GlueUserStiffness : NULL,
                               has_dv ? GlueUserDamping : NULL);
}

int LGNPy_AddDriver(LGNPySystem *sys, int rotation, int a, const double *s_a,
                    const double *axis_a, const double *ref_a, int b,
                    const double *s_b, const double *ref_b, int kind,
                    const double *c)
{
  LGNPyDrive *d;
  int flag, k;
  if (!sys || !sys->joints || sys->mem || kind < 0 || kind > LGNPY_DRIVE_PYTHON)
    return LGN_ILL_INPUT;
  if (sys->ndrives >= (int)(sizeof(sys->drives) / sizeof(sys->drives[0])))
    return LGN_ILL_INPUT;
  d = (LGNPyDrive *)calloc(1, sizeof(*d));
  if (!d) return LGN_MEM_FAIL;
  d->sys = sys;
  d->kind = kind;
  d->index = sys->ndrives;
  for (k = 0; k < 4; k++) d->c[k] = c ? c[k] : 0.0;
  if (sys->planar && rotation) /* 2-vectors s_a, axis_a, s_b; no references */
    flag = LGNJoints_AddPlanarRotationDriver(sys->joints, a, b, GlueDrive, d);
  else if (sys->planar)
    flag = LGNJoints_AddPlanarTranslationDriver(sys->joints, a, s_a, axis_a, b, s_b, GlueDrive,
                                                d);
  else if (rotation)
    flag = LGNJoints_AddRotationDriver(sys->joints, a, axis_a, ref_a, b, ref_b, GlueDrive, d);
  else
    flag = LGNJoints_AddTranslationDriver(sys->joints, a, s_a, axis_a, b, s_b, GlueDrive, d);
  if (flag) {
    free(d);
    return flag;
  }
  sys->drives[sys->ndrives++] = d;
  return LGN_SUCCESS;
}

/* Create the integrator on the model: the state vectors wrap q0, v0 (the
 * Python arrays, which LGNSolve then updates in place) and the outputs
 * vdot, lambda; the callbacks; LGNInit; the dense linear solver. */
int LGNPy_Attach(LGNPySystem *sys, double t0, double *q0, double *v0,
                 double *vdot, double *lambda, int mass_constant)
{
  sunindextype n;
  int flag;
  if (!sys || !sys->G || sys->mem) return LGN_ILL_INPUT;
  if (!sys->python_model) sys->m = LGNModel_NumConstraints(sys->model);
  n = sys->nv + sys->m;
  sys->q = N_VMake_Serial(sys->nq, q0, sys->ctx);
  sys->v = N_VMake_Serial(sys->nv, v0, sys->ctx);
  sys->vdot = N_VMake_Serial(sys->nv, vdot, sys->ctx);
  sys->lambda = N_VMake_Serial(sys->m > 0 ? sys->m : 1, lambda, sys->ctx);
  sys->y = N_VNew_Serial(n, sys->ctx);
  sys->A = SUNDenseMatrix(n, n, sys->ctx);
  if (!sys->q || !sys->v || !sys->vdot || !sys->lambda || !sys->y ||
      !sys->A)
    return LGN_MEM_FAIL;
  sys->LS = LGNLinSol_Dense(sys->y, sys->A, sys->ctx);
  sys->mem = LGNCreate(sys->ctx);
  if (!sys->LS || !sys->mem) return LGN_MEM_FAIL;
  flag = LGNSetErrHandlerFn(sys->mem, GlueErrHandler, sys);
  if (!flag && !sys->python_model) { /* the model installs every callback */
    flag = LGNModel_Attach(sys->model, sys->mem);
  } else if (!flag) {
    flag = LGNSetGroup(sys->mem, sys->G);
    if (!flag) flag = LGNSetUserData(sys->mem, sys);
    if (!flag) flag = LGNSetMassFn(sys->mem, GlueMass);
    if (!flag) flag = LGNSetForceFn(sys->mem, GlueForce);
    if (!flag && sys->m > 0)
      flag = LGNSetConstraints(sys->mem, sys->m, GlueConstr, GlueConstrJac);
    if (!flag && (sys->pyflags & LGNPY_HAS_STIFFNESS))
      flag = LGNSetStiffnessFn(sys->mem, GlueStiffness);
    if (!flag && (sys->pyflags & LGNPY_HAS_DAMPING))
      flag = LGNSetDampingFn(sys->mem, GlueDamping);
    if (!flag && sys->m > 0 && (sys->pyflags & LGNPY_HAS_CURVATURE))
      flag = LGNSetCurvatureFn(sys->mem, GlueCurvature);
    if (!flag && sys->m > 0 && (sys->pyflags & LGNPY_HAS_CONSTR_TIME))
      flag = LGNSetConstraintTimeFn(sys->mem, GlueConstrTime);
  }
  if (!flag) flag = LGNSetMassConstant(sys->mem, mass_constant ? SUNTRUE : SUNFALSE);
  if (!flag) flag = LGNInit(sys->mem, t0, sys->q, sys->v);
  if (!flag) flag = LGNSetLinearSolver(sys->mem, sys->LS, sys->A);
  return flag;
}

int LGNPy_RootInit(LGNPySystem *sys, int nroots)
{
  int flag;
  if (!sys || !sys->mem) return LGN_MEM_NULL;
  flag = LGNRootInit(sys->mem, nroots,
                     nroots < 1 ? NULL : sys->python_model ? GlueRoot : GlueModelRoot);
  if (!flag) sys->nroots = nroots;
  return flag;
}

/* Kinetic and potential energy of the bodies at (q, v), any arrays. */
int LGNPy_Energy(LGNPySystem *sys, double *q, double *v, double *kinetic,
                 double *potential)
{
  N_Vector qq, vv;
  int flag;
  if (!sys || !sys->bodies) return LGN_ILL_INPUT;
  qq = N_VMake_Serial(sys->nq, q, sys->ctx);
  vv = N_VMake_Serial(sys->nv, v, sys->ctx);
  flag = (qq && vv) ? LGNBodies_Energy(sys->bodies, qq, vv, kinetic, potential) : LGN_MEM_FAIL;
  if (qq) N_VDestroy(qq);
  if (vv) N_VDestroy(vv);
  return flag;
}

/* Phi(q, t) of the joints at any q. */
int LGNPy_Residual(LGNPySystem *sys, double t, double *q, double *phi)
{
  N_Vector qq, pp;
  int flag;
  if (!sys || !sys->joints || sys->m < 1) return LGN_ILL_INPUT;
  qq = N_VMake_Serial(sys->nq, q, sys->ctx);
  pp = N_VMake_Serial(sys->m, phi, sys->ctx);
  flag = (qq && pp) ? LGNJoints_Residual(sys->joints, t, qq, pp) : LGN_MEM_FAIL;
  if (qq) N_VDestroy(qq);
  if (pp) N_VDestroy(pp);
  return flag;
}
