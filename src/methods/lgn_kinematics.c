/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The kinematics variants, one table of operations each (LGNKinematicsOps).
 * The step works in the local coordinate sigma of the step,
 * q_{n+1} = q_n o exp(sigma), with Newmark formulas on sigma:
 *
 *   sigma      = h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}
 *   sigma_dot  = v_n + h (1 - gamma) a_n + h gamma a_{n+1}
 *   a_{n+1}    = a+ + (1-af)/(1-am) sigma_ddot,   a+ = (af vdot_n - am a_n)/(1-am)
 *
 * (lgnFormIncrement; sigma = h Delta q_n of the Brüls-Cardona form). The
 * variants differ only in the map (sigma, sigma_dot, sigma_ddot) -> (v, vdot)
 * and what follows from it:
 *
 *   simplified: v = sigma_dot,           vdot = sigma_ddot   (LGNM, LGGalpha;
 *               Brüls and Cardona 2010, Arnold and Brüls 2007)
 *   exact:      v = T(sigma) sigma_dot,  vdot = T sigma_ddot + Tdot(sigma, sigma_dot) sigma_dot
 *               (the modified methods: the velocity is the exact derivative
 *               of the configuration along the step)
 *   sigma:      as simplified, but the predicted increment is scaled by
 *               Xi = I - (h beta/(2 gamma)) ad(sigma_dot) and the Newton
 *               corrections are composed on the right of q1; no T in the
 *               iteration matrix.
 *
 * On R^n all three coincide with the conventional Newmark /
 * generalized-alpha method.
 * ---------------------------------------------------------------------------*/

#include <stddef.h>

#include "lgn_impl.h"

/* =============================================================================
 * Shared by the variants
 * ===========================================================================*/

/* sigma and sigma_dot from the current sigma_ddot (Newmark on sigma):
 * a_{n+1} = a+ + (1-af)/(1-am) sigma_ddot. */
void lgnFormIncrement(LGNMem mem, const LGNStepCoeffs *c)
{
  sunindextype i, nv = mem->nv;
  const sunrealtype h = c->h, beta = mem->beta, gamma = mem->gamma;
  const sunrealtype ca = (SUN_RCONST(1.0) - mem->alpha_f) /
                         (SUN_RCONST(1.0) - mem->alpha_m);
  const sunrealtype *v = lgnData(mem->v), *a = mem->a_step;
  sunrealtype a1;

  for (i = 0; i < nv; i++) {
    a1                = mem->a_pred[i] + ca * mem->sigma_ddot[i];
    mem->sigma[i]     = h * v[i] + h * h * ((SUN_RCONST(0.5) - beta) * a[i] + beta * a1);
    mem->sigma_dot[i] = v[i] + h * ((SUN_RCONST(1.0) - gamma) * a[i] + gamma * a1);
  }
}

/* The saddle-point matrix [[M, B^T], [B, 0]] of the initial values. */
void lgnSaddlePointTerms(LGNMatrixTerms *terms)
{
  terms->cM  = SUN_RCONST(1.0);
  terms->cC  = SUN_RCONST(0.0);
  terms->cK  = SUN_RCONST(0.0);
  terms->cBv = SUN_RCONST(0.0);
  terms->TM = terms->TC = terms->TK = terms->TB = NULL;
  terms->TP = terms->UA = terms->UV = terms->GB = NULL;
  terms->gsign = SUN_RCONST(0.0);
  terms->ggl = SUNFALSE;
}

/* The coefficients of every step's matrix, no T (I everywhere). */
static void StepTerms(LGNMem mem, const LGNStepCoeffs *c, LGNMatrixTerms *terms)
{
  terms->cM  = c->scale * c->beta_p;
  terms->cC  = c->scale * c->gamma_p;
  terms->cK  = c->scale;
  terms->cBv = SUN_RCONST(0.0);
  terms->TM = terms->TC = terms->TK = terms->TB = NULL;
  terms->TP = terms->UA = terms->UV = terms->GB = NULL;
  terms->gsign = SUN_RCONST(0.0);
  terms->ggl = SUNFALSE;
  (void)mem;
}

/* GGL in the Newmark family (doc/theory.md §7.1): the Phi rows B T, and
 * the column of nu = h eta, which moves the Newmark increment
 * s = sigma + B(q_n)^T nu (sigma_dot by gamma' B_n^T dnu, sigma_ddot by
 * beta' B_n^T dnu) but not q1: (cM M UA + cC C UV) B_n^T in the dynamic
 * rows, 0 in the Phi rows, B UV B_n^T in the velocity rows, with UV, UA
 * the normalised derivatives of v and vdot with s. */
static void GGLNewmarkTerms(LGNMem mem, LGNMatrixTerms *terms,
                            const sunrealtype *UA, const sunrealtype *UV)
{
  if (mem->constr_index != LGN_CONSTR_GGL || mem->m == 0) return;
  terms->ggl   = SUNTRUE;
  terms->TP    = mem->Tm;
  terms->UA    = UA;
  terms->UV    = UV;
  terms->GB    = mem->ggl_Bn;
  terms->gsign = SUN_RCONST(1.0);
}

/* Index 2 (and GGL's velocity row) with T in the matrix: the change of
 * B v with the configuration, (1/gamma') D_q(B v) T, with 1/gamma' = cK/cC. */
static void ConstraintVelocityTerm(LGNMem mem, LGNMatrixTerms *terms)
{
  if (mem->constr_index != LGN_CONSTR_INDEX3 && mem->m > 0 &&
      terms->cC != SUN_RCONST(0.0))
    terms->cBv = terms->cK / terms->cC;
}

/* q1 = q_n o exp(sigma); with_tangent: also Tm = T(sigma). */
static int Configuration(LGNMem mem, sunbooleantype with_tangent)
{
  LGNGroup G = mem->G;
  int ret = G->ops.compose_exp(G, lgnData(mem->q), mem->sigma, lgnData(mem->q1));
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
  return with_tangent ? lgnTangentMatrices(mem) : LGN_SUCCESS;
}

/* v1 = sigma_dot and vdot1 = sigma_ddot: the increments live in v1 and
 * vdot1 themselves (nothing to copy per iteration). Bound at the start of
 * every step attempt, since a completed step swaps v with v1 and vdot with
 * vdot1. */
static void BindToIterate(LGNMem mem)
{
  mem->sigma_dot  = lgnData(mem->v1);
  mem->sigma_ddot = lgnData(mem->vdot1);
}

/* q1 = q_n o exp(sigma): the Newmark increment is the chart coordinate. */
static const sunrealtype *NewmarkIncrement(LGNMem mem)
{
  return mem->sigma;
}

/* =============================================================================
 * Simplified kinematics: v = sigma_dot, vdot = sigma_ddot
 * ===========================================================================*/

static int SimplifiedPredict(LGNMem mem, const LGNStepCoeffs *c,
                             sunrealtype *acc, sunbooleantype extrapolate)
{
  (void)mem;
  (void)c;
  (void)acc;
  (void)extrapolate;
  return LGN_SUCCESS; /* the Newmark prediction is the iterate */
}

static int SimplifiedIterate(LGNMem mem, sunbooleantype with_tangent)
{
  return Configuration(mem, with_tangent);
}

/* cM M + cC C + cK K T; B T (index 3) or B + (1/gamma') D_q(B v) T (index 2);
 * GGL: both rows, and v, vdot move with s as with sigma (UA = UV = I). */
static int SimplifiedMatrix(LGNMem mem, const LGNStepCoeffs *c,
                            LGNMatrixTerms *terms)
{
  StepTerms(mem, c, terms);
  terms->TK = mem->Tm;
  terms->TB = mem->constr_index == LGN_CONSTR_INDEX3 ? mem->Tm : NULL;
  ConstraintVelocityTerm(mem, terms);
  GGLNewmarkTerms(mem, terms, NULL, NULL);
  return LGN_SUCCESS;
}

static const LGNKinematicsOps simplified_ops = {
  "simplified", SUNFALSE, SUNFALSE, SUNTRUE,
  BindToIterate, SimplifiedPredict, SimplifiedIterate, SimplifiedMatrix, NULL,
  NewmarkIncrement};

/* =============================================================================
 * Exact kinematics: v = T sigma_dot, vdot = T sigma_ddot + Tdot sigma_dot
 * ===========================================================================*/

/* The increments have arrays of their own (lgnAllocWork). */
static void ExactBind(LGNMem mem)
{
  mem->sigma_dot  = mem->sigma + mem->nv;
  mem->sigma_ddot = mem->sigma + 2 * mem->nv;
}

/* With the extrapolating predictor, the guess acc of vdot_{n+1} mapped into
 * the chart of the step: sigma_ddot = T(sigma)^{-1} (acc - Tdot(sigma,
 * sigma_dot) sigma_dot), one fixed-point pass. */
static int ExactPredict(LGNMem mem, const LGNStepCoeffs *c, sunrealtype *acc,
                        sunbooleantype extrapolate)
{
  LGNGroup G = mem->G;
  sunindextype i, nv = mem->nv;
  int ret;
  if (!extrapolate) return LGN_SUCCESS;
  ret = G->ops.tangent_dot_apply(G, mem->sigma, mem->sigma_dot, mem->sigma_dot,
                                 mem->work_nv);
  for (i = 0; i < nv && ret == 0; i++) mem->work_nv[i] = acc[i] - mem->work_nv[i];
  if (ret == 0)
    ret = G->ops.tangent_inverse_apply(G, mem->sigma, mem->work_nv, mem->sigma_ddot);
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
  lgnFormIncrement(mem, c);
  return LGN_SUCCESS;
}

/* q1, v1, vdot1 (and Tm) leaf by leaf, one fused evaluation per built-in
 * leaf (lgn_tangent.c). */
static int ExactIterate(LGNMem mem, sunbooleantype with_tangent)
{
  return lgnExactKinematicsMap(mem, with_tangent);
}

/* cM M Ta + cC C Tv + cK K T; B T (index 3) or B Tv + (1/gamma') D_q(B v) T
 * (index 2), with Ta, Tv the derivatives of vdot and v (lgn_tangent.c).
 * GGL: both rows; s moves v by gamma' T and vdot by beta' Ta less the part
 * of Ta from sigma itself (Q / beta', O(h^2) relative), taken as Ta. */
static int ExactMatrix(LGNMem mem, const LGNStepCoeffs *c, LGNMatrixTerms *terms)
{
  int flag = lgnExactKinematicsDerivatives(mem, c->gamma_p, c->beta_p);
  if (flag != LGN_SUCCESS) return flag;
  StepTerms(mem, c, terms);
  terms->TM = mem->Ta;
  terms->TC = mem->Tv;
  terms->TK = mem->Tm;
  terms->TB = mem->constr_index == LGN_CONSTR_INDEX3 ? mem->Tm : mem->Tv;
  ConstraintVelocityTerm(mem, terms);
  GGLNewmarkTerms(mem, terms, mem->Ta, mem->Tm);
  return LGN_SUCCESS;
}

static const LGNKinematicsOps exact_ops = {
  "exact", SUNTRUE, SUNTRUE, SUNTRUE,
  ExactBind, ExactPredict, ExactIterate, ExactMatrix, NULL, NewmarkIncrement};

/* =============================================================================
 * The sigma variant: simplified kinematics, scaled predictor, corrections
 * composed on the right
 * ===========================================================================*/

/* Always the zero predictor, then Xi sigma = sigma - (h beta/(2 gamma))
 * ad(sigma_dot) sigma, with ad(w) y = -2 Tdot(0, w) y in any Lie group, and
 * q1 = q_n o exp(Xi sigma). Its result depends on the path of the Newton
 * iterates, so the predictor is part of the method. */
static int SigmaPredict(LGNMem mem, const LGNStepCoeffs *c, sunrealtype *acc,
                        sunbooleantype extrapolate)
{
  LGNGroup G = mem->G;
  sunindextype i, nv = mem->nv;
  sunrealtype *zero = acc;
  int ret;
  (void)extrapolate;
  for (i = 0; i < nv; i++) zero[i] = SUN_RCONST(0.0);
  ret = G->ops.tangent_dot_apply(G, zero, mem->sigma_dot, mem->sigma, mem->work_nv);
  for (i = 0; i < nv && ret == 0; i++)
    mem->sigma[i] += (c->h * mem->beta / mem->gamma) * mem->work_nv[i];
  if (ret == 0)
    ret = G->ops.compose_exp(G, lgnData(mem->q), mem->sigma, lgnData(mem->q1));
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
  for (i = 0; i < nv; i++) mem->incr[i] = mem->sigma[i]; /* q1 = q_n o exp(incr) */
  return LGN_SUCCESS;
}

/* q1 is carried by the corrections; v1, vdot1 are the increments. */
static int SigmaIterate(LGNMem mem, sunbooleantype with_tangent)
{
  (void)mem;
  (void)with_tangent;
  return LGN_SUCCESS;
}

/* No T anywhere: cM M + cC C + cK K, and B. */
static int SigmaMatrix(LGNMem mem, const LGNStepCoeffs *c, LGNMatrixTerms *terms)
{
  StepTerms(mem, c, terms);
  return LGN_SUCCESS;
}

/* q1 <- q1 o exp(delta), and its chart coordinate
 * incr <- log(exp(incr) exp(delta)) = incr + T(incr)^{-1} delta + O(|delta|^2 |incr|)
 * (first order in the correction, exact in incr), for the error estimate
 * and the dense output; without T^{-1} in the group, the Baker-Campbell-
 * Hausdorff form incr + delta + (1/2) ad(incr) delta (ad(x) y = -2 Tdot(0, x) y),
 * third order in h. */
static int SigmaCorrect(LGNMem mem, const sunrealtype *delta)
{
  LGNGroup G = mem->G;
  sunindextype i, nv = mem->nv;
  int ret = G->ops.compose_exp(G, lgnData(mem->q1), delta, lgnData(mem->q1));
  if (ret == 0 && G->ops.tangent_inverse_apply != NULL) {
    ret = G->ops.tangent_inverse_apply(G, mem->incr, delta, mem->work_nv);
    for (i = 0; i < nv && ret == 0; i++) mem->incr[i] += mem->work_nv[i];
  } else if (ret == 0) {
    ret = G->ops.tangent_dot_apply(G, mem->zero_nv, mem->incr, delta, mem->work_nv);
    for (i = 0; i < nv && ret == 0; i++) mem->incr[i] += delta[i] - mem->work_nv[i];
  }
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
  return LGN_SUCCESS;
}

static const sunrealtype *SigmaIncrement(LGNMem mem)
{
  return mem->incr;
}

static const LGNKinematicsOps sigma_ops = {
  "sigma", SUNTRUE, SUNFALSE, SUNFALSE,
  BindToIterate, SigmaPredict, SigmaIterate, SigmaMatrix, SigmaCorrect,
  SigmaIncrement};

/* =============================================================================
 * BDF (lgn_bdf.c): x = sigma the chart coordinate of q_{n+1} at q_n, its
 * BDF derivative xdot = c0 x + r_x, v = T(x) xdot, vdot = c0 v + r_v
 * ===========================================================================*/

static int BDFPredict(LGNMem mem, const LGNStepCoeffs *c, sunrealtype *acc,
                      sunbooleantype extrapolate)
{
  (void)mem;
  (void)c;
  (void)acc;
  (void)extrapolate;
  return LGN_SUCCESS; /* lgn_bdf.c predicts */
}

/* GGL: B(q1) at the iterate's time into mem->Bmat (the residual then
 * uses it: lgnNeedsConstraintJacobian), and v1 -= B^T mu. */
static int GGLVelocity(LGNMem mem, sunrealtype *v1)
{
  sunindextype i, nv = mem->nv;
  int ret;
  ret = lgnEvalConstraintJacobian(mem, mem->ggl_t1, mem->q1, mem->Bmat);
  if (ret != LGN_SUCCESS) return ret;
  lgnMatTvec(mem->Bmat, mem->ggl_mu, mem->work_nv, SUNFALSE);
  for (i = 0; i < nv; i++) v1[i] -= mem->work_nv[i];
  return LGN_SUCCESS;
}

/* x -> q1, v1, vdot1; under GGL the kinematic relation carries the
 * multiplier mu, T(x) xdot = v + B(q)^T mu, so v1 = T(x) xdot - B^T mu. */
static int BDFIterate(LGNMem mem, sunbooleantype with_tangent)
{
  LGNGroup G = mem->G;
  sunindextype i, nv = mem->nv;
  const sunrealtype c0 = mem->bdf_c0;
  sunrealtype *v1 = lgnData(mem->v1), *vdot1 = lgnData(mem->vdot1);
  int ret = Configuration(mem, with_tangent);
  if (ret != LGN_SUCCESS) return ret;
  for (i = 0; i < nv; i++) mem->sigma_dot[i] = c0 * mem->sigma[i] + mem->bdf_rx[i];
  ret = G->ops.tangent_apply(G, mem->sigma, mem->sigma_dot, v1);
  if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
  if (mem->constr_index == LGN_CONSTR_GGL && mem->m > 0) {
    ret = GGLVelocity(mem, v1);
    if (ret != LGN_SUCCESS) return ret;
  }
  for (i = 0; i < nv; i++) vdot1[i] = c0 * v1[i] + mem->bdf_rv[i];
  return LGN_SUCCESS;
}

/* dv/dx ~ c0 T(x) and dvdot/dx ~ c0^2 T(x) (the derivative of T itself
 * along xdot, O(h) relative, left out): cM M T + cC C T + cK K T with
 * cM = scale c0^2, cC = scale c0, cK = scale; B T, or at index 2 the row
 * (B v)/c0 with its block B T + (1/c0) D_q(B v) T. GGL has both rows and
 * the column of mu (lgn_matrix.c). */
static int BDFMatrix(LGNMem mem, const LGNStepCoeffs *c, LGNMatrixTerms *terms)
{
  StepTerms(mem, c, terms);
  terms->TM = terms->TC = terms->TK = terms->TB = mem->Tm;
  ConstraintVelocityTerm(mem, terms);
  terms->ggl   = mem->constr_index == LGN_CONSTR_GGL && mem->m > 0;
  terms->TP    = mem->Tm;
  terms->gsign = SUN_RCONST(-1.0); /* v = T(x) xdot - B(q1)^T mu */
  return LGN_SUCCESS;
}

static const LGNKinematicsOps bdf_ops = {
  "BDF", SUNFALSE, SUNFALSE, SUNFALSE,
  ExactBind, BDFPredict, BDFIterate, BDFMatrix, NULL, NewmarkIncrement};

const LGNKinematicsOps *lgnBDFOps(void) { return &bdf_ops; }

/* =============================================================================
 * The table of a variant
 * ===========================================================================*/

const LGNKinematicsOps *lgnKinematicsOps(int kinematics)
{
  switch (kinematics) {
  case LGN_KINEMATICS_SIMPLIFIED: return &simplified_ops;
  case LGN_KINEMATICS_EXACT:      return &exact_ops;
  case LGN_KINEMATICS_SIGMA:      return &sigma_ops;
  default:                        return NULL;
  }
}
