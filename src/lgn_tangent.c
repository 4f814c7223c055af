/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The tangent operator T(sigma) of the step and the derivatives of the exact
 * kinematics, stored block by block. On a product group G_1 x ... x G_k, T is
 * block diagonal (spec numerics.md §4); the blocks are the factors of the
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

/* Count (pass 1, out == NULL) or record the leaves of G at offsets (qo, vo). */
static int FlattenGroup(LGNGroup G, sunindextype qo, sunindextype vo,
                        LGNMem out, int nblk)
{
  int nf, k;
  const LGNGroup *f;
  const sunindextype *qoff, *voff;
  if (lgnGroupProductFactors(G, &nf, &f, &qoff, &voff) == 0) {
    for (k = 0; k < nf; k++)
      nblk = FlattenGroup(f[k], qo + qoff[k], vo + voff[k], out, nblk);
    return nblk;
  }
  if (out != NULL) {
    out->blk_group[nblk] = G;
    out->blk_qoff[nblk]  = qo;
    out->blk_voff[nblk]  = vo;
  }
  return nblk + 1;
}

void lgnBlocksFree(LGNMem mem)
{
  free(mem->blk_voff);
  free(mem->blk_qoff);
  free(mem->blk_toff);
  free(mem->blk_of);
  free(mem->blk_group);
  mem->blk_voff = mem->blk_qoff = mem->blk_toff = mem->blk_of = NULL;
  mem->blk_group = NULL;
  mem->nblk = 0;
  mem->blk_max = mem->tlen = 0;
}

int lgnBlocksBuild(LGNMem mem)
{
  int b, nblk = FlattenGroup(mem->G, 0, 0, NULL, 0);
  sunindextype i, size;

  lgnBlocksFree(mem);
  mem->blk_voff  = (sunindextype *)malloc((size_t)(nblk + 1) * sizeof(sunindextype));
  mem->blk_qoff  = (sunindextype *)malloc((size_t)(nblk + 1) * sizeof(sunindextype));
  mem->blk_toff  = (sunindextype *)malloc((size_t)(nblk + 1) * sizeof(sunindextype));
  mem->blk_of    = (sunindextype *)malloc((size_t)mem->nv * sizeof(sunindextype));
  mem->blk_group = (LGNGroup *)malloc((size_t)nblk * sizeof(LGNGroup));
  if (mem->blk_voff == NULL || mem->blk_qoff == NULL || mem->blk_toff == NULL ||
      mem->blk_of == NULL || mem->blk_group == NULL) {
    lgnBlocksFree(mem);
    return LGN_MEM_FAIL;
  }
  mem->nblk = FlattenGroup(mem->G, 0, 0, mem, 0);
  mem->blk_voff[nblk] = mem->nv;
  mem->blk_qoff[nblk] = mem->nq;
  mem->blk_toff[0]    = 0;
  for (b = 0; b < nblk; b++) {
    size = mem->blk_voff[b + 1] - mem->blk_voff[b];
    mem->blk_max = SUNMAX(mem->blk_max, size);
    mem->blk_toff[b + 1] = mem->blk_toff[b] + (lgnBlockIsIdentity(mem, b) ? 0 : size * size);
    for (i = mem->blk_voff[b]; i < mem->blk_voff[b + 1]; i++) mem->blk_of[i] = b;
  }
  mem->tlen = mem->blk_toff[nblk];
  return LGN_SUCCESS;
}

/* Tm = T(sigma), block by block. */
int lgnTangentMatrices(LGNMem mem)
{
  int b, ret;
  for (b = 0; b < mem->nblk; b++) {
    LGNGroup F = mem->blk_group[b];
    sunindextype o = mem->blk_voff[b], size = mem->blk_voff[b + 1] - o;
    if (lgnBlockIsIdentity(mem, b)) continue;
    if (F->ops.tangent_matrix == NULL) return lgnCallbackFlag(mem, LGN_CB_GROUP, -1, "lgnStep");
    ret = F->ops.tangent_matrix(F, mem->sigma + o, mem->Tm + mem->blk_toff[b], size);
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "lgnStep");
  }
  return LGN_SUCCESS;
}

/* Derivatives of the exact kinematics with respect to the correction delta
 * (sigma += delta, sigma_dot += gamma' delta, sigma_ddot += beta' delta):
 *   dv/ddelta    = gamma' T + P,                  P e_j = DT(sigma)[e_j] sigma_dot
 *   dvdot/ddelta = beta' T + gamma' (P + Tdot(sigma, sigma_dot)) + Q
 *   Q e_j = DT(sigma)[e_j] sigma_ddot + D_sigma[Tdot(sigma, sigma_dot) sigma_dot] e_j
 * with DT(sigma)[w] = Tdot(sigma, w). The gamma' terms are O(h |v|) relative
 * to beta' T, Q is O(h^2 |v|^2); Q's second part (a second derivative of T)
 * is a forward difference. With all of them Newton converges quadratically
 * and needs no more iterations than with the simplified kinematics.
 * Stored normalised: Tv = (dv/ddelta)/gamma', Ta = (dvdot/ddelta)/beta', so
 * the assembly forms cM M Ta + cC C Tv + cK K T. All three are block
 * diagonal like T (each factor's kinematics involve its own sigma only). */
static int ExactBlock(LGNMem mem, int b, sunrealtype gamma_p, sunrealtype beta_p)
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

int lgnExactKinematicsDerivatives(LGNMem mem, sunrealtype gamma_p,
                                  sunrealtype beta_p)
{
  int b, ret;
  for (b = 0; b < mem->nblk; b++) {
    if (lgnBlockIsIdentity(mem, b)) continue; /* Tv = Ta = I */
    ret = ExactBlock(mem, b, gamma_p, beta_p);
    if (ret != 0) return lgnCallbackFlag(mem, LGN_CB_GROUP, ret, "lgnStep");
  }
  return LGN_SUCCESS;
}

/* Y = X T for a dense nrow x nv block X (leading dimension ldx) and a block
 * diagonal T in packed storage (NULL: T = I), into Y (leading dimension ldy). */
void lgnDenseTimesTangent(LGNMem mem, const sunrealtype *X, sunindextype ldx,
                          sunindextype nrow, const sunrealtype *T,
                          sunrealtype *Y, sunindextype ldy)
{
  sunindextype i, j, k, o, n;
  int b;
  sunrealtype tkj;
  for (b = 0; b < mem->nblk; b++) {
    /* T == NULL stands for T = I: no offset into it */
    const sunrealtype *Tb = T != NULL ? T + mem->blk_toff[b] : NULL;
    o = mem->blk_voff[b];
    n = mem->blk_voff[b + 1] - o;
    for (j = o; j < o + n; j++) {
      sunrealtype *y = Y + j * ldy;
      if (T == NULL || lgnBlockIsIdentity(mem, b)) {
        for (i = 0; i < nrow; i++) y[i] = X[i + j * ldx];
        continue;
      }
      for (i = 0; i < nrow; i++) y[i] = SUN_RCONST(0.0);
      for (k = 0; k < n; k++) {
        tkj = Tb[k + (j - o) * n];
        if (tkj == SUN_RCONST(0.0)) continue;
        for (i = 0; i < nrow; i++) y[i] += X[i + (o + k) * ldx] * tkj;
      }
    }
  }
}
