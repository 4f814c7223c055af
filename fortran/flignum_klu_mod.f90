! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! flignum_klu_mod: Fortran helpers for the sparse path (built only when
! Lignum has KLU, LGN_ENABLE_KLU). With a SUNSparseMatrix and SUNLinSol_KLU
! attached, Lignum hands M, B and (if given) K_t, C_t to the callbacks as
! empty sparse matrices of A's format (CSC or CSR): the callback writes the
! whole structure. These helpers give the three arrays of a SUNSparseMatrix
! as Fortran pointers, without copying:
!
!   FSUNSparseMatrix_Data(A)          val(1:NNZ)    real(c_double)
!   FSUNSparseMatrix_IndexValues(A)   ind(1:NNZ)    integer(c_int64_t)
!   FSUNSparseMatrix_IndexPointers(A) ptr(1:NP+1)   integer(c_int64_t)
!   FSUNSparseMatrix_Reserve(A, nnz)  make room for nnz entries
!
! The arrays are 1-based Fortran views of 0-based C arrays: the *values*
! stored in ind and ptr are C indices. For CSC, column j (1-based) holds the
! entries p = ptr(j)+1 .. ptr(j+1), in rows ind(p)+1, values val(p).
! sunindextype is integer(c_int64_t), checked when Lignum is built
! (fortran/flignum_cshim.c).
!
! The C declarations (SUNSparseMatrix, its accessors, SUNLinSol_KLU,
! SUNLinSol_KLUReInit, CSC_MAT, CSR_MAT) are in flignum_sundials_mod.
! ---------------------------------------------------------------------------
module flignum_klu_mod
  use, intrinsic :: iso_c_binding
  use flignum_sundials_mod, only: SUNSparseMatrix_NNZ, SUNSparseMatrix_NP, &
                                  SUNSparseMatrix_Data, SUNSparseMatrix_IndexValues, &
                                  SUNSparseMatrix_IndexPointers, SUNSparseMatrix_Reallocate
  implicit none
  private

  public :: FSUNSparseMatrix_Data, FSUNSparseMatrix_IndexValues
  public :: FSUNSparseMatrix_IndexPointers, FSUNSparseMatrix_Reserve

contains

  !> The values of a sparse SUNMatrix as a Fortran array (no copy).
  !! Invalid after SUNSparseMatrix_Reallocate (FSUNSparseMatrix_Reserve).
  !! @param A a sparse SUNMatrix
  !! @return  pointer val(1:NNZ) to its values (NNZ = allocated entries)
  function FSUNSparseMatrix_Data(A) result(val)
    type(c_ptr), intent(in) :: A
    real(c_double), pointer :: val(:)

    call c_f_pointer(SUNSparseMatrix_Data(A), val, [SUNSparseMatrix_NNZ(A)])
  end function FSUNSparseMatrix_Data

  !> The row (CSC) or column (CSR) indices of a sparse SUNMatrix as a
  !! Fortran array (no copy); the indices stored are 0-based.
  !! Invalid after SUNSparseMatrix_Reallocate (FSUNSparseMatrix_Reserve).
  !! @param A a sparse SUNMatrix
  !! @return  pointer ind(1:NNZ) to its index values
  function FSUNSparseMatrix_IndexValues(A) result(ind)
    type(c_ptr), intent(in) :: A
    integer(c_int64_t), pointer :: ind(:)

    call c_f_pointer(SUNSparseMatrix_IndexValues(A), ind, [SUNSparseMatrix_NNZ(A)])
  end function FSUNSparseMatrix_IndexValues

  !> The index pointers of a sparse SUNMatrix as a Fortran array (no copy):
  !! ptr(j) is the 0-based position of the first entry of column (CSC) or
  !! row (CSR) j, and ptr(NP+1) the number of entries in use.
  !! @param A a sparse SUNMatrix
  !! @return  pointer ptr(1:NP+1) to its index pointers
  function FSUNSparseMatrix_IndexPointers(A) result(ptr)
    type(c_ptr), intent(in) :: A
    integer(c_int64_t), pointer :: ptr(:)

    call c_f_pointer(SUNSparseMatrix_IndexPointers(A), ptr, [SUNSparseMatrix_NP(A) + 1])
  end function FSUNSparseMatrix_IndexPointers

  !> Make room for nnz entries: SUNSparseMatrix_Reallocate(A, nnz) if A has
  !! fewer, else nothing. Get the arrays (FSUNSparseMatrix_Data, ...) after
  !! this call: reallocation moves them.
  !! @param A   a sparse SUNMatrix
  !! @param nnz entries needed
  !! @return    0 on success, the nonzero flag of SUNSparseMatrix_Reallocate
  function FSUNSparseMatrix_Reserve(A, nnz) result(flag)
    type(c_ptr), intent(in) :: A
    integer(c_int64_t), intent(in) :: nnz
    integer(c_int) :: flag

    flag = 0
    if (SUNSparseMatrix_NNZ(A) < nnz) flag = SUNSparseMatrix_Reallocate(A, nnz)
  end function FSUNSparseMatrix_Reserve

end module flignum_klu_mod
