/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header of lgn_blockprec.c: the block-Jacobi preconditioner of the
 * saddle-point iteration matrix (a pure helper: it sees a CSC matrix and a
 * partition of its velocity unknowns, never the integrator's record).
 * ---------------------------------------------------------------------------*/

#ifndef LGN_BLOCKPREC_H
#define LGN_BLOCKPREC_H

#include <lignum/lignum.h>

typedef struct LGNBlockPrecRec *LGNBlockPrec;

#if defined(LGN_HAVE_KLU)

/* A preconditioner for n x n matrices whose first nv unknowns are the
 * velocities, split into nblocks contiguous ranges voff[b] <= i < voff[b+1]
 * (voff[0] = 0, increasing, voff[nblocks] <= nv: velocities past it, the
 * ghost bodies of a run across ranks, belong to no block and are left
 * out); the other n - nv unknowns (constraint rows) are given to blocks at
 * the first setup (a row with no velocity column in any block to none). NULL when memory is refused. */
LGNBlockPrec lgnBlockPrecCreate(sunindextype n, sunindextype nv, int nblocks,
                                const sunindextype *voff);
void lgnBlockPrecFree(LGNBlockPrec *bp);

/* Factor the blocks of the CSC matrix (colptr, rowind, val), n x n: block b
 * is A restricted to the rows and columns of its unknowns, the velocities
 * of its range and the constraint rows whose first nonzero among the
 * velocity columns lies in that range. pattern: a number that changes
 * when A's pattern does (then the blocks and KLU's analyses are rebuilt;
 * otherwise KLU refactors, and factors anew when its rcond estimate falls
 * below eps^(2/3)). Returns 0, > 0 when a block is singular (1 + the
 * block), < 0 when memory was refused or KLU failed otherwise. */
int lgnBlockPrecSetup(LGNBlockPrec bp, const sunindextype *colptr,
                      const sunindextype *rowind, const sunrealtype *val,
                      long int pattern);

/* z = P^{-1} r (z may be r): the blocks' solves, the coupling dropped; z =
 * r on the unknowns in no block. Returns 0, or -1 before a successful
 * setup. */
int lgnBlockPrecSolve(LGNBlockPrec bp, const sunrealtype *r, sunrealtype *z);

/* Number of blocks, and the reals and integers held (the blocks' patterns
 * and values, the maps; KLU's factors as KLU counts them, in reals). */
int lgnBlockPrecNumBlocks(const LGNBlockPrec bp);
void lgnBlockPrecSpace(const LGNBlockPrec bp, long int *rw, long int *iw);
/* Was bp made for n unknowns, nv of them velocities, in nblocks blocks? */
sunbooleantype lgnBlockPrecFits(const LGNBlockPrec bp, sunindextype n,
                                sunindextype nv, int nblocks);
#else
/* Without KLU there is no block preconditioner (LGNSetBlockPreconditioner
 * refuses): the record's pointer stays NULL. */
static inline void lgnBlockPrecFree(LGNBlockPrec *bp) { (void)bp; }
static inline void lgnBlockPrecSpace(const LGNBlockPrec bp, long int *rw,
                                     long int *iw)
{
  (void)bp;
  (void)rw;
  (void)iw;
}
#endif

#endif
