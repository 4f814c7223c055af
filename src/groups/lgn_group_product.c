/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Direct product G_1 x ... x G_n: coordinates concatenated, exp and log
 * factor by factor, T block diagonal.
 * The content is an array of factor pointers (referenced, not owned; the
 * same factor may appear many times) with the q and v offsets of each
 * factor, so a chain of many identical bodies costs one pointer and two
 * offsets per body and no op allocates.
 * ---------------------------------------------------------------------------*/

#include <stdlib.h>

#include "lgn_so3.h"
#include "lgn_group_impl.h"

typedef struct {
  int nf;             /* number of factors                  */
  LGNGroup *f;        /* factors (not owned)                */
  sunindextype *qoff; /* offset of factor k in q            */
  sunindextype *voff; /* offset of factor k in v            */
} ProductContent;

#define PC(G) ((ProductContent *)(G)->content)

static int ProdComposeExp(LGNGroup G, const sunrealtype *q,
                          const sunrealtype *w, sunrealtype *q_out)
{
  const ProductContent *c = PC(G);
  int k, flag;
  for (k = 0; k < c->nf; k++) {
    LGNGroup F = c->f[k];
    if (F->ops.compose_exp == NULL) return -1;
    flag = F->ops.compose_exp(F, q + c->qoff[k], w + c->voff[k],
                              q_out + c->qoff[k]);
    if (flag != 0) return flag;
  }
  return 0;
}

static int ProdComposeLog(LGNGroup G, const sunrealtype *q1,
                          const sunrealtype *q2, sunrealtype *w)
{
  const ProductContent *c = PC(G);
  int k, flag;
  for (k = 0; k < c->nf; k++) {
    LGNGroup F = c->f[k];
    const sunindextype o = c->qoff[k];
    if (F->ops.compose_log == NULL) return -1;
    flag = F->ops.compose_log(F, q1 + o, q2 + o, w + c->voff[k]);
    if (flag != 0) return flag;
  }
  return 0;
}

static int ProdTangentApply(LGNGroup G, const sunrealtype *w,
                            const sunrealtype *x, sunrealtype *y)
{
  const ProductContent *c = PC(G);
  int k, flag;
  for (k = 0; k < c->nf; k++) {
    LGNGroup F = c->f[k];
    const sunindextype o = c->voff[k];
    if (F->ops.tangent_apply == NULL) return -1;
    flag = F->ops.tangent_apply(F, w + o, x + o, y + o);
    if (flag != 0) return flag;
  }
  return 0;
}

static int ProdTangentInverseApply(LGNGroup G, const sunrealtype *w,
                                   const sunrealtype *x, sunrealtype *y)
{
  const ProductContent *c = PC(G);
  int k, flag;
  for (k = 0; k < c->nf; k++) {
    LGNGroup F = c->f[k];
    const sunindextype o = c->voff[k];
    if (F->ops.tangent_inverse_apply == NULL) return -1;
    flag = F->ops.tangent_inverse_apply(F, w + o, x + o, y + o);
    if (flag != 0) return flag;
  }
  return 0;
}

static int ProdTangentDotApply(LGNGroup G, const sunrealtype *w,
                               const sunrealtype *wdot, const sunrealtype *x,
                               sunrealtype *y)
{
  const ProductContent *c = PC(G);
  int k, flag;
  for (k = 0; k < c->nf; k++) {
    LGNGroup F = c->f[k];
    const sunindextype o = c->voff[k];
    if (F->ops.tangent_dot_apply == NULL) return -1;
    flag = F->ops.tangent_dot_apply(F, w + o, wdot + o, x + o, y + o);
    if (flag != 0) return flag;
  }
  return 0;
}

static int ProdTangentMatrix(LGNGroup G, const sunrealtype *w, sunrealtype *Tm,
                             sunindextype ld)
{
  /* block diagonal: each factor writes its diagonal block, the rest of its
   * columns is zeroed here */
  const ProductContent *c = PC(G);
  const sunindextype nv = G->nv;
  int k, flag;
  if (ld < nv) return -1;
  for (k = 0; k < c->nf; k++) {
    LGNGroup F = c->f[k];
    const sunindextype o = c->voff[k], e = o + F->nv;
    sunindextype i, j;
    if (F->ops.tangent_matrix == NULL) return -1;
    flag = F->ops.tangent_matrix(F, w + o, Tm + o + o * ld, ld);
    if (flag != 0) return flag;
    for (j = o; j < e; j++) {
      sunrealtype *col = Tm + j * ld;
      for (i = 0; i < o; i++) col[i] = 0;
      for (i = e; i < nv; i++) col[i] = 0;
    }
  }
  return 0;
}

static int ProdIdentity(LGNGroup G, sunrealtype *q)
{
  const ProductContent *c = PC(G);
  int k, flag;
  for (k = 0; k < c->nf; k++) {
    LGNGroup F = c->f[k];
    if (F->ops.identity == NULL) return -1;
    flag = F->ops.identity(F, q + c->qoff[k]);
    if (flag != 0) return flag;
  }
  return 0;
}

static int ProdNormalize(LGNGroup G, sunrealtype *q)
{
  /* factors without a normalize op are left as they are */
  const ProductContent *c = PC(G);
  int k, flag;
  for (k = 0; k < c->nf; k++) {
    LGNGroup F = c->f[k];
    if (F->ops.normalize == NULL) continue;
    flag = F->ops.normalize(F, q + c->qoff[k]);
    if (flag != 0) return flag;
  }
  return 0;
}

static void ProdFreeContent(LGNGroup G)
{
  ProductContent *c = PC(G);
  if (c == NULL) return;
  free(c->f);
  free(c->qoff);
  free(c->voff);
  free(c);
  G->content = NULL;
}

LGNGroup LGNGroup_Product(int nfactors, const LGNGroup *factors)
{
  LGNGroup G;
  ProductContent *c;
  sunindextype nq = 0, nv = 0;
  int k;

  if (nfactors < 1 || factors == NULL) return NULL;
  for (k = 0; k < nfactors; k++) {
    if (factors[k] == NULL || factors[k]->nq < 1 || factors[k]->nv < 1)
      return NULL;
    nq += factors[k]->nq;
    nv += factors[k]->nv;
  }

  G = LGNGroup_NewEmpty(nq, nv);
  if (G == NULL) return NULL;
  c = (ProductContent *)calloc(1, sizeof *c);
  if (c == NULL) {
    LGNGroup_Destroy(G);
    return NULL;
  }
  G->content          = c;
  G->ops.free_content = ProdFreeContent; /* frees a partial content too */
  c->nf   = nfactors;
  c->f    = (LGNGroup *)malloc((size_t)nfactors * sizeof *c->f);
  c->qoff = (sunindextype *)malloc((size_t)nfactors * sizeof *c->qoff);
  c->voff = (sunindextype *)malloc((size_t)nfactors * sizeof *c->voff);
  if (c->f == NULL || c->qoff == NULL || c->voff == NULL) {
    LGNGroup_Destroy(G);
    return NULL;
  }
  nq = nv = 0;
  for (k = 0; k < nfactors; k++) {
    c->f[k]    = factors[k];
    c->qoff[k] = nq;
    c->voff[k] = nv;
    nq += factors[k]->nq;
    nv += factors[k]->nv;
  }

  G->kind                      = LGN_GROUP_PRODUCT;
  G->ops.compose_exp           = ProdComposeExp;
  G->ops.tangent_apply         = ProdTangentApply;
  G->ops.tangent_inverse_apply = ProdTangentInverseApply;
  G->ops.tangent_dot_apply     = ProdTangentDotApply;
  G->ops.tangent_matrix        = ProdTangentMatrix;
  G->ops.identity              = ProdIdentity;
  G->ops.normalize             = ProdNormalize;
  G->ops.compose_log           = ProdComposeLog;
  return G;
}

/* The factors of a product (internal: used to split T into diagonal blocks
 * and by the joint helpers to locate bodies). Returns 0 when G is a
 * product, -1 otherwise. */
int lgnGroupProductFactors(LGNGroup G, int *nf, const LGNGroup **factors,
                           const sunindextype **qoff, const sunindextype **voff)
{
  const ProductContent *c;
  if (G == NULL || G->kind != LGN_GROUP_PRODUCT || G->content == NULL) return -1;
  c        = PC(G);
  *nf      = c->nf;
  *factors = c->f;
  *qoff    = c->qoff;
  *voff    = c->voff;
  return 0;
}

/* The bodies of G, which sits at offsets (qo, vo), numbered from k on
 * (lgnGroupRigidBodies). */
static int RigidBodies(LGNGroup G, sunindextype qo, sunindextype vo, sunindextype *qoff,
                       sunindextype *voff, sunbooleantype *se3, int k)
{
  int nf, i;
  const LGNGroup *f;
  const sunindextype *fq, *fv;
  if (lgnGroupProductFactors(G, &nf, &f, &fq, &fv) == 0) {
    for (i = 0; i < nf && k >= 0; i++)
      k = RigidBodies(f[i], qo + fq[i], vo + fv[i], qoff, voff, se3, k);
    return k;
  }
  if (G == NULL || (G->kind != LGN_GROUP_R3XSO3 && G->kind != LGN_GROUP_SE3)) return -1;
  if (qoff != NULL) {
    qoff[k] = qo;
    voff[k] = vo;
    se3[k]  = G->kind == LGN_GROUP_SE3;
  }
  return k + 1;
}

int lgnGroupRigidBodies(LGNGroup G, sunindextype *qoff, sunindextype *voff,
                        sunbooleantype *se3)
{
  return RigidBodies(G, 0, 0, qoff, voff, se3, 0);
}
