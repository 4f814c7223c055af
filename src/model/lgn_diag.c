/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Diagnostics of a singular iteration matrix (or saddle-point matrix of the
 * initial values): which constraints are redundant and which unknown has a
 * zero pivot, in words a multibody engineer can act on.
 *
 *   - Redundant constraints: the rank of B(q) by a QR factorisation with
 *     column pivoting of B^T (LAPACK dgeqp3): B^T P = Q R with |R_11| >=
 *     |R_22| >= ...; the constraints pivoted last, beyond the numerical rank
 *     (|R_kk| <= 1e-10 |R_11|), depend on those before them. Done when
 *     B has at most LGN_DIAG_MAX_ENTRIES entries as a dense matrix (a large
 *     model gets the zero pivot only).
 *   - The zero pivot: the column the factorisation stopped at (dense LU:
 *     SUNLinSolSetup's return value; KLU: common.singular_col), named as the
 *     velocity of a body of the group (leaf, translation or rotation
 *     direction) or as a constraint's multiplier.
 * ---------------------------------------------------------------------------*/

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_impl.h"
#if defined(LGN_HAVE_KLU)
#include <sunlinsol/sunlinsol_klu.h>
#endif

/* The redundant constraints into mem->diag_red (ascending, the user's row
 * numbers), their number into mem->diag_nred, and B's rank into *rank; -1
 * if not computed (lgn_redundancy.c's QR with column pivoting of B^T). */
static int RedundantConstraints(LGNMem mem, sunindextype *rank)
{
  const sunindextype m = mem->m;
  sunindextype *rows, i, nred = 0;
  *rank = -1;
  if (m == 0 || mem->Bmat == NULL) return -1;
  rows = (sunindextype *)malloc((size_t)m * sizeof(sunindextype));
  if (rows == NULL) return -1;
  if (lgnRankRevealingRows(mem->Bmat, m, mem->nv, SUN_RCONST(0.0), rank, rows) == 0) {
    /* the rows beyond the rank, ascending; the kept rows are ascending in
     * the user's numbering, so the map keeps the order */
    for (i = *rank; i < m; i++) mem->diag_red[nred++] = lgnUserRow(mem, rows[i]);
    mem->diag_nred = nred;
  }
  free(rows);
  return *rank >= 0 ? 0 : -1;
}

/* The column of the zero pivot, or -1. */
static sunindextype ZeroPivot(LGNMem mem, int ret)
{
#if defined(LGN_HAVE_KLU)
  if (SUNLinSolGetID(mem->LS) == SUNLINEARSOLVER_KLU) {
    klu_l_common *c = SUNLinSol_KLUGetCommon(mem->LS);
    return c != NULL && c->status == KLU_SINGULAR ? (sunindextype)c->singular_col : -1;
  }
#endif
  {
    /* SUNDIALS' dense LU: the last flag is 1 + the column of the zero pivot */
    const sunindextype lf = (sunindextype)SUNLinSolLastFlag(mem->LS);
    (void)ret;
    /* (SUNLS_LUFACT_FAIL itself names no column: a solver that cannot
     * tell, such as LGNLinSol_PETSc without null pivots, has last flag 0) */
    return lf > 0 ? lf - 1
                  : (ret > 0 && ret != SUNLS_LUFACT_FAIL && ret <= mem->nv + mem->nalg ? ret - 1
                                                                                   : -1);
  }
}

/* Unknown k in words: the velocity of a leaf of the group, or a multiplier. */
static void NameUnknown(LGNMem mem, sunindextype k, char *buf, size_t len)
{
  static const char *rigid[6] = {"translation x", "translation y", "translation z",
                                 "rotation about body x", "rotation about body y",
                                 "rotation about body z"};
  static const char *rot[3] = {"rotation about body x", "rotation about body y",
                               "rotation about body z"};
  if (k >= mem->nv + mem->m) { /* GGL's mu */
    snprintf(buf, len, "the kinematic multiplier (GGL) of constraint %lld",
             (long long)lgnUserRow(mem, k - mem->nv - mem->m));
  } else if (k >= mem->nv) {
    snprintf(buf, len, "the multiplier of constraint %lld",
             (long long)lgnUserRow(mem, k - mem->nv));
  } else {
    const int b = (int)mem->blk_of[k];
    const sunindextype d = k - mem->blk_voff[b];
    const LGNGroupKind kind = mem->blk_group[b]->kind;
    if (kind == LGN_GROUP_R3XSO3 || kind == LGN_GROUP_SE3)
      snprintf(buf, len, "velocity %lld: body %d, %s", (long long)k, b, rigid[d]);
    else if (kind == LGN_GROUP_SO3)
      snprintf(buf, len, "velocity %lld: body %d, %s", (long long)k, b, rot[d]);
    else
      snprintf(buf, len, "velocity %lld: factor %d of the group, component %lld",
               (long long)k, b, (long long)d);
  }
}

/* After a failed setup with return value ret: the diagnosis into buf (a
 * sentence, or "" if there is nothing to add), and into mem for the getters
 * (LGNGetRedundantConstraints, LGNGetZeroPivot). */
void lgnDiagnoseSingular(LGNMem mem, int ret, char *buf, size_t len)
{
  sunindextype rank, i, pivot;
  size_t used = 0;
  char what[96];

  buf[0] = '\0';
  mem->diag_nred  = 0;
  mem->diag_pivot = pivot = ZeroPivot(mem, ret);
  if (RedundantConstraints(mem, &rank) == 0 && mem->diag_nred > 0) {
    used += (size_t)snprintf(buf + used, len - used,
                             " Redundant constraints (B has rank %lld of %lld): ",
                             (long long)rank, (long long)mem->m);
    /* (with rows left out at the start, mem->m counts the kept ones) */
    for (i = 0; i < mem->diag_nred && used < len; i++)
      used += (size_t)snprintf(buf + used, len - used, "%s%lld", i > 0 ? ", " : "",
                               (long long)mem->diag_red[i]);
    if (used < len)
      used += (size_t)snprintf(buf + used, len - used,
                               " (LGNGetRedundantConstraints; LGNJoints_DescribeConstraint "
                               "names their joints).");
  }
  if (pivot >= 0 && used < len && mem->halo != NULL) {
    /* ghost bodies: the solver's column is a global unknown of the ranks'
     * sum (LGNGetGlobalIndices), not one of this rank's */
    used += (size_t)snprintf(buf + used, len - used,
                             " Zero pivot at global unknown %lld of the ranks' summed matrix "
                             "(LGNGetGlobalIndices numbers them).",
                             (long long)pivot);
  } else if (pivot >= 0 && used < len) {
    NameUnknown(mem, pivot, what, sizeof what);
    used += (size_t)snprintf(buf + used, len - used, " Zero pivot at unknown %lld, %s%s.",
                             (long long)pivot, what,
                             pivot < mem->nv && mem->diag_nred == 0
                                 ? " (check the mass matrix and the forces' Jacobian there)"
                                 : "");
  }
}
