/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Private header: Lignum's own solves with a compact copy of the factors of
 * SUNLinSol_KLU (lgn_klu_solve.c, built with LGN_HAVE_KLU, for SUNDIALS with
 * 64-bit indices, whose KLU interface calls klu_l_*). Otherwise the
 * functions are stubs: no copy is ever made, so lgnLsSolve always calls
 * SUNLinSolSolve.
 * ---------------------------------------------------------------------------*/

#ifndef LGN_KLU_SOLVE_H
#define LGN_KLU_SOLVE_H

#include <stdint.h>

#include <lignum/lignum.h>

/* KLU's factorisation of the n x n matrix S it was given (S = A, or A^T for
 * a CSR matrix A, whose arrays SUNDIALS hands to KLU as those of a CSC
 * matrix), as klu_l_extract returns it:
 *
 *     L U + F = Rs^{-1} S(P, Q),  i.e. row k of the left side is row P[k]
 *                                  of S divided by Rs[k], column k is Q[k],
 *
 * with L unit lower and U upper triangular, both block diagonal over the
 * BTF blocks k = R[b] .. R[b+1]-1, and F the entries of the blocks above
 * the diagonal. Stored in compressed columns with 32-bit indices: L without
 * its unit diagonal, U without its diagonal (kept in Udiag). Each column
 * of L and U keeps KLU's order of entries, except that one of them may be
 * exchanged with the first (Lswap, Uswap): a refresh after klu_l_refactor,
 * which keeps the pattern, then takes only the values from KLU's columns. */
typedef struct LGNKluCopyRec {
  int32_t n, nblocks;
  sunbooleantype transpose; /* SUNDIALS solves with klu_l_tsolve (CSR A)   */
  sunbooleantype scaled;    /* Rs holds scale factors (else all ones)      */
  sunbooleantype complete;  /* a whole factorisation was copied            */
  int32_t *Lp, *Li;         /* strictly lower L: n + 1, lnz - n            */
  double *Lx;               /* room for lnz (extracted with the diagonal)  */
  int32_t *Up, *Ui;         /* strictly upper U: n + 1, unz - n            */
  double *Ux;               /* room for unz                                */
  int32_t *Fp, *Fi;         /* off-diagonal blocks: n + 1, nzoff           */
  double *Fx;
  int32_t *P, *Q, *R;       /* n, n, nblocks + 1                           */
  int32_t *Lswap, *Uswap;   /* n each: the place j in KLU's column k of
                               the copy's first entry, which has KLU's
                               first at j (or 0: none exchanged)           */
  /* By rows (klu_l_solve, rows = SUNTRUE): Lp and Up stay the column
   * pointers of KLU's columns (Lswap, Uswap all 0), but Li/Lx and Ui/Ux
   * hold L and U by rows, row i from Lrp[i] (Urp[i]) on, with the column
   * of each entry in Li (Ui): a row of L in increasing and a row of U in
   * decreasing column order, the order in which klu_l_solve's column
   * sweeps update that row, so rows i - 1, i - 2 (L) and i + 1, i + 2 (U)
   * come last. U's rows are stored divided by its diagonal, Ux holding
   * U(i, j) / U(i, i) (the solve's division then is not in the chain of
   * dependences from row to row). Lmap[Lp[k] + j] (Umap[Up[k] + j]) is the
   * place in Li/Lx (Ui/Ux) of KLU's entry j of its column k
   * (lgnKluCopyPlace). */
  sunbooleantype rows;
  int32_t *Lrp, *Urp;       /* n + 1 each                                  */
  int32_t *Lmap, *Umap;     /* lnz - n, unz - n                            */
  size_t cap_rn, cap_lmap, cap_umap;
  double *Udiag, *Rs, *X;   /* n each; X is the work vector of a solve (and
                               of a refactorisation, zero between rows)  */
  /* Lignum's refactorisation (lgnKluCopyRefactor), copies by rows only: row
   * i of S = Rs^{-1} A(P, Q) in its diagonal block is A's data at Apos[q]
   * in column Acol[q] (of S), Arp[i] <= q < Arp[i + 1]; F's entry f is A's
   * data at Fpos[f]. Built for A's pattern number `pattern` (-1: none). */
  int32_t *Arp, *Acol, *Apos, *Fpos;
  size_t cap_arp, cap_acol, cap_apos, cap_fpos;
  long int pattern;
  size_t cap_n, cap_l, cap_u, cap_f; /* allocated n and entries (lnz, ...) */
  int64_t *tmp;             /* 64-bit indices from klu_l_extract           */
  size_t cap_tmp;
  long int nfull, nvalues;  /* refreshes: whole copies, values only        */
  long int nrefactor;       /* Lignum's refactorisations                   */
} LGNKluCopy;

/* The place in Lx (lower != 0) or Ux of KLU's entry j (0 <= j < Llen[k],
 * or Ulen[k]: the order of KLU's packed column, which klu_l_extract keeps
 * after the diagonal) of column k, for a complete copy (by rows, Ux there
 * holds the entry divided by U's diagonal entry of its row). */
static inline int32_t lgnKluCopyPlace(const LGNKluCopy *c, int lower, int32_t k,
                                      int32_t j)
{
  const int32_t p = (lower ? c->Lp : c->Up)[k];
  const int32_t s = (lower ? c->Lswap : c->Uswap)[k];
  if (c->rows) return (lower ? c->Lmap : c->Umap)[p + j];
  return p + (j == 0 ? s : (j == s ? 0 : j));
}

/* Return values of lgnKluCopyRefresh and lgnKluCopyRefactor besides
 * LGN_SUCCESS and LGN_MEM_FAIL. */
#define LGN_KLU_NO_COPY 1 /* no factors, sizes beyond 32 bits, or unknown */
#define LGN_KLU_PIVOT   2 /* a refactorisation with a pivot too small      */

/* The versions whose unpublished layouts the copy reads, the only ones it
 * accepts (LGNSetOwnKLUSolves): KLU's Numeric and Symbolic objects and
 * its packed columns (klu_l_extract's input, GatherColumn), as in KLU 1.3
 * (SuiteSparse 5), and SUNLinSol_KLU's content (its solve function
 * klu_solver), as in SUNDIALS 6.4. */
#define LGN_KLU_COPY_KLU_MAJOR 1
#define LGN_KLU_COPY_KLU_MINOR 3
#define LGN_KLU_COPY_SUN_MAJOR 6
#define LGN_KLU_COPY_SUN_MINOR 4

/* 1 if KLU klu_major.klu_minor with SUNDIALS sun_major.sun_minor are the
 * versions above, else 0 with the reason in *why (a static string; also
 * "supported" on success; why may be NULL). Pure, in every build
 * (lgn_ls.c). */
int lgnKluCopySupported(int klu_major, int klu_minor, int sun_major,
                        int sun_minor, const char **why);

#if defined(LGN_HAVE_KLU) && defined(SUNDIALS_INT64_T)
#define LGN_KLU_COPY

int lgnKluCopyRefresh(LGNKluCopy **copy, SUNLinearSolver LS);
int lgnKluCopyRefactor(LGNKluCopy *c, SUNMatrix A, long int pattern, int scale);
void lgnKluCopySolve(LGNKluCopy *c, const sunrealtype *b, sunrealtype *x);
void lgnKluCopyFree(LGNKluCopy **copy);
void lgnKluCopySpace(const LGNKluCopy *c, long int *rw, long int *iw);

#else

static inline int lgnKluCopyRefresh(LGNKluCopy **copy, SUNLinearSolver LS)
{
  (void)copy;
  (void)LS;
  return LGN_KLU_NO_COPY;
}
static inline void lgnKluCopySolve(LGNKluCopy *c, const sunrealtype *b,
                                   sunrealtype *x)
{
  (void)c;
  (void)b;
  (void)x;
}
static inline int lgnKluCopyRefactor(LGNKluCopy *c, SUNMatrix A,
                                     long int pattern, int scale)
{
  (void)c;
  (void)A;
  (void)pattern;
  (void)scale;
  return LGN_KLU_NO_COPY;
}
static inline void lgnKluCopyFree(LGNKluCopy **copy) { (void)copy; }
static inline void lgnKluCopySpace(const LGNKluCopy *c, long int *rw,
                                   long int *iw)
{
  (void)c;
  (void)rw;
  (void)iw;
}

#endif

#endif
