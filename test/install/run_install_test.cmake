# Driver of the CTest test install_find_package (see CMakeLists.txt here).
# Run as: cmake -DLGN_BUILD_DIR=... -DLGN_WORK_DIR=... -P run_install_test.cmake
#
#  (a) cmake --install <build dir> --prefix <work>/prefix; liblignum.so
#      exports exactly the functions of the installed headers
#  (b) configure + build test/install/consumer with
#      -DCMAKE_PREFIX_PATH=<work>/prefix (find_package(Lignum REQUIRED))
#  (c) run it
#  (d) if pkg-config (pkgconf) is found: compile main.c with the flags of
#      `pkg-config --cflags --libs lignum` and run that program too.
# The steps shared with the Fortran install test are in install_common.cmake.
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/install_common.cmake)

lgn_install_setup(run_install_test.cmake)
if(NOT LGN_C_COMPILER)
  set(LGN_C_COMPILER cc)
endif()

# --- (a) install --------------------------------------------------------------
lgn_install()
lgn_expect_files(
  ${LGN_INCDIR}/lignum/lignum.h
  ${LGN_INCDIR}/lignum/lignum_group.h
  ${LGN_INCDIR}/lignum/lignum_joints.h
  ${LGN_INCDIR}/lignum/lignum_bodies.h
  ${LGN_INCDIR}/lignum/lignum_planar.h
  ${LGN_INCDIR}/lignum/lignum_ls.h
  ${LGN_INCDIR}/lignum/lignum_config.h
  ${LGN_INCDIR}/lignum/lignum_export.h
  ${LGN_LIBDIR}/cmake/Lignum/LignumConfig.cmake
  ${LGN_LIBDIR}/cmake/Lignum/LignumConfigVersion.cmake
  ${LGN_LIBDIR}/cmake/Lignum/LignumTargets.cmake
  ${LGN_LIBDIR}/pkgconfig/lignum.pc
  ${LGN_PREFIX}/share/doc/lignum/README.md
  ${LGN_PREFIX}/share/doc/lignum/tutorial.md
  ${LGN_PREFIX}/share/doc/lignum/theory.md
  ${LGN_PREFIX}/share/doc/lignum/conventions.md
  ${LGN_PREFIX}/share/doc/lignum/which-method.md
  ${LGN_PREFIX}/share/doc/lignum/user-guide.md
  ${LGN_PREFIX}/share/doc/lignum/figures/heavy_top_study.png)
file(GLOB _libs ${LGN_LIBDIR}/liblignum.*)
if(NOT _libs)
  message(FATAL_ERROR "[install] no liblignum.* in ${LGN_LIBDIR}")
endif()
# lignum_petsc.h: LGNLinSol_PETSc is exported by the library lignum_petsc
lgn_check_exports(lignum -DLGN_HEADER_DIRS=${LGN_INCDIR}/lignum -DLGN_HEADER_EXCLUDE=lignum_petsc.h)

# --- (b) configure and build the outside project, (c) run it ---------------------
lgn_build_consumer(
  -DCMAKE_C_COMPILER=${LGN_C_COMPILER}
  -DCMAKE_C_FLAGS=${LGN_C_FLAGS}
  -DLIGNUM_EXPECTED_VERSION=${LGN_VERSION})
lgn_run_consumer(lignum_consumer)

# --- (d) pkg-config -------------------------------------------------------------
find_program(_pkgconfig NAMES pkgconf pkg-config NO_CACHE)
if(NOT _pkgconfig)
  message(STATUS "[pkg-config] pkgconf/pkg-config not found: check skipped")
  return()
endif()
set(ENV{PKG_CONFIG_PATH} "${LGN_LIBDIR}/pkgconfig")
lgn_run(pkg-config ${_pkgconfig} --modversion lignum)
string(STRIP "${LGN_LAST_OUTPUT}" _pc_version)
if(NOT _pc_version STREQUAL LGN_VERSION)
  message(FATAL_ERROR "[pkg-config] lignum.pc has version '${_pc_version}', expected '${LGN_VERSION}'")
endif()
lgn_run(pkg-config ${_pkgconfig} --cflags --libs lignum)
string(STRIP "${LGN_LAST_OUTPUT}" _pc_flags)
message(STATUS "[pkg-config] flags: ${_pc_flags}")
if(NOT _pc_flags MATCHES "-llignum" OR NOT _pc_flags MATCHES "-lsundials_nvecserial")
  message(FATAL_ERROR "[pkg-config] unexpected flags: ${_pc_flags}")
endif()
separate_arguments(_pc_flags UNIX_COMMAND "${_pc_flags}")
separate_arguments(_extra_flags UNIX_COMMAND "${LGN_C_FLAGS}")
set(_pc_exe ${LGN_WORK_DIR}/lignum_consumer_pc)
lgn_run(pkg-config-build ${LGN_C_COMPILER} -std=c11 ${_extra_flags}
  "-DLIGNUM_EXPECTED_VERSION=\"${LGN_VERSION}\""
  ${LGN_CONSUMER_SOURCE_DIR}/main.c -o ${_pc_exe} ${_pc_flags}
  -Wl,-rpath,${LGN_LIBDIR})
lgn_run(pkg-config-run ${_pc_exe})
message(STATUS "[pkg-config-run] output:\n${LGN_LAST_OUTPUT}")
