/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The multibody model object (lignum_model.h): a body set, a joint set and
 * a user force, installed on an integrator by LGNModel_Attach, which sets
 * the callbacks below through the public setters. Each callback sums the
 * sets' terms in a fixed order, bodies then joints then the user's, by the
 * helpers' rule that adds into dense and sparse matrices alike:
 *
 *   g   = g_bodies(q, v) + g_u(t, q, v)
 *   K_t = d g_bodies/dq + d(B^T lambda)/dq + d g_u/dq
 *   C_t = d g_bodies/dv + d g_u/dv
 *
 * It sits on top of the integrator's public API (like a user's program)
 * and knows nothing of the groups but what the sets tell it.
 * ---------------------------------------------------------------------------*/

#include <stdlib.h>

#include <lignum/lignum_model.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_err.h"
#include "lgn_matops.h"
#include "lgn_mbs.h"

struct LGNModelRec {
  LGNErrSink err;
  LGNBodies bodies;         /* referenced                         */
  LGNJoints joints;         /* referenced; NULL: no constraints   */
  LGNGroup G;               /* the sets' group                    */
  LGNForceFn uforce;        /* the user force g_u, or NULL        */
  LGNStiffnessFn ustiff;    /* d g_u/dq, or NULL                  */
  LGNDampingFn udamp;       /* d g_u/dv, or NULL                  */
  void *user_data;          /* passed to the three                */
  N_Vector gu;              /* work: g_u                          */
  SUNMatrix Ku, Cu;         /* work: the user's K and C           */
};

#define MSG_MEM_FAIL "A memory request failed."

static int NullModel(const char *func)
{
  lgnReport(NULL, LGN_ILL_INPUT, func, "model = NULL illegal.");
  return LGN_ILL_INPUT;
}

/* ---------------------------------------------------------------------------
 * Creation, settings, destruction
 * ------------------------------------------------------------------------ */

LGNModel LGNModel_Create(LGNBodies bodies, LGNJoints joints)
{
  struct LGNModelRec *md;
  if (bodies == NULL) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__, "bodies = NULL illegal.");
    return NULL;
  }
  if (joints != NULL && lgnJointsGroup(joints) != lgnBodiesGroup(bodies)) {
    lgnReport(NULL, LGN_ILL_INPUT, __func__,
              "joints: created on another group than bodies (both sets must be "
              "created on the same LGNGroup).");
    return NULL;
  }
  md = (struct LGNModelRec *)calloc(1, sizeof *md);
  if (md == NULL) {
    lgnReport(NULL, LGN_MEM_FAIL, __func__, MSG_MEM_FAIL);
    return NULL;
  }
  lgnErrSinkInit(&md->err);
  md->bodies = bodies;
  md->joints = joints;
  md->G      = lgnBodiesGroup(bodies);
  return md;
}

int LGNModel_SetErrHandlerFn(LGNModel model, LGNErrHandlerFn ehfun, void *eh_data)
{
  if (model == NULL) return NullModel(__func__);
  model->err.ehfun   = ehfun;
  model->err.eh_data = eh_data;
  return LGN_SUCCESS;
}

int LGNModel_SetErrFile(LGNModel model, FILE *errfp)
{
  if (model == NULL) return NullModel(__func__);
  model->err.errfp = errfp;
  return LGN_SUCCESS;
}

void LGNModel_Destroy(LGNModel *model)
{
  if (model == NULL || *model == NULL) return;
  if ((*model)->gu != NULL) N_VDestroy((*model)->gu);
  if ((*model)->Ku != NULL) SUNMatDestroy((*model)->Ku);
  if ((*model)->Cu != NULL) SUNMatDestroy((*model)->Cu);
  free(*model);
  *model = NULL;
}

int LGNModel_SetUserForce(LGNModel model, LGNForceFn force, LGNStiffnessFn K, LGNDampingFn C)
{
  if (model == NULL) return NullModel(__func__);
  if (force == NULL && (K != NULL || C != NULL)) {
    lgnReport(&model->err, LGN_ILL_INPUT, __func__,
              "%s given without force: illegal (the derivatives of which force?).",
              K != NULL ? "K" : "C");
    return LGN_ILL_INPUT;
  }
  model->uforce = force;
  model->ustiff = K;
  model->udamp  = C;
  return LGN_SUCCESS;
}

int LGNModel_SetUserData(LGNModel model, void *user_data)
{
  if (model == NULL) return NullModel(__func__);
  model->user_data = user_data;
  return LGN_SUCCESS;
}

void *LGNModel_GetUserData(LGNModel model) { return model != NULL ? model->user_data : NULL; }

LGNBodies LGNModel_GetBodies(LGNModel model) { return model != NULL ? model->bodies : NULL; }

LGNJoints LGNModel_GetJoints(LGNModel model) { return model != NULL ? model->joints : NULL; }

sunindextype LGNModel_NumConstraints(LGNModel model)
{
  return model != NULL && model->joints != NULL ? LGNJoints_NumConstraints(model->joints) : 0;
}

/* ---------------------------------------------------------------------------
 * The callbacks (user_data = the model). A helper's failure (a negative
 * flag, reported through its set's handler) is unrecoverable (-1); the
 * user's callbacks' returns are passed on.
 * ------------------------------------------------------------------------ */

static int Status(int flag) { return flag == LGN_SUCCESS ? 0 : -1; }

static int ModelMass(sunrealtype t, N_Vector q, SUNMatrix M, void *user_data)
{
  (void)t;
  return Status(LGNBodies_Mass(((LGNModel)user_data)->bodies, q, M));
}

/* g = g_bodies + g_u, g_u written by the user into a zeroed work vector */
static int ModelForce(sunrealtype t, N_Vector q, N_Vector v, N_Vector g, void *user_data)
{
  LGNModel md = (LGNModel)user_data;
  int flag    = LGNBodies_Force(md->bodies, q, v, g);
  if (flag != LGN_SUCCESS) return -1;
  if (md->uforce == NULL) return 0;
  if (md->gu != NULL && N_VGetLength(md->gu) != N_VGetLength(g)) {
    N_VDestroy(md->gu);
    md->gu = NULL;
  }
  if (md->gu == NULL && (md->gu = N_VClone(g)) == NULL) {
    lgnReport(&md->err, LGN_MEM_FAIL, "LGNModel (force)", MSG_MEM_FAIL);
    return -1;
  }
  N_VConst(SUN_RCONST(0.0), md->gu);
  flag = md->uforce(t, q, v, md->gu, md->user_data);
  if (flag != 0) return flag;
  N_VLinearSum(SUN_RCONST(1.0), g, SUN_RCONST(1.0), md->gu, g);
  return 0;
}

static int ModelConstr(sunrealtype t, N_Vector q, N_Vector phi, void *user_data)
{
  return Status(LGNJoints_Residual(((LGNModel)user_data)->joints, t, q, phi));
}

static int ModelConstrJac(sunrealtype t, N_Vector q, SUNMatrix B, void *user_data)
{
  return Status(LGNJoints_Jacobian(((LGNModel)user_data)->joints, t, q, B));
}

static int ModelCurvature(sunrealtype t, N_Vector q, N_Vector v, N_Vector z, void *user_data)
{
  return Status(LGNJoints_Curvature(((LGNModel)user_data)->joints, t, q, v, z));
}

static int ModelConstrTime(sunrealtype t, N_Vector q, N_Vector phit, void *user_data)
{
  return Status(LGNJoints_TimeDerivative(((LGNModel)user_data)->joints, t, q, phit));
}

/* The user's matrix term: *W as an empty matrix like A (dense: zeroed;
 * sparse: no entries), for the user's callback to write; NULL if out of
 * memory. */
static SUNMatrix UserMatrix(LGNModel md, SUNMatrix *W, SUNMatrix A)
{
  if (lgnMatIsSparse(A)) {
    if (*W != NULL && !lgnMatIsSparse(*W)) {
      SUNMatDestroy(*W);
      *W = NULL;
    }
    if (lgnSparseWorkLike(W, A) == NULL)
      lgnReport(&md->err, LGN_MEM_FAIL, "LGNModel (K_t, C_t)", MSG_MEM_FAIL);
    return *W;
  }
  if (*W != NULL && (lgnMatID(*W) != SUNMATRIX_DENSE || SM_ROWS_D((*W)) != SM_ROWS_D(A) ||
                     SM_COLUMNS_D((*W)) != SM_COLUMNS_D(A))) {
    SUNMatDestroy(*W);
    *W = NULL;
  }
  if (*W == NULL && (*W = SUNMatClone(A)) == NULL) {
    lgnReport(&md->err, LGN_MEM_FAIL, "LGNModel (K_t, C_t)", MSG_MEM_FAIL);
    return NULL;
  }
  lgnMatClear(*W);
  return *W;
}

/* A += W, dense or sparse */
static int AddUserMatrix(LGNModel md, SUNMatrix A, SUNMatrix W)
{
  if (lgnMatIsSparse(A)) {
    if (lgnSparseAdd(A, W) == LGN_SUCCESS) return 0;
    lgnReport(&md->err, LGN_MEM_FAIL, "LGNModel (K_t, C_t)", MSG_MEM_FAIL);
    return -1;
  }
  return SUNMatScaleAdd(SUN_RCONST(1.0), A, W) == 0 ? 0 : -1;
}

/* K_t = d g_bodies/dq (M is constant) + d(B^T lambda)/dq + d g_u/dq */
static int ModelStiffness(sunrealtype t, N_Vector q, N_Vector v, N_Vector vdot, N_Vector lambda,
                          SUNMatrix K, void *user_data)
{
  LGNModel md = (LGNModel)user_data;
  SUNMatrix W;
  int flag = LGNBodies_Stiffness(md->bodies, q, v, K);
  if (flag == LGN_SUCCESS && md->joints != NULL)
    flag = LGNJoints_Stiffness(md->joints, t, q, lambda, K);
  if (flag != LGN_SUCCESS) return -1;
  if (md->ustiff == NULL) return 0;
  if ((W = UserMatrix(md, &md->Ku, K)) == NULL) return -1;
  flag = md->ustiff(t, q, v, vdot, lambda, W, md->user_data);
  return flag != 0 ? flag : AddUserMatrix(md, K, W);
}

/* C_t = d g_bodies/dv + d g_u/dv */
static int ModelDamping(sunrealtype t, N_Vector q, N_Vector v, SUNMatrix C, void *user_data)
{
  LGNModel md = (LGNModel)user_data;
  SUNMatrix W;
  int flag = LGNBodies_Damping(md->bodies, q, v, C);
  if (flag != LGN_SUCCESS) return -1;
  if (md->udamp == NULL) return 0;
  if ((W = UserMatrix(md, &md->Cu, C)) == NULL) return -1;
  flag = md->udamp(t, q, v, W, md->user_data);
  return flag != 0 ? flag : AddUserMatrix(md, C, W);
}

/* ---------------------------------------------------------------------------
 * Attaching
 * ------------------------------------------------------------------------ */

int LGNModel_Attach(LGNModel model, void *lgn_mem)
{
  const sunindextype m = LGNModel_NumConstraints(model);
  const sunbooleantype drivers =
      model != NULL && model->joints != NULL && LGNJoints_NumDrivers(model->joints) > 0;
  int flag;
  if (model == NULL) return NullModel(__func__);
  if (lgn_mem == NULL) {
    lgnReport(&model->err, LGN_MEM_NULL, __func__, "lgn_mem = NULL illegal (LGNCreate first).");
    return LGN_MEM_NULL;
  }
  /* the only setter that can refuse a valid memory: first, so that a
   * refusal changes nothing */
  flag = LGNSetGroup(lgn_mem, model->G);
  if (flag != LGN_SUCCESS) {
    lgnReport(&model->err, flag, __func__,
              "lgn_mem: its state (LGNInit) has other sizes than the model's group "
              "(nq = %lld, nv = %lld); nothing changed.",
              (long long)model->G->nq, (long long)model->G->nv);
    return flag;
  }
  /* with a user force but no derivative of it, Lignum's difference
   * quotients give the whole K_t (C_t) */
  (void)LGNSetUserData(lgn_mem, model);
  (void)LGNSetMassFn(lgn_mem, ModelMass);
  (void)LGNSetMassConstant(lgn_mem, SUNTRUE);
  (void)LGNSetForceFn(lgn_mem, ModelForce);
  (void)LGNSetConstraints(lgn_mem, m, m > 0 ? ModelConstr : NULL, m > 0 ? ModelConstrJac : NULL);
  (void)LGNSetCurvatureFn(lgn_mem, m > 0 ? ModelCurvature : NULL);
  (void)LGNSetConstraintTimeFn(lgn_mem, drivers ? ModelConstrTime : NULL);
  (void)LGNSetStiffnessFn(lgn_mem,
                          model->uforce != NULL && model->ustiff == NULL ? NULL : ModelStiffness);
  (void)LGNSetDampingFn(lgn_mem,
                        model->uforce != NULL && model->udamp == NULL ? NULL : ModelDamping);
  return LGN_SUCCESS;
}
