/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The block-Jacobi preconditioner of the saddle-point iteration matrix
 *
 *   A = [[ S, B^T ], [ B', 0 ]]   (S = cM M TM + cC C TC + cK K TK)
 *
 * for the Krylov solvers (lgn_krylov.c). The velocity unknowns are split
 * into contiguous ranges (blocks of bodies); a constraint row belongs to the
 * block of its first nonzero velocity column (for a joint between two
 * blocks: the block of its lower body; a row with no velocity column in
 * any block, a joint between two ghost bodies, is in no block and the
 * preconditioner leaves it as it is). Block b is A restricted to the rows
 * and columns of its unknowns, itself a saddle-point matrix, factored with
 * KLU; the entries coupling two blocks (the off-block columns of the joints
 * at a boundary, and of S where a model couples bodies) are left to the
 * Krylov iteration. One block is A itself: the preconditioned matrix is then
 * the identity to roundoff. This is the per-rank preconditioner of the
 * distributed design (one block per rank, or several), here on one process.
 *
 * The blocks' patterns and the map from A's entries to theirs are built
 * when A's pattern changes (a number given by the caller); KLU analyses
 * each block once per pattern, refactors with its pivots at each setup, and
 * factors anew when its rcond estimate falls below eps^(2/3) (as
 * SUNLinSol_KLU does).
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <klu.h>
#include <sundials/sundials_math.h>

#include "lgn_blockprec.h"

typedef struct {
  SuiteSparse_long n;      /* unknowns of the block                        */
  SuiteSparse_long *Ap;    /* n + 1                                        */
  SuiteSparse_long *Ai;    /* Ap[n]                                        */
  double *Ax;              /* Ap[n]                                        */
  sunindextype *src;       /* Ap[n]: the position of each entry in A       */
  sunindextype *glob;      /* n: the global index of each local unknown    */
  double *work;            /* n: the right-hand side, gathered             */
  klu_l_symbolic *sym;
  klu_l_numeric *num;
} Block;

struct LGNBlockPrecRec {
  sunindextype n, nv;
  int nblocks;
  sunindextype *voff;      /* nblocks + 1                                  */
  Block *blk;              /* nblocks                                      */
  long int pattern;        /* A's pattern the blocks were built for        */
  sunbooleantype built;    /* the blocks' patterns exist                   */
  sunbooleantype factored; /* the last setup succeeded                     */
  klu_l_common common;
};

static void FreeBlock(Block *b, klu_l_common *common)
{
  if (b->num != NULL) klu_l_free_numeric(&b->num, common);
  if (b->sym != NULL) klu_l_free_symbolic(&b->sym, common);
  free(b->Ap);
  free(b->Ai);
  free(b->Ax);
  free(b->src);
  free(b->glob);
  free(b->work);
  memset(b, 0, sizeof *b);
}

LGNBlockPrec lgnBlockPrecCreate(sunindextype n, sunindextype nv, int nblocks,
                                const sunindextype *voff)
{
  LGNBlockPrec bp;
  int b;
  if (nblocks < 1 || voff == NULL || n < nv || voff[0] != 0 || voff[nblocks] > nv)
    return NULL;
  for (b = 0; b < nblocks; b++)
    if (voff[b + 1] <= voff[b]) return NULL;
  bp = (LGNBlockPrec)calloc(1, sizeof *bp);
  if (bp == NULL) return NULL;
  bp->voff = (sunindextype *)malloc((size_t)(nblocks + 1) * sizeof *bp->voff);
  bp->blk  = (Block *)calloc((size_t)nblocks, sizeof *bp->blk);
  if (bp->voff == NULL || bp->blk == NULL) {
    free(bp->voff);
    free(bp->blk);
    free(bp);
    return NULL;
  }
  memcpy(bp->voff, voff, (size_t)(nblocks + 1) * sizeof *bp->voff);
  bp->n       = n;
  bp->nv      = nv;
  bp->nblocks = nblocks;
  bp->pattern = -1;
  klu_l_defaults(&bp->common);
  return bp;
}

void lgnBlockPrecFree(LGNBlockPrec *bp)
{
  int b;
  if (bp == NULL || *bp == NULL) return;
  for (b = 0; b < (*bp)->nblocks; b++) FreeBlock(&(*bp)->blk[b], &(*bp)->common);
  free((*bp)->blk);
  free((*bp)->voff);
  free(*bp);
  *bp = NULL;
}

/* The block of each unknown and its index there; the blocks' patterns, the
 * map of their entries into A, and KLU's analyses. */
static int Build(LGNBlockPrec bp, const sunindextype *colptr,
                 const sunindextype *rowind)
{
  const sunindextype n = bp->n, nv = bp->nv;
  int *owner = (int *)malloc((size_t)SUNMAX(n, 1) * sizeof(int));
  sunindextype *loc = (sunindextype *)malloc((size_t)SUNMAX(n, 1) * sizeof(sunindextype));
  sunindextype i, j, p;
  int b, flag = 0;
  if (owner == NULL || loc == NULL) {
    free(owner);
    free(loc);
    return -1;
  }
  for (b = 0; b < bp->nblocks; b++) FreeBlock(&bp->blk[b], &bp->common);
  /* velocities past the last range (ghost bodies): in no block (-1) */
  for (i = 0; i < n; i++) owner[i] = -1;
  for (b = 0; b < bp->nblocks; b++)
    for (i = bp->voff[b]; i < bp->voff[b + 1]; i++) owner[i] = b;
  /* a constraint row: the block of its first velocity column in a block
   * (columns in increasing order: the first one seen); one without any (a
   * joint between two ghost bodies) in no block: an empty row there would
   * make the block singular, and the iteration carries it */
  for (j = 0; j < bp->voff[bp->nblocks]; j++)
    for (p = colptr[j]; p < colptr[j + 1]; p++)
      if (rowind[p] >= nv && owner[rowind[p]] < 0) owner[rowind[p]] = owner[j];
  /* local numbering: in increasing global order within each block */
  for (i = 0; i < n; i++) loc[i] = owner[i] >= 0 ? bp->blk[owner[i]].n++ : -1;
  for (b = 0; b < bp->nblocks && flag == 0; b++) {
    Block *k = &bp->blk[b];
    k->glob = (sunindextype *)malloc((size_t)k->n * sizeof(sunindextype));
    k->work = (double *)malloc((size_t)k->n * sizeof(double));
    k->Ap   = (SuiteSparse_long *)calloc((size_t)k->n + 1, sizeof(SuiteSparse_long));
    if (k->glob == NULL || k->work == NULL || k->Ap == NULL) flag = -1;
  }
  if (flag == 0) {
    for (i = 0; i < n; i++)
      if (owner[i] >= 0) bp->blk[owner[i]].glob[loc[i]] = i;
    /* count, then place: the entries of column j within j's block */
    for (j = 0; j < n; j++)
      for (p = colptr[j]; p < colptr[j + 1]; p++)
        if (owner[j] >= 0 && owner[rowind[p]] == owner[j]) bp->blk[owner[j]].Ap[loc[j] + 1]++;
    for (b = 0; b < bp->nblocks && flag == 0; b++) {
      Block *k = &bp->blk[b];
      SuiteSparse_long c;
      for (c = 0; c < k->n; c++) k->Ap[c + 1] += k->Ap[c];
      k->Ai  = (SuiteSparse_long *)malloc((size_t)SUNMAX(k->Ap[k->n], 1) * sizeof(SuiteSparse_long));
      k->Ax  = (double *)malloc((size_t)SUNMAX(k->Ap[k->n], 1) * sizeof(double));
      k->src = (sunindextype *)malloc((size_t)SUNMAX(k->Ap[k->n], 1) * sizeof(sunindextype));
      if (k->Ai == NULL || k->Ax == NULL || k->src == NULL) flag = -1;
    }
  }
  if (flag == 0) {
    for (j = 0; j < n; j++) {
      Block *k;
      SuiteSparse_long q;
      if (owner[j] < 0) continue;
      k = &bp->blk[owner[j]];
      q = k->Ap[loc[j]];
      for (p = colptr[j]; p < colptr[j + 1]; p++)
        if (owner[rowind[p]] == owner[j]) {
          k->Ai[q]    = (SuiteSparse_long)loc[rowind[p]];
          k->src[q++] = p;
        }
    }
    for (b = 0; b < bp->nblocks && flag == 0; b++) {
      Block *k = &bp->blk[b];
      k->sym   = klu_l_analyze(k->n, k->Ap, k->Ai, &bp->common);
      if (k->sym == NULL) flag = -1;
    }
  }
  free(owner);
  free(loc);
  if (flag != 0)
    for (b = 0; b < bp->nblocks; b++) FreeBlock(&bp->blk[b], &bp->common);
  bp->built = flag == 0 ? SUNTRUE : SUNFALSE;
  return flag;
}

int lgnBlockPrecSetup(LGNBlockPrec bp, const sunindextype *colptr,
                      const sunindextype *rowind, const sunrealtype *val,
                      long int pattern)
{
  const double rcond_min = pow(SUN_UNIT_ROUNDOFF, 2.0 / 3.0);
  SuiteSparse_long q;
  int b;
  bp->factored = SUNFALSE;
  if (!bp->built || pattern != bp->pattern) {
    if (Build(bp, colptr, rowind) != 0) return -1;
    bp->pattern = pattern;
  }
  for (b = 0; b < bp->nblocks; b++) {
    Block *k = &bp->blk[b];
    int ok = 0;
    for (q = 0; q < k->Ap[k->n]; q++) k->Ax[q] = val[k->src[q]];
    if (k->num != NULL) { /* KLU's pivots of the last factorisation */
      ok = klu_l_refactor(k->Ap, k->Ai, k->Ax, k->sym, k->num, &bp->common) &&
           klu_l_rcond(k->sym, k->num, &bp->common) &&
           bp->common.rcond >= rcond_min;
      if (!ok) klu_l_free_numeric(&k->num, &bp->common);
    }
    if (k->num == NULL) {
      k->num = klu_l_factor(k->Ap, k->Ai, k->Ax, k->sym, &bp->common);
      if (k->num == NULL || bp->common.status == KLU_SINGULAR) {
        if (k->num != NULL) klu_l_free_numeric(&k->num, &bp->common);
        return bp->common.status == KLU_SINGULAR ? b + 1 : -1;
      }
    }
  }
  bp->factored = SUNTRUE;
  return 0;
}

int lgnBlockPrecSolve(LGNBlockPrec bp, const sunrealtype *r, sunrealtype *z)
{
  int b;
  sunindextype i;
  if (!bp->factored) return -1;
  if (z != r) /* the unknowns in no block: z = r there */
    memcpy(z, r, (size_t)bp->n * sizeof(sunrealtype));
  for (b = 0; b < bp->nblocks; b++) {
    Block *k = &bp->blk[b];
    for (i = 0; i < k->n; i++) k->work[i] = r[k->glob[i]];
    if (!klu_l_solve(k->sym, k->num, k->n, 1, k->work, &bp->common)) return -1;
    for (i = 0; i < k->n; i++) z[k->glob[i]] = k->work[i];
  }
  return 0;
}

int lgnBlockPrecNumBlocks(const LGNBlockPrec bp)
{
  return bp != NULL ? bp->nblocks : 0;
}

void lgnBlockPrecSpace(const LGNBlockPrec bp, long int *rw, long int *iw)
{
  int b;
  if (bp == NULL) return;
  *iw += bp->nblocks + 1;
  for (b = 0; b < bp->nblocks; b++) {
    const Block *k = &bp->blk[b];
    const long int nnz = k->Ap != NULL ? (long int)k->Ap[k->n] : 0L;
    *rw += nnz + (long int)k->n;                      /* Ax, work        */
    *iw += 2 * nnz + 2 * (long int)k->n + 1;          /* Ai, src, Ap, glob */
  }
  /* KLU's symbolic and numeric objects, as it counts them (bytes) */
  *rw += (long int)(bp->common.memusage / sizeof(double));
}

sunbooleantype lgnBlockPrecFits(const LGNBlockPrec bp, sunindextype n,
                                sunindextype nv, int nblocks)
{
  return bp != NULL && bp->n == n && bp->nv == nv && bp->nblocks == nblocks;
}
