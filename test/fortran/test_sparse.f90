! -----------------------------------------------------------------------------
! Lignum Fortran test (LGN_ENABLE_KLU): the sparse helpers of flignum_klu_mod
! and KLU from Fortran.
!
!  - FSUNSparseMatrix_Data/_IndexValues/_IndexPointers have the sizes NNZ,
!    NNZ, NP + 1 and view the C arrays (a value written through the Fortran
!    pointer is read back through the C accessor's address);
!    FSUNSparseMatrix_Reserve grows a matrix only when it is too small;
!  - the sparse B and K of the joint helpers (CSC and CSR), read through the
!    helpers, equal the dense ones entry by entry, with ptr(NP+1) equal to
!    LGNJoints_JacobianNnz / _StiffnessNnz and sorted indices;
!  - an integration with KLU whose Fortran callbacks fill CSC matrices
!    through the helpers: M q'' + K q = 0 on R^2 with a full 2x2 M and K,
!    Newmark (1/4, 1/2), against the same run with dense matrices (to
!    1e-12) and against the modal solution; with KLU Lignum's solves on a
!    copy of KLU's factors are opted in (LGNSetOwnKLUSolves, off by
!    default), and their getters count one copy, Lignum's refactorisations
!    and every solve (dense: all 0).
! SPDX-License-Identifier: BSD-3-Clause
! ---------------------------------------------------------------------------

! Callbacks of M q'' + K q = 0, M = [2 1; 1 2], K = [3 -1; -1 3], for dense
! or CSC matrices.
module test_sparse_model
  use, intrinsic :: iso_c_binding
  use flignum_sundials_mod
  use flignum_klu_mod
  implicit none

  real(c_double), parameter :: mass_matrix(2, 2) = &
    reshape([2.0_c_double, 1.0_c_double, 1.0_c_double, 2.0_c_double], [2, 2])
  real(c_double), parameter :: stiffness_matrix(2, 2) = &
    reshape([3.0_c_double, -1.0_c_double, -1.0_c_double, 3.0_c_double], [2, 2])

  !> Matrices written as CSC by write_full (the callbacks got sparse ones).
  integer :: ncsc_written = 0

contains

  !> Write the full 2x2 matrix X into A (dense, or CSC with all 4 entries).
  function write_full(A, X) result(ierr)
    type(c_ptr), intent(in) :: A
    real(c_double), intent(in) :: X(2, 2)
    integer(c_int) :: ierr
    real(c_double), pointer :: a2(:, :), val(:)
    integer(c_int64_t), pointer :: ind(:), ptr(:)
    integer :: i, j, p

    ierr = 0
    if (SUNMatGetID(A) == SUNMATRIX_DENSE) then
      a2 => FSUNDenseMatrix_Array(A)
      a2 = X
      return
    end if
    if (SUNSparseMatrix_SparseType(A) /= CSC_MAT) then
      ierr = -1
      return
    end if
    if (FSUNSparseMatrix_Reserve(A, 4_c_int64_t) /= 0) then
      ierr = -1
      return
    end if
    val => FSUNSparseMatrix_Data(A)
    ind => FSUNSparseMatrix_IndexValues(A)
    ptr => FSUNSparseMatrix_IndexPointers(A)
    p = 0
    ptr(1) = 0
    do j = 1, 2
      do i = 1, 2
        p = p + 1
        ind(p) = i - 1          ! 0-based row
        val(p) = X(i, j)
      end do
      ptr(j + 1) = p            ! 0-based end of column j
    end do
    ncsc_written = ncsc_written + 1
  end function write_full

  !> LGNMassFn
  integer(c_int) function mass(t, q, M, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, M, user_data

    ierr = write_full(M, mass_matrix)
  end function mass

  !> LGNForceFn: g = K q
  integer(c_int) function force(t, q, v, g, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, g, user_data
    real(c_double), pointer :: qq(:), gg(:)

    qq => FN_VGetArray(q)
    gg => FN_VGetArray(g)
    gg(1:2) = matmul(stiffness_matrix, qq(1:2))
    ierr = 0
  end function force

  !> LGNStiffnessFn: K_t = K
  integer(c_int) function stiffness(t, q, v, vdot, lambda, K, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, vdot, lambda, K, user_data

    ierr = write_full(K, stiffness_matrix)
  end function stiffness

  !> LGNDampingFn: C_t = 0 (nothing stored)
  integer(c_int) function damping(t, q, v, C, user_data) result(ierr) bind(c)
    real(c_double), value :: t
    type(c_ptr), value :: q, v, C, user_data
    integer(c_int64_t), pointer :: ptr(:)

    ierr = 0
    if (SUNMatGetID(C) == SUNMATRIX_SPARSE) then
      ptr => FSUNSparseMatrix_IndexPointers(C)
      ptr = 0
    end if
  end function damping

end module test_sparse_model

program test_sparse
  use, intrinsic :: iso_c_binding
  use flignum_mod
  use flignum_joints_mod
  use flignum_sundials_mod
  use flignum_klu_mod
  use test_sparse_model
  use ftest_util
  implicit none

  type(c_ptr) :: ctx

  call expect(FSUNContext_Create(ctx) == 0, "SUNContext_Create")
  call test_helpers()
  call test_joints_sparse()
  call test_klu_integration()
  call expect(SUNContext_Free(ctx) == 0, "SUNContext_Free")
  call ftest_finish("test_sparse")

contains

  !> Sizes, aliasing of the C arrays, FSUNSparseMatrix_Reserve.
  subroutine test_helpers()
    type(c_ptr) :: S
    real(c_double), pointer :: val(:), cval(:)
    integer(c_int64_t), pointer :: ind(:), ptr(:), cind(:)

    S = SUNSparseMatrix(3_c_int64_t, 5_c_int64_t, 7_c_int64_t, CSC_MAT, ctx)
    val => FSUNSparseMatrix_Data(S)
    ind => FSUNSparseMatrix_IndexValues(S)
    ptr => FSUNSparseMatrix_IndexPointers(S)
    call expect(size(val) == 7 .and. size(ind) == 7, "3x5 CSC, NNZ 7: val(1:7), ind(1:7)")
    call expect(size(ptr) == 5 + 1, "CSC: ptr(1:columns + 1)")
    val(7) = 2.5_c_double
    ind(7) = 2
    call c_f_pointer(SUNSparseMatrix_Data(S), cval, [7])
    call c_f_pointer(SUNSparseMatrix_IndexValues(S), cind, [7])
    call expect_near(cval(7), 2.5_c_double, 0.0_c_double, "val(7) is the C value data[6]")
    call expect(cind(7) == 2, "ind(7) is the C index indexvals[6]")

    call expect(FSUNSparseMatrix_Reserve(S, 5_c_int64_t) == 0, "Reserve(5) of NNZ 7")
    call expect(SUNSparseMatrix_NNZ(S) == 7, "Reserve(5) leaves NNZ = 7")
    call expect(FSUNSparseMatrix_Reserve(S, 20_c_int64_t) == 0, "Reserve(20) of NNZ 7")
    call expect(SUNSparseMatrix_NNZ(S) == 20, "Reserve(20) grows NNZ to 20")
    val => FSUNSparseMatrix_Data(S)
    call expect(size(val) == 20, "the arrays after Reserve have the new size")
    call expect(FSUNSparseMatrix_Reserve(S, -1_c_int64_t) == 0, "Reserve(-1) does nothing")
    call SUNMatDestroy(S)

    S = SUNSparseMatrix(3_c_int64_t, 5_c_int64_t, 7_c_int64_t, CSR_MAT, ctx)
    ptr => FSUNSparseMatrix_IndexPointers(S)
    call expect(size(ptr) == 3 + 1, "CSR: ptr(1:rows + 1)")
    call SUNMatDestroy(S)
  end subroutine test_helpers

  !> The dense matrix of a CSC or CSR matrix read through the helpers, and
  !! whether its indices are in range and increasing within each column/row.
  subroutine to_dense(S, D, sorted)
    type(c_ptr), intent(in) :: S
    real(c_double), intent(out) :: D(:, :)
    logical, intent(out) :: sorted
    real(c_double), pointer :: val(:)
    integer(c_int64_t), pointer :: ind(:), ptr(:)
    integer(c_int64_t) :: k, p, o
    logical :: csc

    csc = SUNSparseMatrix_SparseType(S) == CSC_MAT
    val => FSUNSparseMatrix_Data(S)
    ind => FSUNSparseMatrix_IndexValues(S)
    ptr => FSUNSparseMatrix_IndexPointers(S)
    D = 0
    sorted = ptr(1) == 0
    do k = 1, size(ptr, kind=c_int64_t) - 1
      do p = ptr(k) + 1, ptr(k + 1)
        o = ind(p) + 1                       ! 1-based row (CSC) / column (CSR)
        if (o < 1 .or. o > merge(size(D, 1), size(D, 2), csc)) then
          sorted = .false.
          cycle
        end if
        if (p > ptr(k) + 1) sorted = sorted .and. ind(p) > ind(p - 1)
        if (csc) then
          D(o, k) = D(o, k) + val(p)
        else
          D(k, o) = D(k, o) + val(p)
        end if
      end do
    end do
  end subroutine to_dense

  !> Sparse B and K of the joint helpers against the dense ones.
  subroutine test_joints_sparse()
    real(c_double), parameter :: pa(3) = [0.1_c_double, -0.2_c_double, 0.5_c_double]
    real(c_double), parameter :: pb(3) = [-0.3_c_double, 0.2_c_double, -0.4_c_double]
    real(c_double), parameter :: ax(3) = [0.0_c_double, 0.0_c_double, 1.0_c_double]
    type(c_ptr) :: body, G, J, qv, lv, B, K, S
    type(c_ptr) :: factors(3)
    real(c_double), pointer :: q(:), lam(:), Ba(:, :), Ka(:, :)
    integer(c_int64_t), pointer :: ptr(:)
    real(c_double), allocatable :: D(:, :)
    integer(c_int64_t) :: m, nv
    integer(c_int) :: st
    integer :: i, kind
    logical :: sorted
    character(len=3) :: name

    body = LGNGroup_R3xSO3()
    factors = [body, body, body]
    G = LGNGroup_Product(3_c_int, factors)
    J = LGNJoints_Create(G)
    call expect(LGNJoints_AddSpherical(J, LGN_GROUND, pa, 0_c_int, pb) == 0, "AddSpherical")
    call expect(LGNJoints_AddRevolute(J, 0_c_int, pa, ax, 1_c_int, pb, ax) == 0, "AddRevolute")
    call expect(LGNJoints_AddUniversal(J, 2_c_int, pa, ax, 1_c_int, pb, pa) == 0, &
                "AddUniversal")
    m = LGNJoints_NumConstraints(J)
    nv = 18
    qv = N_VNew_Serial(21_c_int64_t, ctx)
    lv = N_VNew_Serial(m, ctx)
    q => FN_VGetArray(qv)
    lam => FN_VGetArray(lv)
    do i = 0, 2
      q(7 * i + 1:7 * i + 3) = [0.3_c_double * i, -0.2_c_double, 0.1_c_double * i]
      call LGNQuaternionFromRotationVector([0.2_c_double * i, 0.5_c_double, -0.3_c_double], &
                                           q(7 * i + 4:7 * i + 7))
    end do
    do i = 1, int(m)
      lam(i) = cos(1.7_c_double * i)
    end do
    B = SUNDenseMatrix(m, nv, ctx)
    K = SUNDenseMatrix(nv, nv, ctx)
    Ba => FSUNDenseMatrix_Array(B)
    Ka => FSUNDenseMatrix_Array(K)
    Ba = 0
    Ka = 0
    call expect(LGNJoints_Jacobian(J, 0.0_c_double, qv, B) == 0, "dense B")
    call expect(LGNJoints_Stiffness(J, 0.0_c_double, qv, lv, K) == 0, "dense K")

    do kind = 1, 2
      st = merge(CSC_MAT, CSR_MAT, kind == 1)
      name = merge("CSC", "CSR", kind == 1)
      ! too small on purpose: LGNJoints_Jacobian reallocates
      S = SUNSparseMatrix(m, nv, 4_c_int64_t, st, ctx)
      call expect(LGNJoints_Jacobian(J, 0.0_c_double, qv, S) == 0, name//" B")
      allocate (D(m, nv))
      call to_dense(S, D, sorted)
      call expect(sorted, name//" B: indices in range and increasing")
      call expect(maxval(abs(D - Ba)) <= 0, name//" B = dense B, entry by entry")
      ptr => FSUNSparseMatrix_IndexPointers(S)
      call expect(ptr(size(ptr)) == LGNJoints_JacobianNnz(J), &
                  name//" B: ptr(NP+1) = JacobianNnz")
      deallocate (D)
      call SUNMatDestroy(S)

      S = SUNSparseMatrix(nv, nv, 4_c_int64_t, st, ctx)
      call expect(LGNJoints_Stiffness(J, 0.0_c_double, qv, lv, S) == 0, name//" K")
      allocate (D(nv, nv))
      call to_dense(S, D, sorted)
      call expect(sorted, name//" K: indices in range and increasing")
      call expect(maxval(abs(D - Ka)) <= 0, name//" K = dense K, entry by entry")
      call expect(maxval(abs(Ka)) > 0, "K is not zero")
      ptr => FSUNSparseMatrix_IndexPointers(S)
      call expect(ptr(size(ptr)) == LGNJoints_StiffnessNnz(J), &
                  name//" K: ptr(NP+1) = StiffnessNnz")
      deallocate (D)
      call SUNMatDestroy(S)
    end do

    call SUNMatDestroy(B)
    call SUNMatDestroy(K)
    call N_VDestroy(qv)
    call N_VDestroy(lv)
    call LGNJoints_Destroy(J)
    call LGNGroup_Destroy(G)
    call LGNGroup_Destroy(body)
  end subroutine test_joints_sparse

  !> Integrate M q'' + K q = 0 to t = 1 with KLU (CSC) or dense matrices.
  subroutine integrate(sparse, qend, nanalyses)
    logical, intent(in) :: sparse
    real(c_double), intent(out) :: qend(2)
    integer(c_long), intent(out) :: nanalyses
    type(c_ptr) :: G, qv, vv, A, tmpl, LS, mem
    real(c_double), pointer :: q(:)
    integer(c_long) :: ncopies, nvalues, nrefactors, nsolves, nlsolves
    integer(c_long) :: npivot, npattern, nnocopy
    real(c_double) :: t

    G = LGNGroup_Rn(2_c_int64_t)
    qv = N_VNew_Serial(2_c_int64_t, ctx)
    vv = N_VNew_Serial(2_c_int64_t, ctx)
    tmpl = N_VNew_Serial(2_c_int64_t, ctx)
    q => FN_VGetArray(qv)
    q = [1.0_c_double, 0.0_c_double]
    call N_VConst(0.0_c_double, vv)
    if (sparse) then
      A = SUNSparseMatrix(2_c_int64_t, 2_c_int64_t, 1_c_int64_t, CSC_MAT, ctx)
      LS = SUNLinSol_KLU(tmpl, A, ctx)
    else
      A = SUNDenseMatrix(2_c_int64_t, 2_c_int64_t, ctx)
      LS = SUNLinSol_Dense(tmpl, A, ctx)
    end if
    call expect(c_associated(LS), "linear solver created")
    mem = LGNCreate(ctx)
    call expect(LGNSetGroup(mem, G) == 0, "LGNSetGroup")
    call expect(LGNSetMassFn(mem, c_funloc(mass)) == 0, "LGNSetMassFn")
    call expect(LGNSetForceFn(mem, c_funloc(force)) == 0, "LGNSetForceFn")
    call expect(LGNSetStiffnessFn(mem, c_funloc(stiffness)) == 0, "LGNSetStiffnessFn")
    call expect(LGNSetDampingFn(mem, c_funloc(damping)) == 0, "LGNSetDampingFn")
    call expect(LGNInit(mem, 0.0_c_double, qv, vv) == 0, "LGNInit")
    call expect(LGNSetLinearSolver(mem, LS, A) == 0, "LGNSetLinearSolver")
    ! Lignum's solves on a copy of KLU's factors (off by default): opted in
    if (sparse) call expect(LGNSetOwnKLUSolves(mem, 1_c_int) == 0, "LGNSetOwnKLUSolves(1)")
    call expect(LGNSetNewmark(mem, 0.25_c_double, 0.5_c_double) == 0, "LGNSetNewmark")
    call expect(LGNSetStepSize(mem, 1.0e-3_c_double) == 0, "LGNSetStepSize")
    call expect_flag(LGNSolve(mem, 1.0_c_double, t, qv, vv, LGN_NORMAL), LGN_SUCCESS, &
                     "LGN_SUCCESS", "LGNSolve")
    call expect(LGNGetNumSparsityAnalyses(mem, nanalyses) == 0, "LGNGetNumSparsityAnalyses")
    ! the copy's counters: CSC, so one copy, then Lignum refactors into it
    call expect(LGNGetNumKLUFactorCopies(mem, ncopies) == 0, "LGNGetNumKLUFactorCopies")
    call expect(LGNGetNumKLUValueCopies(mem, nvalues) == 0, "LGNGetNumKLUValueCopies")
    call expect(LGNGetNumOwnKLURefactors(mem, nrefactors) == 0, "LGNGetNumOwnKLURefactors")
    call expect(LGNGetNumOwnKLUSolves(mem, nsolves) == 0, "LGNGetNumOwnKLUSolves")
    call expect(LGNGetNumKLUFallbacks(mem, npivot, npattern, nnocopy) == 0, &
                "LGNGetNumKLUFallbacks")
    call expect(LGNGetNumLinSolves(mem, nlsolves) == 0, "LGNGetNumLinSolves")
    if (sparse) then
      call expect(ncopies == 1 .and. nvalues == 0 .and. nrefactors > 0 .and. &
                  nsolves == nlsolves .and. npivot == 0 .and. npattern == 0 .and. &
                  nnocopy == 0, "KLU CSC, copy on: one copy, Lignum's refactorisations and solves")
    else
      call expect(ncopies == 0 .and. nvalues == 0 .and. nrefactors == 0 .and. &
                  nsolves == 0 .and. npivot == 0 .and. npattern == 0 .and. &
                  nnocopy == 0, "dense: the copy's counters are 0")
    end if
    qend = q
    call LGNFree(mem)
    call expect(SUNLinSolFree(LS) == 0, "SUNLinSolFree")
    call SUNMatDestroy(A)
    call N_VDestroy(qv)
    call N_VDestroy(vv)
    call N_VDestroy(tmpl)
    call LGNGroup_Destroy(G)
  end subroutine integrate

  !> KLU with Fortran-filled CSC matrices = dense = the modal solution.
  subroutine test_klu_integration()
    real(c_double) :: qs(2), qd(2), exact(2), c1, c2
    integer(c_long) :: nas, nad

    call integrate(.true., qs, nas)
    call expect(ncsc_written > 0, "with KLU the callbacks filled CSC matrices")
    call integrate(.false., qd, nad)
    call expect(nas == 1, "KLU: one sparsity analysis (the pattern stays fixed)")
    call expect(nad == 0, "dense: no sparsity analysis")
    call expect_near(maxval(abs(qs - qd)), 0.0_c_double, 1.0e-12_c_double, &
                     "KLU (CSC filled in Fortran) = dense")
    ! modes (1, 1): omega^2 = 2/3, (1, -1): omega^2 = 4; q0 = (1, 0), v0 = 0
    c1 = 0.5_c_double * cos(sqrt(2.0_c_double / 3.0_c_double))
    c2 = 0.5_c_double * cos(2.0_c_double)
    exact = [c1 + c2, c1 - c2]
    call expect_near(maxval(abs(qs - exact)), 0.0_c_double, 1.0e-5_c_double, &
                     "KLU solution = modal solution (Newmark error O(h^2))")
  end subroutine test_klu_integration

end program test_sparse
