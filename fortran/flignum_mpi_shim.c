/* -----------------------------------------------------------------------------
 * Lignum: Lie group Newmark-type integrators for constrained multibody systems.
 * SPDX-License-Identifier: BSD-3-Clause
 * -----------------------------------------------------------------------------
 * The C side of flignum_halo_mod (library lignum_fortran, built with MPI):
 * LGNHalo_Create with a Fortran communicator handle. A C MPI_Comm has no
 * portable Fortran type (a pointer in Open MPI, an int in MPICH); the
 * Fortran handle (MPI_Fint) has, and MPI_Comm_f2c converts it.
 * ---------------------------------------------------------------------------*/

#include <mpi.h>

#include <lignum/lignum_halo.h>

LGNHalo FLGNHalo_Create(MPI_Fint fcomm, LGNGroup G, int nowned, const long int *global_id,
                        const int *ghost_owner);

_Static_assert(sizeof(MPI_Fint) == sizeof(int), "the Fortran modules bind MPI_Fint as integer(c_int)");

/* LGNHalo_Create on the communicator of the Fortran handle fcomm. */
LGNHalo FLGNHalo_Create(MPI_Fint fcomm, LGNGroup G, int nowned, const long int *global_id,
                        const int *ghost_owner)
{
  return LGNHalo_Create(MPI_Comm_f2c(fcomm), G, nowned, global_id, ghost_owner);
}
