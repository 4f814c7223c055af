/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The tangent operator T(sigma) of the step and the derivatives of the exact
 * kinematics, stored block by block. On a product group G_1 x ... x G_k, T is
 * block diagonal (doc/theory.md §1.1); the blocks are the factors of the
 * product, flattened (a product of products gives the leaves). Factors on
 * which T = I (R^n) are "identity blocks" and store nothing. So a chain of N
 * bodies keeps N 6x6 blocks, not an (6N)^2 matrix, and every routine here is
 * linear in N.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "groups/lgn_group_impl.h"
#include "lgn_impl.h"

/* Tm = T(sigma), block by block. */
int lgnTangentMatrices(LGNMem mem)
{
  int b, ret;
  for (b = 0; b < mem->nblk; b++) {
    LGNGroup F = mem->blk_group[b];
    sunindextype o = mem->blk_voff[b], size = mem->blk_voff[b + 1] - o;
    if (lgnBlockIsIdentity(mem, b)) continue;
    if (F->ops.tangent_matrix == NULL) return lgnCallbackFlag(mem, LGN_CB_GROUP, -1, "LGNSolve");
    ret = F->ops.tangent_matrix(F, mem->sigma + o, mem->Tm + mem->blk_toff[b], size);
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
  }
  return LGN_SUCCESS;
}

/* =============================================================================
 * The exact kinematics, block by block
 * ===========================================================================*/

/* The fused map of a built-in leaf (lgn_group_impl.h); 1: not one. */
static int LeafExactMap(LGNGroup F, const sunrealtype *q, const sunrealtype *w,
                        const sunrealtype *wd, const sunrealtype *wdd,
                        sunrealtype *q1, sunrealtype *v, sunrealtype *vdot,
                        sunrealtype *Tm)
{
  switch (F->kind) {
  case LGN_GROUP_SO3:    return lgnGroupSO3ExactMap(F, q, w, wd, wdd, q1, v, vdot, Tm);
  case LGN_GROUP_R3XSO3: return lgnGroupR3xSO3ExactMap(F, q, w, wd, wdd, q1, v, vdot, Tm);
  case LGN_GROUP_SE3:    return lgnGroupSE3ExactMap(F, q, w, wd, wdd, q1, v, vdot, Tm);
  default:               return 1;
  }
}

/* A leaf's exact kinematics by its public ops (a user-supplied group, or
 * a built-in one whose ops were replaced). */
static int OpsExactMap(LGNMem mem, LGNGroup F, sunindextype n,
                       const sunrealtype *q, const sunrealtype *w,
                       const sunrealtype *wd, const sunrealtype *wdd,
                       sunrealtype *q1, sunrealtype *v, sunrealtype *vdot,
                       sunrealtype *Tm)
{
  sunrealtype *t = mem->blk_work;
  sunindextype i;
  int ret = F->ops.compose_exp(F, q, w, q1);
  if (ret == 0 && Tm != NULL)
    ret = F->ops.tangent_matrix != NULL ? F->ops.tangent_matrix(F, w, Tm, n) : -1;
  if (ret == 0) ret = F->ops.tangent_apply(F, w, wd, v);
  if (ret == 0) ret = F->ops.tangent_apply(F, w, wdd, vdot);
  if (ret == 0) ret = F->ops.tangent_dot_apply(F, w, wd, wd, t);
  for (i = 0; i < n && ret == 0; i++) vdot[i] += t[i];
  return ret;
}

/* q1 = q_n o exp(sigma), v1 = T(sigma) sigma_dot, vdot1 = T(sigma)
 * sigma_ddot + Tdot(sigma, sigma_dot) sigma_dot and, with with_tangent,
 * Tm = T(sigma), leaf by leaf: a built-in leaf in one fused evaluation (one
 * sine and cosine for exp, T and Tdot), bit for bit what its ops give; R^n
 * leaves are q + sigma and copies; other leaves through their ops. */
int lgnExactKinematicsMap(LGNMem mem, sunbooleantype with_tangent)
{
  const sunrealtype *q = lgnData(mem->q);
  sunrealtype *q1 = lgnData(mem->q1), *v1 = lgnData(mem->v1);
  sunrealtype *vdot1 = lgnData(mem->vdot1);
  int b, ret;
  for (b = 0; b < mem->nblk; b++) {
    LGNGroup F = mem->blk_group[b];
    const sunindextype o = mem->blk_voff[b], n = mem->blk_voff[b + 1] - o;
    const sunindextype qo = mem->blk_qoff[b];
    const sunrealtype *w = mem->sigma + o, *wd = mem->sigma_dot + o;
    const sunrealtype *wdd = mem->sigma_ddot + o;
    sunrealtype *Tm = with_tangent ? mem->Tm + mem->blk_toff[b] : NULL;
    sunindextype i;
    if (lgnBlockIsIdentity(mem, b)) { /* R^n: T = I, Tdot = 0 */
      for (i = 0; i < n; i++) {
        q1[qo + i]    = q[qo + i] + w[i];
        v1[o + i]     = wd[i];
        vdot1[o + i]  = wdd[i];
      }
      continue;
    }
    ret = LeafExactMap(F, q + qo, w, wd, wdd, q1 + qo, v1 + o, vdot1 + o, Tm);
    if (ret == 1)
      ret = OpsExactMap(mem, F, n, q + qo, w, wd, wdd, q1 + qo, v1 + o,
                        vdot1 + o, Tm);
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
  }
  return LGN_SUCCESS;
}

/* Derivatives of the exact kinematics with respect to the correction delta
 * (sigma += delta, sigma_dot += gamma' delta, sigma_ddot += beta' delta):
 *   dv/ddelta    = gamma' T + P,                  P e_j = DT(sigma)[e_j] sigma_dot
 *   dvdot/ddelta = beta' T + gamma' (P + Tdot(sigma, sigma_dot)) + Q
 *   Q e_j = DT(sigma)[e_j] sigma_ddot + D_sigma[Tdot(sigma, sigma_dot) sigma_dot] e_j
 * with DT(sigma)[w] = Tdot(sigma, w): the exact Jacobian of the map
 * (sigma, sigma_dot, sigma_ddot) -> (v, vdot). The gamma' terms are
 * O(h |v|) relative to beta' T, Q is O(h^2 |v|^2). With all of them Newton
 * converges quadratically and needs no more iterations than with the
 * simplified kinematics. Stored normalised: Tv = (dv/ddelta)/gamma',
 * Ta = (dvdot/ddelta)/beta', so the assembly forms cM M Ta + cC C Tv +
 * cK K T. All three are block diagonal like T (each factor's kinematics
 * involve its own sigma only).
 *
 * The built-in leaves give them in closed form (lgnSO3_ExactBlocks: DT, D^2T
 * and, for SE(3), D^3T of the SO(3) tangent operator); other leaves by their
 * ops: P, Tdot and DT[e_j] sigma_ddot exactly (tangent_dot_apply is linear
 * in its second and third arguments), Q's second part, a second derivative
 * of T, by a forward difference (ExactBlockDQ). */
static int ExactBlockDQ(LGNMem mem, int b, sunrealtype gamma_p, sunrealtype beta_p)
{
  LGNGroup F = mem->blk_group[b];
  const sunindextype o = mem->blk_voff[b], n = mem->blk_voff[b + 1] - o;
  const sunrealtype ratio = gamma_p / beta_p, srur = sqrt(SUN_UNIT_ROUNDOFF);
  sunrealtype *sigma = mem->sigma + o, *sd = mem->sigma_dot + o, *sdd = mem->sigma_ddot + o;
  sunrealtype *Tm = mem->Tm + mem->blk_toff[b], *Tv = mem->Tv + mem->blk_toff[b];
  sunrealtype *Ta = mem->Ta + mem->blk_toff[b];
  sunrealtype *e = mem->blk_work, *col = e + n, *td0 = col + n, eps, sj;
  sunindextype i, j;
  int ret;

  if (F->ops.tangent_dot_apply == NULL) return -1;
  /* Tdot(sigma, sigma_dot) sigma_dot at the current sigma */
  ret = F->ops.tangent_dot_apply(F, sigma, sd, sd, td0);
  for (i = 0; i < n; i++) e[i] = SUN_RCONST(0.0);
  for (j = 0; j < n && ret == 0; j++) {
    e[j] = SUN_RCONST(1.0);
    /* P e_j */
    ret = F->ops.tangent_dot_apply(F, sigma, e, sd, col);
    for (i = 0; i < n && ret == 0; i++) {
      Tv[i + j * n] = Tm[i + j * n] + col[i] / gamma_p;
      Ta[i + j * n] = Tm[i + j * n] + ratio * col[i];
    }
    /* Tdot(sigma, sigma_dot) e_j */
    if (ret == 0) ret = F->ops.tangent_dot_apply(F, sigma, sd, e, col);
    for (i = 0; i < n && ret == 0; i++) Ta[i + j * n] += ratio * col[i];
    /* Q e_j: DT(sigma)[e_j] sigma_ddot ... */
    if (ret == 0) ret = F->ops.tangent_dot_apply(F, sigma, e, sdd, col);
    for (i = 0; i < n && ret == 0; i++) Ta[i + j * n] += col[i] / beta_p;
    /* ... + forward difference of Tdot(., sigma_dot) sigma_dot along e_j */
    e[j] = SUN_RCONST(0.0);
    if (ret == 0) {
      sj       = sigma[j];
      eps      = srur * SUNMAX(SUN_RCONST(1.0), fabs(sj));
      sigma[j] = sj + eps;
      ret      = F->ops.tangent_dot_apply(F, sigma, sd, sd, col);
      sigma[j] = sj;
      for (i = 0; i < n && ret == 0; i++)
        Ta[i + j * n] += (col[i] - td0[i]) / eps / beta_p;
    }
  }
  return ret;
}

/* The closed forms of a built-in leaf; 1: not one. */
static int ExactBlockAnalytic(LGNMem mem, int b, sunrealtype gamma_p,
                              sunrealtype beta_p)
{
  LGNGroup F = mem->blk_group[b];
  const sunindextype o = mem->blk_voff[b], to = mem->blk_toff[b];
  const sunrealtype *w = mem->sigma + o, *wd = mem->sigma_dot + o;
  const sunrealtype *wdd = mem->sigma_ddot + o, *Tm = mem->Tm + to;
  sunrealtype *Tv = mem->Tv + to, *Ta = mem->Ta + to;
  switch (F->kind) {
  case LGN_GROUP_SO3:
    return lgnGroupSO3ExactDerivatives(F, w, wd, wdd, gamma_p, beta_p, Tm, Tv, Ta);
  case LGN_GROUP_R3XSO3:
    return lgnGroupR3xSO3ExactDerivatives(F, w, wd, wdd, gamma_p, beta_p, Tm, Tv, Ta);
  case LGN_GROUP_SE3:
    return lgnGroupSE3ExactDerivatives(F, w, wd, wdd, gamma_p, beta_p, Tm, Tv, Ta);
  default:
    return 1;
  }
}

int lgnExactKinematicsDerivatives(LGNMem mem, sunrealtype gamma_p,
                                  sunrealtype beta_p)
{
  int b, ret;
  for (b = 0; b < mem->nblk; b++) {
    if (lgnBlockIsIdentity(mem, b)) continue; /* Tv = Ta = I */
    ret = ExactBlockAnalytic(mem, b, gamma_p, beta_p);
    if (ret == 1) ret = ExactBlockDQ(mem, b, gamma_p, beta_p);
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "LGNSolve");
  }
  return LGN_SUCCESS;
}

/* Y = X T for a dense nrow x nv block X (leading dimension ldx) and a block
 * diagonal T in packed storage (NULL: T = I), into Y (leading dimension ldy).
 * Column j of Y combines only the columns of X that column j of T can
 * have nonzero (lgnTangentColumnRange: one in an R^3 x SO(3) leaf's
 * translation part, three in its rotation part). One and three columns
 * (R^3 x SO(3), SO(3)) are straight-line code: loops with trip counts of 3
 * or 6 cost more in loop overhead than in arithmetic. */
void lgnDenseTimesTangent(LGNMem mem, const sunrealtype *X, sunindextype ldx,
                          sunindextype nrow, const sunrealtype *T,
                          sunrealtype *Y, sunindextype ldy)
{
  sunindextype i, j, k, k0, k1, o, n;
  int b;
  for (b = 0; b < mem->nblk; b++) {
    /* T == NULL stands for T = I: no offset into it */
    const sunrealtype *Tb = T != NULL ? T + mem->blk_toff[b] : NULL;
    const sunbooleantype ident = T == NULL || lgnBlockIsIdentity(mem, b);
    o = mem->blk_voff[b];
    n = mem->blk_voff[b + 1] - o;
    for (j = o; j < o + n; j++) {
      sunrealtype *restrict y = Y + j * ldy;
      const sunrealtype *restrict tj;
      if (ident) {
        for (i = 0; i < nrow; i++) y[i] = X[i + j * ldx];
        continue;
      }
      tj = Tb + (j - o) * n - o; /* tj[k] = T(k, j) */
      lgnTangentColumnRange(mem, j, &k0, &k1);
      if (k1 - k0 == 1) {
        const sunrealtype *restrict x0 = X + k0 * ldx, t0 = tj[k0];
        for (i = 0; i < nrow; i++) y[i] = x0[i] * t0;
      } else if (k1 - k0 == 3) { /* a rotation: straight-line code */
        const sunrealtype *restrict x0 = X + k0 * ldx, *restrict x1 = x0 + ldx;
        const sunrealtype *restrict x2 = x1 + ldx;
        const sunrealtype t0 = tj[k0], t1 = tj[k0 + 1], t2 = tj[k0 + 2];
        for (i = 0; i < nrow; i++) y[i] = x0[i] * t0 + x1[i] * t1 + x2[i] * t2;
      } else {
        for (i = 0; i < nrow; i++) {
          const sunrealtype *restrict x = X + i;
          sunrealtype s = SUN_RCONST(0.0);
          for (k = k0; k < k1; k++) s += x[k * ldx] * tj[k];
          y[i] = s;
        }
      }
    }
  }
}
