/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Ghost bodies of a run across ranks (LGNSetHalo, lignum_halo.h): joints
 * and force elements between bodies of different ranks.
 *
 * A rank's local arrays hold its owned bodies, then its ghosts (the halo's
 * order), and the stepper works on them as on any model: the callbacks see
 * both, the kinematics update both. What makes the ranks one model:
 *   - the global residual of a body is the sum of the ranks' rows for it
 *     (each joint and force element lives on one rank, and a ghost carries
 *     no mass or force of its own), and so is the global iteration matrix:
 *     a right-hand side is FOLDED (ghost rows added to the owners') before
 *     a solve, whose unknowns are the owned velocities and the multipliers;
 *   - the solution's ghost entries are then EXPANDED from their owners, so
 *     that every rank applies the owner's correction to its copy of a body;
 *   - after every step the ghosts' state is refreshed from the owners (the
 *     copies were updated with the same corrections, and are now exactly
 *     the owners' values).
 * Norms and error tests count the owned entries only (nv_own).
 * ---------------------------------------------------------------------------*/

#include <stdlib.h>
#include <string.h>

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "lgn_halo.h"
#include "lgn_impl.h"

int lgnGhostsOwnedBodies(const LGNMem mem)
{
  int b = 0;
  while (b < mem->nblk && mem->blk_voff[b] < mem->nv_own) b++;
  return b;
}

#if defined(LGN_HAVE_MPI)

void lgnGhostsFold(LGNMem mem, const sunrealtype *ext, sunrealtype *owned)
{
  const sunindextype nvo = mem->nv_own;
  memcpy(owned, ext, (size_t)nvo * sizeof(sunrealtype));
  lgnHaloReverse(mem->halo, ext, owned);
  memcpy(owned + nvo, ext + mem->nv, (size_t)mem->m * sizeof(sunrealtype));
}

void lgnGhostsRestrict(LGNMem mem, const sunrealtype *ext, sunrealtype *owned)
{
  const sunindextype nvo = mem->nv_own;
  memcpy(owned, ext, (size_t)nvo * sizeof(sunrealtype));
  memcpy(owned + nvo, ext + mem->nv, (size_t)mem->m * sizeof(sunrealtype));
}

void lgnGhostsExpand(LGNMem mem, const sunrealtype *owned, sunrealtype *ext)
{
  const sunindextype nvo = mem->nv_own;
  memcpy(ext, owned, (size_t)nvo * sizeof(sunrealtype));
  lgnHaloForward(mem->halo, LGN_HALO_VELOCITY, ext);
  memcpy(ext + mem->nv, owned + nvo, (size_t)mem->m * sizeof(sunrealtype));
}

void lgnGhostsRefreshState(LGNMem mem)
{
  if (mem->halo == NULL) return;
  lgnHaloForward(mem->halo, LGN_HALO_CONFIGURATION, lgnData(mem->q));
  lgnHaloForward(mem->halo, LGN_HALO_VELOCITY, lgnData(mem->v));
  lgnHaloForward(mem->halo, LGN_HALO_VELOCITY, lgnData(mem->vdot));
  lgnHaloForward(mem->halo, LGN_HALO_VELOCITY, lgnData(mem->a));
}

void lgnGhostsOwnedLengths(const LGNMem mem, sunindextype *nq, sunindextype *nv)
{
  *nq = mem->G->nq;
  *nv = mem->G->nv;
  if (mem->halo != NULL) lgnHaloOwnedLengths(mem->halo, nq, nv);
}

void lgnGhostsClear(const LGNMem mem, sunrealtype *q, sunrealtype *v)
{
  if (mem->halo != NULL) lgnHaloClearGhosts(mem->halo, q, v);
}

int lgnGhostsCheckMass(LGNMem mem, SUNMatrix M)
{
  const sunindextype nvo = mem->nv_own;
  sunindextype i, j, p, bad = -1;
  if (mem->halo == NULL) return LGN_SUCCESS;
  if (lgnMatIsSparse(M)) { /* CSC or CSR: an entry with an index past the owned ones */
    const sunindextype *ptr = SUNSparseMatrix_IndexPointers(M);
    const sunindextype *ind = SUNSparseMatrix_IndexValues(M);
    const sunrealtype *val  = SUNSparseMatrix_Data(M);
    for (j = 0; j < SUNSparseMatrix_NP(M) && bad < 0; j++)
      for (p = ptr[j]; p < ptr[j + 1]; p++)
        if (val[p] != SUN_RCONST(0.0) && (j >= nvo || ind[p] >= nvo)) {
          bad = j >= nvo ? j : ind[p];
          break;
        }
  } else {
    for (j = 0; j < SM_COLUMNS_D(M) && bad < 0; j++)
      for (i = 0; i < SM_ROWS_D(M); i++)
        if ((i >= nvo || j >= nvo) && SM_ELEMENT_D(M, i, j) != SUN_RCONST(0.0)) {
          bad = j >= nvo ? j : i;
          break;
        }
  }
  if (bad < 0) return LGN_SUCCESS;
  LGN_ERROR(mem, LGN_ILL_INPUT,
            "The mass matrix has entries of ghost body %lld (leaf %lld of the group, "
            "velocity %lld): a ghost's mass belongs to its owner's rank, and the ranks' "
            "matrices are summed (mark ghosts with LGNBodies_SetGhosts).",
            (long long)(mem->blk_of[bad] - lgnGhostsOwnedBodies(mem)), (long long)mem->blk_of[bad],
            (long long)bad);
  return LGN_ILL_INPUT;
}

int lgnGhostsCheck(LGNMem mem)
{
  if (mem->halo == NULL || lgnHaloGroup(mem->halo) == mem->G) return LGN_SUCCESS;
  LGN_ERROR(mem, LGN_ILL_INPUT,
            "The halo (LGNSetHalo) was made for another group than the one of "
            "LGNSetGroup: make it for the rank's group of owned and ghost bodies.");
  return LGN_ILL_INPUT;
}

int LGNSetHalo(void *lgn_mem, LGNHalo H)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (mem->G == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, MSG_NO_GROUP);
    return LGN_ILL_INPUT;
  }
  if (H != NULL && lgnHaloGroup(H) != mem->G) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "H was made for another group than the integrator's (LGNSetGroup): "
              "make the halo with the rank's group of owned and ghost bodies.");
    return LGN_ILL_INPUT;
  }
  if (H != NULL && mem->malloc_done && mem->par == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT,
              "H needs a run across ranks: q0 and v0 of LGNInit must be "
              "N_Vector_Parallel or MPIPlusX vectors.");
    return LGN_ILL_INPUT;
  }
  if (H == mem->halo) return LGN_SUCCESS;
  mem->halo = H;
  lgnInvalidate(mem, LGN_CHANGE_SIZES | LGN_CHANGE_LINSOL);
  return LGN_SUCCESS;
}

int LGNGetSubdomainSize(void *lgn_mem, sunindextype *n)
{
  LGNMem mem;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  if (n == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, "n = NULL illegal.");
    return LGN_ILL_INPUT;
  }
  *n = mem->nv + mem->m;
  return LGN_SUCCESS;
}

int LGNGetGlobalIndices(void *lgn_mem, sunindextype *idx)
{
  LGNMem mem;
  sunindextype nq_own, nv_own, i;
  long long mine, first = 0;
  sunrealtype *gv;
  int flag = lgnAccessMem(lgn_mem, __func__, &mem);
  if (flag != LGN_SUCCESS) return flag;
  if (!mem->malloc_done) {
    LGN_ERROR(mem, LGN_NO_MALLOC, MSG_NO_MALLOC);
    return LGN_NO_MALLOC;
  }
  if (idx == NULL || mem->halo == NULL) {
    LGN_ERROR(mem, LGN_ILL_INPUT, idx == NULL ? "idx = NULL illegal."
                                              : "No halo: call LGNSetHalo first.");
    flag = LGN_ILL_INPUT;
  }
  /* agreed before the collective numbering (a rank's bad argument must not
   * leave the others waiting in it) */
  flag = lgnAgree(mem, flag);
  if (flag != LGN_SUCCESS) return flag;
  lgnHaloOwnedLengths(mem->halo, &nq_own, &nv_own);
  mine = (long long)(nv_own + mem->m);
  {
    MPI_Comm comm = lgnHaloComm(mem->halo);
    int hrank = 0;
    MPI_Comm_rank(comm, &hrank);
    MPI_Exscan(&mine, &first, 1, MPI_LONG_LONG, MPI_SUM, comm);
    if (hrank == 0) first = 0; /* MPI_Exscan leaves rank 0's undefined */
  }
  /* the owners' numbers of the ghosts' velocities: sent as reals (exact
   * below 2^53) through the velocity exchange */
  gv = (sunrealtype *)malloc((size_t)SUNMAX(mem->nv, 1) * sizeof(sunrealtype));
  flag = lgnAgree(mem, gv == NULL ? LGN_MEM_FAIL : LGN_SUCCESS);
  if (flag != LGN_SUCCESS) {
    free(gv);
    if (gv == NULL) LGN_ERROR(mem, LGN_MEM_FAIL, MSG_MEM_FAIL);
    return flag;
  }
  for (i = 0; i < mem->nv; i++) gv[i] = (sunrealtype)(first + (long long)i);
  lgnHaloForward(mem->halo, LGN_HALO_VELOCITY, gv);
  for (i = 0; i < mem->nv; i++) idx[i] = (sunindextype)gv[i];
  for (i = 0; i < mem->m; i++) idx[mem->nv + i] = (sunindextype)(first + nv_own + i);
  free(gv);
  return LGN_SUCCESS;
}

#else /* without MPI: never a halo */

void lgnGhostsFold(LGNMem mem, const sunrealtype *ext, sunrealtype *owned)
{
  (void)mem;
  (void)ext;
  (void)owned;
}
void lgnGhostsRestrict(LGNMem mem, const sunrealtype *ext, sunrealtype *owned)
{
  (void)mem;
  (void)ext;
  (void)owned;
}
void lgnGhostsExpand(LGNMem mem, const sunrealtype *owned, sunrealtype *ext)
{
  (void)mem;
  (void)owned;
  (void)ext;
}
void lgnGhostsRefreshState(LGNMem mem) { (void)mem; }
int lgnGhostsCheck(LGNMem mem)
{
  (void)mem;
  return LGN_SUCCESS;
}
int lgnGhostsCheckMass(LGNMem mem, SUNMatrix M)
{
  (void)mem;
  (void)M;
  return LGN_SUCCESS;
}
void lgnGhostsOwnedLengths(const LGNMem mem, sunindextype *nq, sunindextype *nv)
{
  *nq = mem->G->nq;
  *nv = mem->G->nv;
}
void lgnGhostsClear(const LGNMem mem, sunrealtype *q, sunrealtype *v)
{
  (void)mem;
  (void)q;
  (void)v;
}

#endif
