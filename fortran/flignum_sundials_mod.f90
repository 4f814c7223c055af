! -----------------------------------------------------------------------------
! Lignum: Lie group Newmark-type integrators for constrained multibody systems.
! SPDX-License-Identifier: BSD-3-Clause
! -----------------------------------------------------------------------------
! flignum_sundials_mod: bind(C) interfaces to the SUNDIALS C functions a
! Fortran user of Lignum needs (context, serial N_Vector, dense and sparse
! SUNMatrix, dense and KLU linear solvers), checked against the SUNDIALS
! 6.4.1 headers. Debian ships SUNDIALS' own Fortran modules without .mod files
! (style.md §4), so this module binds the C libraries directly; never link
! SUNDIALS::f*_mod together with it (same Fortran names).
!
! Only interfaces (and helpers calling the serial vector and dense matrix
! functions, which Lignum::lignum links) are compiled: declaring the sparse
! and KLU functions costs nothing, calling them needs a program linked with
! SUNDIALS::sunmatrixsparse / SUNDIALS::sunlinsolklu (LGN_ENABLE_KLU).
!
! Types: N_Vector, SUNMatrix, SUNLinearSolver, SUNContext -> type(c_ptr);
! sunindextype -> integer(c_int64_t); sunrealtype -> real(c_double).
! Helpers that exist only in Fortran carry an F prefix: FSUNContext_Create,
! FN_VGetArray, FSUNDenseMatrix_Array; those for sparse matrices
! (FSUNSparseMatrix_Data, ...) are in flignum_klu_mod (LGN_ENABLE_KLU).
! ---------------------------------------------------------------------------
module flignum_sundials_mod
  use, intrinsic :: iso_c_binding
  implicit none

  ! SUNOutputFormat (sundials_types.h), for LGNPrintAllStats
  enum, bind(c)
    enumerator :: SUN_OUTPUTFORMAT_TABLE = 0, SUN_OUTPUTFORMAT_CSV
  end enum

  ! SUNMatrix_ID (sundials_matrix.h), returned by SUNMatGetID
  enum, bind(c)
    enumerator :: SUNMATRIX_DENSE = 0, SUNMATRIX_MAGMADENSE, SUNMATRIX_ONEMKLDENSE
    enumerator :: SUNMATRIX_BAND, SUNMATRIX_SPARSE, SUNMATRIX_SLUNRLOC
    enumerator :: SUNMATRIX_CUSPARSE, SUNMATRIX_GINKGO, SUNMATRIX_KOKKOSDENSE
    enumerator :: SUNMATRIX_CUSTOM
  end enum

  ! sparse storage types (sunmatrix_sparse.h)
  integer(c_int), parameter :: CSC_MAT = 0
  integer(c_int), parameter :: CSR_MAT = 1

  ! reinit_type of SUNLinSol_KLUReInit (sunlinsol_klu.h)
  integer(c_int), parameter :: SUNKLU_REINIT_FULL = 1
  integer(c_int), parameter :: SUNKLU_REINIT_PARTIAL = 2

  interface
    ! =========================================================================
    ! SUNContext (sundials_context.h)
    ! =========================================================================

    !> Create a context. comm: c_null_ptr in SUNDIALS 6.x (FSUNContext_Create
    !! hides the version difference).
    integer(c_int) function SUNContext_Create(comm, ctx) bind(c, name="SUNContext_Create")
      import :: c_int, c_ptr
      type(c_ptr), value :: comm
      type(c_ptr), intent(out) :: ctx
    end function SUNContext_Create

    !> Free a context; sets ctx = c_null_ptr.
    integer(c_int) function SUNContext_Free(ctx) bind(c, name="SUNContext_Free")
      import :: c_int, c_ptr
      type(c_ptr), intent(inout) :: ctx
    end function SUNContext_Free

    ! =========================================================================
    ! N_Vector (sundials_nvector.h, nvector_serial.h)
    ! =========================================================================

    !> New serial vector of length n (own data).
    type(c_ptr) function N_VNew_Serial(n, sunctx) bind(c, name="N_VNew_Serial")
      import :: c_ptr, c_int64_t
      integer(c_int64_t), value :: n
      type(c_ptr), value :: sunctx
    end function N_VNew_Serial

    !> Serial vector on user data: v_data = c_loc(x) of a contiguous
    !! real(c_double), target :: x(n) that outlives the vector.
    type(c_ptr) function N_VMake_Serial(n, v_data, sunctx) bind(c, name="N_VMake_Serial")
      import :: c_ptr, c_int64_t
      integer(c_int64_t), value :: n
      type(c_ptr), value :: v_data, sunctx
    end function N_VMake_Serial

    !> Address of the vector's data (see FN_VGetArray for a Fortran array).
    type(c_ptr) function N_VGetArrayPointer(v) bind(c, name="N_VGetArrayPointer")
      import :: c_ptr
      type(c_ptr), value :: v
    end function N_VGetArrayPointer

    !> Global length of a vector.
    integer(c_int64_t) function N_VGetLength(v) bind(c, name="N_VGetLength")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: v
    end function N_VGetLength

    !> z = cval (every entry).
    subroutine N_VConst(cval, z) bind(c, name="N_VConst")
      import :: c_ptr, c_double
      real(c_double), value :: cval
      type(c_ptr), value :: z
    end subroutine N_VConst

    !> Destroy a vector (its data too, unless made with N_VMake_Serial).
    subroutine N_VDestroy(v) bind(c, name="N_VDestroy")
      import :: c_ptr
      type(c_ptr), value :: v
    end subroutine N_VDestroy

    ! =========================================================================
    ! SUNMatrix (sundials_matrix.h, sunmatrix_dense.h, sunmatrix_sparse.h)
    ! =========================================================================

    !> Matrix type, SUNMATRIX_DENSE, SUNMATRIX_SPARSE, ...
    integer(c_int) function SUNMatGetID(A) bind(c, name="SUNMatGetID")
      import :: c_int, c_ptr
      type(c_ptr), value :: A
    end function SUNMatGetID

    !> A = 0 (for a sparse matrix: also the index arrays).
    integer(c_int) function SUNMatZero(A) bind(c, name="SUNMatZero")
      import :: c_int, c_ptr
      type(c_ptr), value :: A
    end function SUNMatZero

    !> Destroy a matrix.
    subroutine SUNMatDestroy(A) bind(c, name="SUNMatDestroy")
      import :: c_ptr
      type(c_ptr), value :: A
    end subroutine SUNMatDestroy

    !> Dense M x N matrix, column-major.
    type(c_ptr) function SUNDenseMatrix(M, N, sunctx) bind(c, name="SUNDenseMatrix")
      import :: c_ptr, c_int64_t
      integer(c_int64_t), value :: M, N
      type(c_ptr), value :: sunctx
    end function SUNDenseMatrix

    !> Rows of a dense matrix.
    integer(c_int64_t) function SUNDenseMatrix_Rows(A) bind(c, name="SUNDenseMatrix_Rows")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: A
    end function SUNDenseMatrix_Rows

    !> Columns of a dense matrix.
    integer(c_int64_t) function SUNDenseMatrix_Columns(A) bind(c, name="SUNDenseMatrix_Columns")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: A
    end function SUNDenseMatrix_Columns

    !> Length M*N of the data of a dense matrix.
    integer(c_int64_t) function SUNDenseMatrix_LData(A) bind(c, name="SUNDenseMatrix_LData")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: A
    end function SUNDenseMatrix_LData

    !> Address of the column-major data (see FSUNDenseMatrix_Array).
    type(c_ptr) function SUNDenseMatrix_Data(A) bind(c, name="SUNDenseMatrix_Data")
      import :: c_ptr
      type(c_ptr), value :: A
    end function SUNDenseMatrix_Data

    !> Address of column j (0-based).
    type(c_ptr) function SUNDenseMatrix_Column(A, j) bind(c, name="SUNDenseMatrix_Column")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: A
      integer(c_int64_t), value :: j
    end function SUNDenseMatrix_Column

    !> Sparse M x N matrix with room for NNZ entries, CSC_MAT or CSR_MAT.
    type(c_ptr) function SUNSparseMatrix(M, N, NNZ, sparsetype, sunctx) &
        bind(c, name="SUNSparseMatrix")
      import :: c_ptr, c_int, c_int64_t
      integer(c_int64_t), value :: M, N, NNZ
      integer(c_int), value :: sparsetype
      type(c_ptr), value :: sunctx
    end function SUNSparseMatrix

    !> Rows of a sparse matrix.
    integer(c_int64_t) function SUNSparseMatrix_Rows(A) bind(c, name="SUNSparseMatrix_Rows")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: A
    end function SUNSparseMatrix_Rows

    !> Columns of a sparse matrix.
    integer(c_int64_t) function SUNSparseMatrix_Columns(A) &
        bind(c, name="SUNSparseMatrix_Columns")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: A
    end function SUNSparseMatrix_Columns

    !> Allocated number of nonzeros.
    integer(c_int64_t) function SUNSparseMatrix_NNZ(A) bind(c, name="SUNSparseMatrix_NNZ")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: A
    end function SUNSparseMatrix_NNZ

    !> Number of index pointers minus one (columns for CSC, rows for CSR).
    integer(c_int64_t) function SUNSparseMatrix_NP(A) bind(c, name="SUNSparseMatrix_NP")
      import :: c_ptr, c_int64_t
      type(c_ptr), value :: A
    end function SUNSparseMatrix_NP

    !> CSC_MAT or CSR_MAT.
    integer(c_int) function SUNSparseMatrix_SparseType(A) &
        bind(c, name="SUNSparseMatrix_SparseType")
      import :: c_ptr, c_int
      type(c_ptr), value :: A
    end function SUNSparseMatrix_SparseType

    !> Address of the values, real(c_double)(NNZ).
    type(c_ptr) function SUNSparseMatrix_Data(A) bind(c, name="SUNSparseMatrix_Data")
      import :: c_ptr
      type(c_ptr), value :: A
    end function SUNSparseMatrix_Data

    !> Address of the 0-based row (CSC) / column (CSR) indices, integer(c_int64_t)(NNZ).
    type(c_ptr) function SUNSparseMatrix_IndexValues(A) &
        bind(c, name="SUNSparseMatrix_IndexValues")
      import :: c_ptr
      type(c_ptr), value :: A
    end function SUNSparseMatrix_IndexValues

    !> Address of the 0-based index pointers, integer(c_int64_t)(NP + 1).
    type(c_ptr) function SUNSparseMatrix_IndexPointers(A) &
        bind(c, name="SUNSparseMatrix_IndexPointers")
      import :: c_ptr
      type(c_ptr), value :: A
    end function SUNSparseMatrix_IndexPointers

    !> Change the storage to NNZ entries (0 on success).
    integer(c_int) function SUNSparseMatrix_Reallocate(A, NNZ) &
        bind(c, name="SUNSparseMatrix_Reallocate")
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value :: A
      integer(c_int64_t), value :: NNZ
    end function SUNSparseMatrix_Reallocate

    !> Shrink the storage to the number of nonzeros in use (0 on success).
    integer(c_int) function SUNSparseMatrix_Realloc(A) bind(c, name="SUNSparseMatrix_Realloc")
      import :: c_ptr, c_int
      type(c_ptr), value :: A
    end function SUNSparseMatrix_Realloc

    ! =========================================================================
    ! SUNLinearSolver (sundials_linearsolver.h, sunlinsol_dense.h, sunlinsol_klu.h)
    ! =========================================================================

    !> Dense direct solver for the dense matrix A; y a template vector.
    type(c_ptr) function SUNLinSol_Dense(y, A, sunctx) bind(c, name="SUNLinSol_Dense")
      import :: c_ptr
      type(c_ptr), value :: y, A, sunctx
    end function SUNLinSol_Dense

    !> KLU sparse direct solver for the sparse matrix A (LGN_ENABLE_KLU).
    type(c_ptr) function SUNLinSol_KLU(y, A, sunctx) bind(c, name="SUNLinSol_KLU")
      import :: c_ptr
      type(c_ptr), value :: y, A, sunctx
    end function SUNLinSol_KLU

    !> KLU's fill-reducing ordering: 0 AMD, 1 COLAMD (SUNDIALS' default),
    !! 2 natural. AMD suits Lignum's iteration matrices, whose pattern is
    !! symmetric.
    integer(c_int) function SUNLinSol_KLUSetOrdering(S, ordering_choice) &
        bind(c, name="SUNLinSol_KLUSetOrdering")
      import :: c_ptr, c_int
      type(c_ptr), value :: S
      integer(c_int), value :: ordering_choice
    end function SUNLinSol_KLUSetOrdering

    !> Re-initialise KLU after the sparsity pattern changed.
    integer(c_int) function SUNLinSol_KLUReInit(S, A, nnz, reinit_type) &
        bind(c, name="SUNLinSol_KLUReInit")
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value :: S, A
      integer(c_int64_t), value :: nnz
      integer(c_int), value :: reinit_type
    end function SUNLinSol_KLUReInit

    !> Free a linear solver.
    integer(c_int) function SUNLinSolFree(S) bind(c, name="SUNLinSolFree")
      import :: c_int, c_ptr
      type(c_ptr), value :: S
    end function SUNLinSolFree
  end interface

contains

  !> Create a SUNDIALS context without MPI communicator (the one place that
  !! knows the SUNContext_Create signature: NULL in 6.x, SUN_COMM_NULL in 7.x).
  !! @param ctx on return, the context (free it with SUNContext_Free)
  !! @return    0 on success
  function FSUNContext_Create(ctx) result(flag)
    type(c_ptr), intent(out) :: ctx
    integer(c_int) :: flag

    flag = SUNContext_Create(c_null_ptr, ctx)
  end function FSUNContext_Create

  !> The data of a serial N_Vector as a Fortran array (no copy).
  !! @param v a serial N_Vector
  !! @return  pointer x(1:N_VGetLength(v)) to its data
  function FN_VGetArray(v) result(x)
    type(c_ptr), intent(in) :: v
    real(c_double), pointer :: x(:)

    call c_f_pointer(N_VGetArrayPointer(v), x, [N_VGetLength(v)])
  end function FN_VGetArray

  !> The data of a dense SUNMatrix as a Fortran array (no copy): both are
  !! column-major, so A(i, j) is SM_ELEMENT_D(A, i-1, j-1).
  !! @param A a dense SUNMatrix
  !! @return  pointer a(1:rows, 1:columns) to its data
  function FSUNDenseMatrix_Array(A) result(a2)
    type(c_ptr), intent(in) :: A
    real(c_double), pointer :: a2(:, :)

    call c_f_pointer(SUNDenseMatrix_Data(A), a2, &
                     [SUNDenseMatrix_Rows(A), SUNDenseMatrix_Columns(A)])
  end function FSUNDenseMatrix_Array

end module flignum_sundials_mod
