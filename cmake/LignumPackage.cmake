# Packaging of Lignum, modelled on SUNDIALS' top-level CMakeLists.txt:
#   - install the library, the public headers and the generated headers;
#   - the CMake package Lignum (LignumConfig.cmake, LignumConfigVersion.cmake,
#     LignumTargets.cmake with the target Lignum::lignum), installed to
#     ${CMAKE_INSTALL_LIBDIR}/cmake/Lignum and also exported from the build
#     tree (-DLignum_DIR=<build dir> works without installing);
#   - lignum.pc for pkg-config, which lists the SUNDIALS libraries explicitly
#     because SUNDIALS ships no .pc file;
#   - the target `doc` (Doxygen), only when Doxygen is found, which fails on
#     any Doxygen warning, and the CTest test doc_no_warnings that runs it;
#   - the manual (README.md, doc/*.md, doc/figures) in share/doc/lignum, with
#     the HTML API reference in share/doc/lignum/html when it was built.
#
# Included at the end of the top-level CMakeLists.txt, after src/ (and the
# optional Fortran module) have defined their targets.
#
# Other installable targets (e.g. the Fortran module library) join the export
# set by appending their names to the global property LGN_EXPORT_TARGETS:
#   set_property(GLOBAL APPEND PROPERTY LGN_EXPORT_TARGETS lignum_fortran)
# Each such target should set EXPORT_NAME so that it appears as Lignum::<name>.

include(CMakePackageConfigHelpers)

set(LGN_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/Lignum")
set(LGN_INSTALL_PKGCONFIGDIR "${CMAKE_INSTALL_LIBDIR}/pkgconfig")

# -----------------------------------------------------------------------------
# Library and headers
# -----------------------------------------------------------------------------
set_target_properties(lignum PROPERTIES EXPORT_NAME lignum)

set(_lgn_export_targets lignum)
get_property(_lgn_extra_targets GLOBAL PROPERTY LGN_EXPORT_TARGETS)
list(APPEND _lgn_export_targets ${_lgn_extra_targets})
list(REMOVE_DUPLICATES _lgn_export_targets)

install(TARGETS ${_lgn_export_targets}
  EXPORT LignumTargets
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})

# Public headers (include/lignum/*.h), and the generated ones in the build
# tree's include/lignum (lignum_config.h, lignum_export.h with LGN_EXPORT).
# lignum_petsc.h only with PETSc (LGN_ENABLE_PETSC).
set(_lgn_header_excludes "")
if(NOT LGN_ENABLE_PETSC)
  list(APPEND _lgn_header_excludes PATTERN "lignum_petsc.h" EXCLUDE)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/lignum
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h" ${_lgn_header_excludes})
install(FILES ${PROJECT_BINARY_DIR}/include/lignum/lignum_config.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lignum)
install(DIRECTORY ${PROJECT_BINARY_DIR}/include/lignum
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h" PATTERN "lignum_config.h" EXCLUDE)

# -----------------------------------------------------------------------------
# CMake package: find_package(Lignum) -> Lignum::lignum
# -----------------------------------------------------------------------------
# The SUNDIALS components for find_dependency(), as a space separated list.
string(REPLACE ";" " " LGN_SUNDIALS_COMPONENTS_STRING "${LGN_SUNDIALS_COMPONENTS}")

# The config file finds LignumTargets.cmake next to itself, so the same file
# serves the build tree (with export() below) and the install tree.
configure_package_config_file(
  ${PROJECT_SOURCE_DIR}/cmake/LignumConfig.cmake.in
  ${PROJECT_BINARY_DIR}/LignumConfig.cmake
  INSTALL_DESTINATION ${LGN_INSTALL_CMAKEDIR})
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/LignumConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMajorVersion)

install(EXPORT LignumTargets
  NAMESPACE Lignum::
  FILE LignumTargets.cmake
  DESTINATION ${LGN_INSTALL_CMAKEDIR})
install(FILES
  ${PROJECT_BINARY_DIR}/LignumConfig.cmake
  ${PROJECT_BINARY_DIR}/LignumConfigVersion.cmake
  DESTINATION ${LGN_INSTALL_CMAKEDIR})

# Build tree: find_package(Lignum) with -DLignum_DIR=<build dir>.
# A static lignum carries $<LINK_ONLY:lignum_build_flags> in its interface,
# and export() keeps $<BUILD_INTERFACE:...>, so the (non-installed) flags
# target must be exported with it; it then only passes on its link options
# (the sanitizers). The installed package never refers to it.
set(_lgn_build_tree_targets ${_lgn_export_targets})
get_target_property(_lgn_type lignum TYPE)
if(_lgn_type STREQUAL "STATIC_LIBRARY" AND TARGET lignum_build_flags)
  list(APPEND _lgn_build_tree_targets lignum_build_flags)
endif()
export(TARGETS ${_lgn_build_tree_targets}
  NAMESPACE Lignum::
  FILE ${PROJECT_BINARY_DIR}/LignumTargets.cmake)

# -----------------------------------------------------------------------------
# pkg-config: lignum.pc
# -----------------------------------------------------------------------------
# Relocatable: the prefix is found from the .pc file's own location, so that
# `cmake --install build --prefix DIR` yields a working file. Absolute
# CMAKE_INSTALL_LIBDIR / INCLUDEDIR are written as they are.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}" OR IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(LGN_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  set(LGN_PC_LIBDIR "${CMAKE_INSTALL_FULL_LIBDIR}")
  set(LGN_PC_INCLUDEDIR "${CMAKE_INSTALL_FULL_INCLUDEDIR}")
else()
  file(RELATIVE_PATH _lgn_pc_up "/prefix/${LGN_INSTALL_PKGCONFIGDIR}" "/prefix")
  string(REGEX REPLACE "/$" "" _lgn_pc_up "${_lgn_pc_up}")
  set(LGN_PC_PREFIX "\${pcfiledir}/${_lgn_pc_up}")
  set(LGN_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
  set(LGN_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
endif()

# SUNDIALS libraries, one -l per component Lignum links. Each SUNDIALS
# library carries its own copy of the core (SUNContext_Create, ...).
set(LGN_PC_SUNDIALS_LIBS "")
get_target_property(_lgn_nvec_loc SUNDIALS::nvecserial_shared LOCATION)
if(_lgn_nvec_loc)
  get_filename_component(_lgn_sundials_libdir "${_lgn_nvec_loc}" DIRECTORY)
  if(NOT _lgn_sundials_libdir IN_LIST CMAKE_C_IMPLICIT_LINK_DIRECTORIES)
    string(APPEND LGN_PC_SUNDIALS_LIBS " -L${_lgn_sundials_libdir}")
  endif()
endif()
foreach(_lgn_comp IN LISTS LGN_SUNDIALS_COMPONENTS)
  string(APPEND LGN_PC_SUNDIALS_LIBS " -lsundials_${_lgn_comp}")
endforeach()
# With KLU, Lignum calls KLU itself (klu_l_extract, klu_l_solve): a static
# liblignum needs libklu on the link line (a shared one carries it).
if(LGN_ENABLE_KLU AND _lgn_type STREQUAL "STATIC_LIBRARY")
  string(APPEND LGN_PC_SUNDIALS_LIBS " -lklu -lspqr -lcholmod") # + SuiteSparseQR
endif()
# LAPACK (the diagnostics' QR): likewise for a static liblignum.
if(NOT BUILD_SHARED_LIBS)
  string(APPEND LGN_PC_SUNDIALS_LIBS " -llapack -lblas")
endif()
string(STRIP "${LGN_PC_SUNDIALS_LIBS}" LGN_PC_SUNDIALS_LIBS)

# The KLU path needs <klu.h> (in /usr/include/suitesparse on Debian).
set(LGN_PC_EXTRA_CFLAGS "")
if(LGN_ENABLE_KLU AND TARGET SUNDIALS::KLU)
  get_target_property(_lgn_klu_inc SUNDIALS::KLU INTERFACE_INCLUDE_DIRECTORIES)
  foreach(_lgn_dir IN LISTS _lgn_klu_inc)
    if(_lgn_dir)
      string(APPEND LGN_PC_EXTRA_CFLAGS " -I${_lgn_dir}")
    endif()
  endforeach()
endif()

# lignum.pc describes liblignum only: LGNLinSol_PETSc is in the library
# lignum_petsc (CMake: Lignum::lignum_petsc), which needs PETSc and MPI.
configure_file(${PROJECT_SOURCE_DIR}/cmake/lignum.pc.in
               ${PROJECT_BINARY_DIR}/lignum.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/lignum.pc
  DESTINATION ${LGN_INSTALL_PKGCONFIGDIR})

# -----------------------------------------------------------------------------
# Documentation: `cmake --build build --target doc` (HTML in build/doc/html)
# -----------------------------------------------------------------------------
find_package(Doxygen QUIET)
if(DOXYGEN_FOUND)
  configure_file(${PROJECT_SOURCE_DIR}/doc/Doxyfile.in
                 ${PROJECT_BINARY_DIR}/doc/Doxyfile @ONLY)
  add_custom_target(doc
    COMMAND Doxygen::doxygen ${PROJECT_BINARY_DIR}/doc/Doxyfile
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}/doc
    COMMENT "Generating the API documentation with Doxygen"
    VERBATIM)
  # Doxyfile.in sets WARN_AS_ERROR = FAIL_ON_WARNINGS: the run fails on any
  # warning (all of them in build/doc/doxygen-warnings.log).
  add_test(NAME doc_no_warnings
    COMMAND Doxygen::doxygen ${PROJECT_BINARY_DIR}/doc/Doxyfile
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}/doc)
  set_tests_properties(doc_no_warnings PROPERTIES LABELS doc)
endif()

# -----------------------------------------------------------------------------
# The manual: share/doc/lignum (README.md, doc/*.md, doc/figures, and the
# HTML reference if `cmake --build build --target doc` was run)
# -----------------------------------------------------------------------------
set(LGN_INSTALL_DOCDIR "${CMAKE_INSTALL_DATAROOTDIR}/doc/lignum")
file(GLOB _lgn_manual ${PROJECT_SOURCE_DIR}/doc/*.md)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${_lgn_manual}
  DESTINATION ${LGN_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/doc/figures
  DESTINATION ${LGN_INSTALL_DOCDIR}
  FILES_MATCHING PATTERN "*.png" PATTERN "*.csv")
install(DIRECTORY ${PROJECT_BINARY_DIR}/doc/html
  DESTINATION ${LGN_INSTALL_DOCDIR}
  OPTIONAL)
