/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header of the sparse path: compressed-column views of the model
 * matrices, the fixed pattern of the iteration matrix with the maps of where
 * the model matrices' entries go in it, and the column colouring of the
 * difference-quotient tangents.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_SPARSE_H
#define LGN_SPARSE_H

#include <lignum/lignum.h>

/* A compressed sparse column matrix. Either a view of a CSC SUNMatrix (cap =
 * 0, arrays not owned) or Lignum-owned storage (cap = allocated entries). */
typedef struct {
  sunindextype nrows, ncols;
  sunindextype *colptr; /* ncols + 1 */
  sunindextype *rowind; /* colptr[ncols]        */
  sunrealtype *val;
  sunindextype cap;     /* allocated entries (0: a view) */
  sunindextype capcol;  /* allocated columns             */
} LGNCsc;

/* Columns grouped so that no two columns of a group share a row: one
 * displaced evaluation per group gives all its columns (Curtis-Powell-Reid). */
typedef struct {
  sunindextype ncolors;
  sunindextype *ptr;  /* ncolors + 1 */
  sunindextype *cols; /* nv          */
} LGNColoring;

/* The index arrays of a model matrix as its callback last wrote them, to
 * tell whether the next evaluation has the same pattern (the callbacks write
 * the whole structure every time), and for a CSR matrix where each of its
 * entries goes in the CSC copy, so that a copy of the same pattern is a
 * gather of the values instead of a transposition. */
typedef struct {
  sunbooleantype seen;      /* ptr and ind hold a pattern                  */
  sunindextype np, nnz;     /* pointers - 1 (columns or rows) and entries  */
  sunindextype *ptr, *ind;  /* np + 1 and nnz                              */
  sunindextype *perm;       /* CSR: entry p is entry perm[p] of the copy   */
  sunindextype capp, cap;   /* allocated pointers and entries              */
} LGNPatternMemo;

/* Where the entries of a model matrix X go in A (lgn_assemble_sparse.c):
 * entry p of column k is added at A.colptr[j] + off[p] in every column j
 * of A that combines column k of X -- those columns hold the same rows --
 * or, for the B^T block, at off[p] (p an entry of B, column nv + its row).
 * Built for a pattern of A and of X, and valid while neither changes. */
typedef struct {
  const LGNCsc *src;        /* the matrix mapped                          */
  sunindextype *off;        /* one per entry of src                       */
  sunindextype cap;         /* allocated entries of off                   */
  sunbooleantype valid;
} LGNScatterMap;

/* The maps of A's terms (B's also serves D_q(B v), which has its pattern). */
enum { LGN_MAP_M = 0, LGN_MAP_C, LGN_MAP_K, LGN_MAP_B, LGN_MAP_BT, LGN_NMAPS };

struct LGNSparseWorkRec {
  /* the iteration matrix in CSC (pattern fixed until a miss or a reset;
   * values only for a CSR A, before the permutation: a CSC A is filled in
   * place) */
  LGNCsc A;
  sunbooleantype have_pattern;
  sunbooleantype analysed;   /* KLU has a symbolic analysis of this pattern */
  sunindextype *csr_perm;    /* CSR A: position of CSC entry k in A's data  */
  long int npattern;         /* patterns built (symbolic analyses)          */
  LGNScatterMap map[LGN_NMAPS];
  long int nmapped;          /* maps built (for the tests)                  */

  /* CSC views or transposed copies of the model matrices, and the patterns
   * their callbacks wrote last. Bt is B^T, transposed when B's pattern
   * changes: its values are those of that evaluation (unused). */
  LGNCsc M, B, Bt, K, C;
  LGNPatternMemo Mseen, Bseen, Kseen, Cseen;
  /* difference-quotient tangents: symmetric patterns with their colourings */
  LGNCsc Kdq, Cdq;
  LGNColoring Kcol, Ccol;
  sunbooleantype have_dq_patterns;
  sunrealtype *Bvq;          /* D_q(B v) on the pattern of B (CSC view)     */
  sunindextype Bvq_cap;

  /* scratch */
  sunindextype *mark;        /* n: column stamp of a row                    */
  sunindextype *list;        /* n: rows of the column being built           */
};

/* A column of a pattern under construction: its distinct rows, found with
 * a mark array stamped with the column index (marks reset to -1 after use). */
typedef struct {
  sunindextype col, cnt;
  sunindextype *mark, *list;
} LGNColumnBuilder;

static inline void lgnColumnAddRow(LGNColumnBuilder *cb, sunindextype r)
{
  if (cb->mark[r] != cb->col) {
    cb->mark[r]           = cb->col;
    cb->list[cb->cnt++] = r;
  }
}

/* lgn_sparse.c */
int lgnCscAppendColumn(LGNCsc *P, LGNColumnBuilder *cb);
void lgnCscFree(LGNCsc *A);
int lgnCscView(SUNMatrix S, LGNCsc *view);
int lgnCscViewSeen(SUNMatrix S, LGNCsc *view, LGNPatternMemo *seen,
                   sunbooleantype *changed);
void lgnPatternMemoFree(LGNPatternMemo *seen);
int lgnCscTranspose(const LGNCsc *A, LGNCsc *At);
int lgnCscReserve(LGNCsc *A, sunindextype nrows, sunindextype ncols,
                  sunindextype nnz);
void lgnColoringFree(LGNColoring *c);
int lgnColorColumns(const LGNCsc *sym, sunindextype *mark, LGNColoring *c);

#endif
