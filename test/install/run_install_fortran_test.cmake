# Driver of the CTest test install_find_package_fortran (see CMakeLists.txt
# here); the Fortran counterpart of run_install_test.cmake.
#
#  (a) cmake --install <build dir> --prefix <work>/prefix
#      and check the library, the .mod files and the package files; with
#      LGN_FORTRAN_MODULE_SOURCES, that liblignum_fortran.so exports only
#      its modules' entities and FLGN* helpers (check_exports.cmake)
#  (b) configure + build test/install/consumer_fortran with
#      -DCMAKE_PREFIX_PATH=<work>/prefix
#      (find_package(Lignum REQUIRED COMPONENTS Fortran)); no CMake warning
#  (c) run it
# The steps shared with the C install test are in install_common.cmake.
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/install_common.cmake)

lgn_install_setup(run_install_fortran_test.cmake LGN_Fortran_COMPILER)

# --- (a) install --------------------------------------------------------------
lgn_install()
set(_moddir ${LGN_INCDIR}/lignum/fortran)
set(_files
  ${_moddir}/flignum_mod.mod
  ${_moddir}/flignum_joints_mod.mod
  ${_moddir}/flignum_bodies_mod.mod
  ${_moddir}/flignum_planar_mod.mod
  ${_moddir}/flignum_sundials_mod.mod
  ${LGN_LIBDIR}/cmake/Lignum/LignumConfig.cmake
  ${LGN_LIBDIR}/cmake/Lignum/LignumTargets.cmake)
if(LGN_ENABLE_KLU)
  list(APPEND _files ${_moddir}/flignum_klu_mod.mod)
endif()
lgn_expect_files(${_files})
file(GLOB _libs ${LGN_LIBDIR}/liblignum_fortran.*)
if(NOT _libs)
  message(FATAL_ERROR "[install] no liblignum_fortran.* in ${LGN_LIBDIR}")
endif()
if(LGN_FORTRAN_MODULE_SOURCES)
  lgn_check_exports(lignum_fortran -DLGN_FORTRAN=ON
    -DLGN_C_LIBRARY=${LGN_LIBDIR}/liblignum.so
    "-DLGN_FORTRAN_SOURCES=${LGN_FORTRAN_MODULE_SOURCES}")
endif()

# --- (b) configure and build the outside project, (c) run it ---------------------
lgn_build_consumer(
  -DCMAKE_Fortran_COMPILER=${LGN_Fortran_COMPILER}
  -DCMAKE_Fortran_FLAGS=${LGN_EXTRA_FLAGS})
if(LGN_CONFIGURE_OUTPUT MATCHES "CMake Warning")
  message(FATAL_ERROR "[consumer-configure] warnings:\n${LGN_CONFIGURE_OUTPUT}")
endif()
lgn_run_consumer(lignum_consumer_fortran ${LGN_VERSION})
