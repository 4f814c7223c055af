! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! flignum_vtk_mod: hand-written ISO_C_BINDING interface to the trajectory
! writer of include/lignum/lignum_vtk.h (VTK XML PolyData files per output
! and a .pvd collection for ParaView).
!
! Names are the C names, types as in flignum_mod:
!   LGNVtk, LGNGroup, N_Vector -> type(c_ptr), value
!   LGNVtk *w (LGNVtk_Destroy) -> type(c_ptr), by reference (set to c_null_ptr)
!   int (body numbers, flags)  -> integer(c_int), 0-based bodies as in C
!   const sunrealtype r[3]     -> real(c_double) :: origin(3)
!   const sunrealtype R[9]     -> type(c_ptr) rot (c_loc of 9 reals, row-major;
!                                 c_null_ptr: the body's axes)
!   const char *basename       -> FLGNVtk_Create takes a Fortran string
! ---------------------------------------------------------------------------
module flignum_vtk_mod
  use, intrinsic :: iso_c_binding
  implicit none

  interface
    !> A writer for the bodies of G (basename NUL-terminated: use FLGNVtk_Create).
    type(c_ptr) function LGNVtk_Create(G, basename) bind(c, name="LGNVtk_Create")
      import :: c_ptr, c_char
      type(c_ptr), value :: G
      character(kind=c_char), intent(in) :: basename(*)
    end function LGNVtk_Create

    !> Free the writer; w becomes c_null_ptr.
    subroutine LGNVtk_Destroy(w) bind(c, name="LGNVtk_Destroy")
      import :: c_ptr
      type(c_ptr) :: w
    end subroutine LGNVtk_Destroy

    !> Where the writer's messages go.
    integer(c_int) function LGNVtk_SetErrHandlerFn(w, ehfun, eh_data) &
        bind(c, name="LGNVtk_SetErrHandlerFn")
      import :: c_int, c_ptr, c_funptr
      type(c_ptr), value :: w
      type(c_funptr), value :: ehfun
      type(c_ptr), value :: eh_data
    end function LGNVtk_SetErrHandlerFn

    !> The number of bodies drawn.
    integer(c_int) function LGNVtk_GetNumBodies(w, nbodies) bind(c, name="LGNVtk_GetNumBodies")
      import :: c_int, c_ptr
      type(c_ptr), value :: w
      integer(c_int), intent(out) :: nbodies
    end function LGNVtk_GetNumBodies

    !> Body k (0-based) is a box of edges lx, ly, lz.
    integer(c_int) function LGNVtk_SetBox(w, k, lx, ly, lz) bind(c, name="LGNVtk_SetBox")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: w
      integer(c_int), value :: k
      real(c_double), value :: lx, ly, lz
    end function LGNVtk_SetBox

    !> Body k is a cylinder along its z axis.
    integer(c_int) function LGNVtk_SetCylinder(w, k, radius, length) &
        bind(c, name="LGNVtk_SetCylinder")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: w
      integer(c_int), value :: k
      real(c_double), value :: radius, length
    end function LGNVtk_SetCylinder

    !> Body k is a sphere.
    integer(c_int) function LGNVtk_SetSphere(w, k, radius) bind(c, name="LGNVtk_SetSphere")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: w
      integer(c_int), value :: k
      real(c_double), value :: radius
    end function LGNVtk_SetSphere

    !> Body k is a triangle mesh: points(3, npoints), triangles(3, ntriangles)
    !! with 0-based point numbers.
    integer(c_int) function LGNVtk_SetMesh(w, k, npoints, points, ntriangles, triangles) &
        bind(c, name="LGNVtk_SetMesh")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: w
      integer(c_int), value :: k, npoints, ntriangles
      real(c_double), intent(in) :: points(*)
      integer(c_int), intent(in) :: triangles(*)
    end function LGNVtk_SetMesh

    !> A frame at origin with axes the columns of rot (C's R: row-major 3x3,
    !! c_loc of 9 reals; c_null_ptr: the body's axes) on body k (-1: the
    !! ground), axes of length size.
    integer(c_int) function LGNVtk_AddFrame(w, k, origin, rot, size) bind(c, name="LGNVtk_AddFrame")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: w
      integer(c_int), value :: k
      real(c_double), intent(in) :: origin(3)
      type(c_ptr), value :: rot
      real(c_double), value :: size
    end function LGNVtk_AddFrame

    !> Write the output at time t (q: an N_Vector of the group's nq).
    integer(c_int) function LGNVtk_Write(w, t, q) bind(c, name="LGNVtk_Write")
      import :: c_int, c_ptr, c_double
      type(c_ptr), value :: w
      real(c_double), value :: t
      type(c_ptr), value :: q
    end function LGNVtk_Write
  end interface

contains

  !> LGNVtk_Create with a Fortran string (trailing blanks ignored).
  !! @param G        the group of the integrator
  !! @param basename path and prefix of the files
  !! @return         the writer, c_null_ptr on failure
  function FLGNVtk_Create(G, basename) result(w)
    type(c_ptr), intent(in) :: G
    character(len=*), intent(in) :: basename
    type(c_ptr) :: w

    w = LGNVtk_Create(G, trim(basename)//c_null_char)
  end function FLGNVtk_Create

end module flignum_vtk_mod
