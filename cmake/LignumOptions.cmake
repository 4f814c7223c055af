# Build options of Lignum, all prefixed LGN_.
option(BUILD_SHARED_LIBS "Build Lignum as a shared library" ON)
option(LGN_BUILD_EXAMPLES "Build the teaching examples in examples/ (also registered as tests)" ON)
option(LGN_BUILD_TESTS "Build the test suite" ON)
option(LGN_BUILD_BENCHMARKS "Build the benchmarks and the study tools in bench/ (tools also registered as tests)" ON)
# Warnings are always on; errors only when asked for (CI passes ON), as
# SUNDIALS' ENABLE_ALL_WARNINGS / ENABLE_WARNINGS_AS_ERRORS.
option(LGN_WARNINGS_AS_ERRORS "Compile with -Wall -Wextra -Wpedantic -Werror" OFF)
option(LGN_ENABLE_SANITIZERS "Build with AddressSanitizer and UBSan" OFF)
option(LGN_ENABLE_TSAN "Build with ThreadSanitizer (not with LGN_ENABLE_SANITIZERS)" OFF)
option(LGN_BUILD_FUZZ "Build the libFuzzer target test/fuzz (Clang only; implies ASan + UBSan)" OFF)
option(LGN_ENABLE_KLU "Enable the sparse path with SUNDIALS' KLU linear solver" ON)
# The Fortran interface is built by default when a Fortran compiler works
# (checked only while the option is not yet set).
set(_lgn_fortran_default OFF)
if(NOT DEFINED LGN_ENABLE_FORTRAN)
  include(CheckLanguage)
  check_language(Fortran)
  if(CMAKE_Fortran_COMPILER)
    set(_lgn_fortran_default ON)
  endif()
endif()
option(LGN_ENABLE_FORTRAN
  "Build the Fortran 2003 interface (modules flignum_mod, flignum_sundials_mod, flignum_joints_mod, flignum_bodies_mod, and flignum_klu_mod with KLU)"
  ${_lgn_fortran_default})
option(LGN_ENABLE_VALGRIND_TESTS "Run examples and study tools under valgrind when it is found" ON)
# The direct solve through PETSc and MUMPS (LGNLinSol_PETSc,
# include/lignum/lignum_petsc.h) is built by default when pkg-config finds
# PETSc (PETSc.pc; checked only while the option is not yet set); with
# LGN_ENABLE_PETSC=ON a PETSc without MUMPS, or no PETSc, is an error.
set(_lgn_petsc_default OFF)
if(NOT DEFINED LGN_ENABLE_PETSC)
  find_package(PkgConfig QUIET)
  if(PKG_CONFIG_FOUND)
    pkg_check_modules(_LGN_PETSC_PROBE QUIET PETSc)
    if(_LGN_PETSC_PROBE_FOUND)
      set(_lgn_petsc_default ON)
    endif()
  endif()
endif()
option(LGN_ENABLE_PETSC
  "Build LGNLinSol_PETSc, a direct solve through PETSc's KSP with MUMPS (needs PETSc with MUMPS, and MPI)"
  ${_lgn_petsc_default})
# Runs across MPI ranks (state vectors of type N_Vector_Parallel or
# MPIPlusX; src/parallel/lgn_parallel.c) are built by default when MPI for C is
# found (checked only while the option is not yet set). liblignum then
# links MPI and SUNDIALS' parallel vectors privately; its headers do not
# include <mpi.h>.
set(_lgn_mpi_default OFF)
if(NOT DEFINED LGN_ENABLE_MPI)
  find_package(MPI QUIET COMPONENTS C)
  if(MPI_C_FOUND)
    set(_lgn_mpi_default ON)
  endif()
endif()
option(LGN_ENABLE_MPI
  "Runs across MPI ranks with SUNDIALS' parallel vectors (needs MPI and SUNDIALS' nvecparallel and nvecmpiplusx)"
  ${_lgn_mpi_default})

# The summary of the optional components at the end of the configuration:
# each is an explicit option; Fortran, PETSc and MPI default to ON when they
# are found on the first configuration (and to OFF otherwise), KLU to ON;
# an option set to ON whose component is missing stops the
# configuration with a message.
function(lgn_print_components)
  message(STATUS "Lignum components (choose with -D<option>=ON or OFF):")
  foreach(_opt LGN_ENABLE_KLU LGN_ENABLE_FORTRAN LGN_ENABLE_MPI
               LGN_ENABLE_PETSC LGN_WARNINGS_AS_ERRORS)
    message(STATUS "  ${_opt} = ${${_opt}}")
  endforeach()
endfunction()
