/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Consistent initial values (spec numerics.md §2, "Consistent initial values"):
 *
 *   [ M   B^T ] [ vdot_0   ]   [ -g(q0, v0, t0)    ]
 *   [ B   0   ] [ lambda_0 ] = [ -Z(q0)(v0, v0)    ]
 *
 * i.e. the index-1 form of the DAE; then a_0 = vdot_0 unless the user gave a_0.
 * ---------------------------------------------------------------------------*/

#include <string.h>

#include "lgn_impl.h"

static int SolveIndex1System(LGNMem mem)
{
  sunindextype i, nv = mem->nv, m = mem->m;
  sunrealtype *rhs = lgnData(mem->rhs), *sol = lgnData(mem->sol);
  const sunrealtype *g = lgnData(mem->g);
  LGNMatrixTerms terms;
  int ret, flag;

  /* evaluate at (q0, v0) through the iterate slots */
  N_VScale(SUN_RCONST(1.0), mem->q, mem->q1);
  N_VScale(SUN_RCONST(1.0), mem->v, mem->v1);
  N_VConst(SUN_RCONST(0.0), mem->vdot1);
  if (m > 0) N_VConst(SUN_RCONST(0.0), mem->lambda1);

  flag = lgnEvalModel(mem, mem->tn, SUNTRUE); /* B: the matrix below */
  if (flag != LGN_SUCCESS) return flag;
  for (i = 0; i < nv; i++) rhs[i] = -g[i];
  if (m > 0) {
    if (mem->curvature != NULL) {
      N_VConst(SUN_RCONST(0.0), mem->phi);
      ret = mem->curvature(mem->tn, mem->q, mem->v, mem->phi, mem->user_data);
      ret = lgnCallbackVector(mem, LGN_CB_CURVATURE, ret, mem->phi, "LGNSolve");
      if (ret != LGN_SUCCESS) return ret;
    } else {
      flag = lgnCurvatureDQ(mem, mem->tn, mem->q, mem->v, mem->phi);
      if (flag != LGN_SUCCESS) return flag;
    }
    for (i = 0; i < m; i++) rhs[nv + i] = -lgnData(mem->phi)[i];
  }
  if (!lgnAllFinite(rhs, nv + m)) {
    LGN_ERROR(mem, LGN_NONFINITE,
              MSG_TIME "NaN or Inf in the forces or constraint curvature at "
              "the initial state.", (double)mem->tn);
    return LGN_NONFINITE;
  }

  lgnInvalidate(mem, LGN_CHANGE_MATRIX); /* A now holds the saddle-point matrix */
  lgnSaddlePointTerms(&terms);
  flag = lgnAssembleIterationMatrix(mem, mem->tn, &terms);
  if (flag == LGN_SUCCESS) flag = lgnLsSetup(mem);
  if (flag == LGN_SUCCESS) flag = lgnLsSolve(mem, mem->sol, mem->rhs);
  if (flag != LGN_SUCCESS) {
    LGN_ERROR(mem, LGN_IC_FAIL,
              MSG_TIME "the consistent initial accelerations could not be "
              "computed: [[M, B^T], [B, 0]] is singular or the solve failed "
              "(check M and B at q0).%s", (double)mem->tn,
              flag == LGN_LSETUP_FAIL ? mem->diag_text : "");
    return LGN_IC_FAIL;
  }
  if (!lgnAllFinite(sol, nv + m)) {
    LGN_ERROR(mem, LGN_IC_FAIL,
              MSG_TIME "the consistent initial accelerations are not finite.",
              (double)mem->tn);
    return LGN_IC_FAIL;
  }
  memcpy(lgnData(mem->vdot), sol, (size_t)nv * sizeof(sunrealtype));
  if (m > 0) memcpy(lgnData(mem->lambda), sol + nv, (size_t)m * sizeof(sunrealtype));
  return LGN_SUCCESS;
}

int lgnInitialConditions(LGNMem mem)
{
  int flag;
  if (!mem->user_vdot0) {
    flag = SolveIndex1System(mem);
    if (flag != LGN_SUCCESS) return flag;
  }
  if (!mem->user_a0) N_VScale(SUN_RCONST(1.0), mem->vdot, mem->a);
  mem->ic_done = SUNTRUE;
  return LGN_SUCCESS;
}
