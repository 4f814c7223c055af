/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * Joints and force elements between bodies on different MPI ranks (built
 * with LGN_ENABLE_MPI): the halo of ghost bodies.
 *
 * A rank's model is its own bodies followed by ghost bodies: copies of the
 * bodies of other ranks that its joints and force elements touch. Its Lie
 * group, its vectors q and v (N_Vector_Parallel or MPIPlusX) and its
 * callbacks cover both; every joint and force element is declared on ONE
 * rank (any rank holding both of its bodies, as owned bodies or ghosts).
 * Lignum then
 *   - keeps the ghosts' entries of the state equal to their owners' (the
 *     owner's values are sent before the first step and after every step;
 *     the ghosts' entries of q0 and v0 are not read),
 *   - evaluates the callbacks on the rank's bodies and ghosts, and adds
 *     what a rank's joints and force elements put on a ghost body (its rows
 *     of B^T lambda, of the forces, of the iteration matrix) to the owner's
 *     rows: the global residual and matrix are the sums of the ranks',
 *   - solves the coupled Newton system across the ranks: a Krylov solver
 *     (the block preconditioner factors each rank's own bodies) or
 *     LGNLinSol_PETScSubdomain (MUMPS).
 * Ghost bodies carry no mass and no applied force of their own: with the
 * body helpers, mark them with LGNBodies_SetGhosts.
 * Norms, error tests and counts are over the owned entries only.
 * ---------------------------------------------------------------------------*/

#ifndef LIGNUM_HALO_H
#define LIGNUM_HALO_H

#include <mpi.h>

#include <lignum/lignum.h>
#include <lignum/lignum_config.h>
#include <lignum/lignum_export.h>

#if !defined(LGN_HAVE_MPI)
#error "This Lignum was built without MPI (LGN_ENABLE_MPI=OFF): ghost bodies are not available."
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** The ghost bodies of one rank and who owns them. */
typedef struct LGNHaloRec *LGNHalo;

/** Which entries LGNHalo_UpdateGhosts fills: per body nq reals (a
 *  configuration) or nv reals (a velocity-type vector). */
#define LGN_HALO_CONFIGURATION 0
#define LGN_HALO_VELOCITY      1

/**
 * Create the halo of this rank (collective over comm).
 * @param comm        the communicator of the run (that of the state
 *                    vectors); duplicated, so it may be freed after
 * @param G           this rank's configuration group: nowned bodies
 *                    (leaves, R^3 x SO(3) or SE(3)) followed by the ghosts;
 *                    referenced, must outlive the halo
 * @param nowned      the number of this rank's own bodies, 1 ... the number
 *                    of leaves of G
 * @param global_id   the global number (>= 0) of each leaf of G, owned ones
 *                    first; each global number is owned by exactly one rank,
 *                    and a rank lists a ghost at most once
 * @param ghost_owner the rank owning each ghost (leaves nowned ... ; NULL
 *                    when there are none)
 * @return the halo, or NULL on every rank (message on stderr naming the
 *         argument, from the rank that found the fault) if an argument is
 *         wrong, a ghost's global number is not owned by the rank named,
 *         the owner's body is of another kind (R^3 x SO(3) vs SE(3)), or
 *         memory ran out.
 */
LGN_EXPORT LGNHalo LGNHalo_Create(MPI_Comm comm, LGNGroup G, int nowned,
                                  const long int *global_id, const int *ghost_owner);

/** Free a halo (collective: it frees a communicator) and set *H to NULL;
 *  NULL is allowed. Free it after the integrators that use it (LGNFree). */
LGN_EXPORT void LGNHalo_Destroy(LGNHalo *H);

/** Number of this rank's own bodies (0 for H = NULL). */
LGN_EXPORT int LGNHalo_NumOwned(LGNHalo H);

/** Number of ghost bodies on this rank (0 for H = NULL). */
LGN_EXPORT int LGNHalo_NumGhosts(LGNHalo H);

/** The ranks this rank exchanges ghosts with (0 for H = NULL). */
LGN_EXPORT int LGNHalo_NumNeighbours(LGNHalo H);

/**
 * Fill the ghosts' entries of a rank-local array from their owners
 * (collective): for kind LGN_HALO_CONFIGURATION the array has G's nq
 * entries, for LGN_HALO_VELOCITY its nv.
 * @return LGN_SUCCESS, or LGN_ILL_INPUT (H or x NULL, another kind) on
 *         this rank (then no rank may go on with the call: check first).
 */
LGN_EXPORT int LGNHalo_UpdateGhosts(LGNHalo H, int kind, sunrealtype *x);

/**
 * Couple this integrator's ranks through the halo H (a local call; every
 * rank must make it, which LGNSolve checks). Call it after LGNSetGroup
 * with the halo's G, best before LGNInit: then the ghosts' entries of q0
 * and v0 are not read; after LGNInit they must hold a group element (a
 * quaternion that normalises). The vectors q0, v0 and those LGNSolve and
 * the getters return hold the owned bodies and the ghosts (their local
 * length is G's nq, nv); Lignum keeps the ghosts' entries equal to their
 * owners'. H is referenced, not copied: it must outlive every call on
 * this integrator (destroy it after LGNFree). A NULL halo removes it.
 * The linear solver must work across ranks: a Krylov solver
 * (LGNSetLinearSolver(mem, LS, NULL); with LGNSetBlockPreconditioner the
 * blocks cover the owned bodies), or LGNLinSol_PETScSubdomain with a
 * sparse matrix of LGNGetSubdomainSize rows and the indices of
 * LGNGetGlobalIndices. Dense and KLU solvers are refused by LGNSolve.
 * @return LGN_SUCCESS, LGN_MEM_NULL, or LGN_ILL_INPUT if no group is set,
 *         H was made for another group, or (after LGNInit) q0 and v0 were
 *         not MPI vectors.
 */
LGN_EXPORT int LGNSetHalo(void *lgn_mem, LGNHalo H);

/**
 * The size of this rank's subdomain iteration matrix: the velocities of
 * the owned bodies and the ghosts, and this rank's constraints (nv + m of
 * the rank's group and constraints).
 * @return LGN_SUCCESS, LGN_MEM_NULL, LGN_NO_MALLOC or LGN_ILL_INPUT (n NULL).
 */
LGN_EXPORT int LGNGetSubdomainSize(void *lgn_mem, sunindextype *n);

/**
 * The global index of each unknown of this rank's subdomain matrix
 * (collective): the unknowns of all ranks are numbered rank by rank, each
 * rank's owned velocities then its multipliers; a ghost's velocities get
 * the numbers their owner gives them. In the subdomain matrix's order
 * (owned velocities, ghosts' velocities, multipliers) the owned numbers
 * are thus in two consecutive runs, each owned number once, as
 * LGNLinSol_PETScSubdomain requires.
 * @param lgn_mem the integrator (LGNInit and LGNSetHalo called)
 * @param idx     room for LGNGetSubdomainSize entries
 * @return LGN_SUCCESS, LGN_MEM_NULL, LGN_NO_MALLOC, LGN_ILL_INPUT (idx NULL,
 *         or no halo set, on any rank: every rank returns the flag).
 */
LGN_EXPORT int LGNGetGlobalIndices(void *lgn_mem, sunindextype *idx);

#ifdef __cplusplus
}
#endif

#endif
