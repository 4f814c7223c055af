/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The getters of one scalar (the current time and step, the settings in
 * use, the counters), written out one by one so that grep and ctags find
 * them. Each checks the memory block and the output pointer, then reads one
 * field of the record. The getters of several outputs, of vectors and of
 * names are in lgn_setget.c.
 * ---------------------------------------------------------------------------*/

#include "lgn_impl.h"
#include "lgn_sparse.h"

/* The preamble of every getter here: the memory block exists and the output
 * pointer, named name in the message, is not NULL. */
static int ScalarOut(void *lgn_mem, const char *func, const void *out, const char *name,
                     LGNMem *mem)
{
  int flag = lgnAccessMem(lgn_mem, func, mem);
  if (flag != LGN_SUCCESS) return flag;
  if (out == NULL) {
    LGN_ERROR(*mem, LGN_ILL_INPUT, "%s = NULL illegal.", name);
    return LGN_ILL_INPUT;
  }
  return LGN_SUCCESS;
}

int LGNGetCurrentTime(void *lgn_mem, sunrealtype *tcur)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, tcur, "tcur", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *tcur = mem->tn;
  return LGN_SUCCESS;
}

int LGNGetLastStep(void *lgn_mem, sunrealtype *hlast)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, hlast, "hlast", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *hlast = mem->hlast;
  return LGN_SUCCESS;
}

int LGNGetCurrentStep(void *lgn_mem, sunrealtype *hcur)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, hcur, "hcur", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *hcur = mem->step_control == LGN_STEP_ADAPTIVE ? mem->hnext : mem->h;
  return LGN_SUCCESS;
}

int LGNGetActualInitStep(void *lgn_mem, sunrealtype *hinused)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, hinused, "hinused", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *hinused = mem->step_control == LGN_STEP_ADAPTIVE ? mem->h0_actual : mem->h;
  return LGN_SUCCESS;
}

int LGNGetNumErrTestFails(void *lgn_mem, long int *netfails)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, netfails, "netfails", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *netfails = mem->netf;
  return LGN_SUCCESS;
}

int LGNGetStepSize(void *lgn_mem, sunrealtype *h)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, h, "h", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *h = mem->h;
  return LGN_SUCCESS;
}

int LGNGetKinematics(void *lgn_mem, int *kinematics)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, kinematics, "kinematics", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *kinematics = mem->kinematics;
  return LGN_SUCCESS;
}

int LGNGetConstraintIndex(void *lgn_mem, int *index)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, index, "index", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *index = mem->constr_index;
  return LGN_SUCCESS;
}

int LGNGetNewtonMode(void *lgn_mem, int *mode)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, mode, "mode", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *mode = mem->newton_mode;
  return LGN_SUCCESS;
}

int LGNGetStepControl(void *lgn_mem, int *control)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, control, "control", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *control = mem->step_control;
  return LGN_SUCCESS;
}

int LGNGetLastErrNorm(void *lgn_mem, sunrealtype *errnorm)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, errnorm, "errnorm", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *errnorm = mem->err_norm;
  return LGN_SUCCESS;
}

int LGNGetNumSteps(void *lgn_mem, long int *nsteps)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nsteps, "nsteps", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nsteps = mem->nst;
  return LGN_SUCCESS;
}

int LGNGetNumNewtonIters(void *lgn_mem, long int *nniters)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nniters, "nniters", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nniters = mem->nni;
  return LGN_SUCCESS;
}

int LGNGetNumNewtonConvFails(void *lgn_mem, long int *nncfails)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nncfails, "nncfails", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nncfails = mem->nncf;
  return LGN_SUCCESS;
}

int LGNGetNumStepFails(void *lgn_mem, long int *nfails)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nfails, "nfails", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nfails = mem->nfails;
  return LGN_SUCCESS;
}

int LGNGetNumResEvals(void *lgn_mem, long int *nres)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nres, "nres", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nres = mem->nre;
  return LGN_SUCCESS;
}

int LGNGetNumDQEvals(void *lgn_mem, long int *ndq)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, ndq, "ndq", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *ndq = mem->ndq;
  return LGN_SUCCESS;
}

int LGNGetNumJacEvals(void *lgn_mem, long int *njevals)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, njevals, "njevals", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *njevals = mem->nje;
  return LGN_SUCCESS;
}

int LGNGetNumLinSolvSetups(void *lgn_mem, long int *nlsetups)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nlsetups, "nlsetups", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nlsetups = mem->nlsetup;
  return LGN_SUCCESS;
}

int LGNGetNumLinSolves(void *lgn_mem, long int *nlsolves)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nlsolves, "nlsolves", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nlsolves = mem->nlsolve;
  return LGN_SUCCESS;
}

int LGNGetLastLinFlag(void *lgn_mem, long int *flag)
{
  LGNMem mem;
  int status = ScalarOut(lgn_mem, __func__, flag, "flag", &mem);
  if (status != LGN_SUCCESS) return status;
  *flag = mem->last_lin_flag;
  return LGN_SUCCESS;
}

int LGNGetNumNewtonStalls(void *lgn_mem, long int *nstalls)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nstalls, "nstalls", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nstalls = mem->nstall;
  return LGN_SUCCESS;
}

int LGNGetNumMatrixReuses(void *lgn_mem, long int *nreuses)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nreuses, "nreuses", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nreuses = mem->nreuse;
  return LGN_SUCCESS;
}

int LGNGetNumNewtonRestarts(void *lgn_mem, long int *nrestarts)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nrestarts, "nrestarts", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nrestarts = mem->nrestart;
  return LGN_SUCCESS;
}

int LGNGetNumSparsityAnalyses(void *lgn_mem, long int *nanalyses)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nanalyses, "nanalyses", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nanalyses = mem->sp != NULL ? mem->sp->npattern : 0L;
  return LGN_SUCCESS;
}

int LGNGetIterationMatrixNnz(void *lgn_mem, long int *nnz)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, nnz, "nnz", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *nnz = lgnIterationMatrixNnz(mem);
  return LGN_SUCCESS;
}

int LGNGetNumDQColors(void *lgn_mem, long int *ncolors)
{
  LGNMem mem;
  int flag = ScalarOut(lgn_mem, __func__, ncolors, "ncolors", &mem);
  if (flag != LGN_SUCCESS) return flag;
  *ncolors = mem->sp != NULL ? (long int)mem->sp->Kcol.ncolors : (long int)mem->nv;
  return LGN_SUCCESS;
}
