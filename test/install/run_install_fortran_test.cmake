# Driver of the CTest test install_find_package_fortran (see CMakeLists.txt
# here); the Fortran counterpart of run_install_test.cmake.
#
#  (a) cmake --install <build dir> --prefix <work>/prefix
#      and check the library, the .mod files and the package files
#  (b) configure + build test/install/consumer_fortran with
#      -DCMAKE_PREFIX_PATH=<work>/prefix
#      (find_package(Lignum REQUIRED COMPONENTS Fortran))
#  (c) run it
cmake_minimum_required(VERSION 3.25)

foreach(_var LGN_BUILD_DIR LGN_WORK_DIR LGN_CONSUMER_SOURCE_DIR
             LGN_INSTALL_LIBDIR LGN_INSTALL_INCLUDEDIR LGN_VERSION
             LGN_Fortran_COMPILER)
  if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
    message(FATAL_ERROR "run_install_fortran_test.cmake: -D${_var}=... is required")
  endif()
endforeach()
set(_prefix ${LGN_WORK_DIR}/prefix)
set(_consumer_build ${LGN_WORK_DIR}/consumer-build)
file(REMOVE_RECURSE ${LGN_WORK_DIR})
file(MAKE_DIRECTORY ${LGN_WORK_DIR})

# Run a command, echo it, stop with its output on failure.
function(lgn_run step)
  string(REPLACE ";" " " _pretty "${ARGN}")
  message(STATUS "[${step}] ${_pretty}")
  execute_process(COMMAND ${ARGN}
    RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _err)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "[${step}] failed (${_rc}):\n${_out}\n${_err}")
  endif()
  set(LGN_LAST_OUTPUT "${_out}" PARENT_SCOPE)
endfunction()

# --- (a) install --------------------------------------------------------------
set(_install_cmd ${CMAKE_COMMAND} --install ${LGN_BUILD_DIR} --prefix ${_prefix})
if(LGN_CONFIG)
  list(APPEND _install_cmd --config ${LGN_CONFIG})
endif()
lgn_run(install ${_install_cmd})

set(_libdir ${_prefix}/${LGN_INSTALL_LIBDIR})
set(_moddir ${_prefix}/${LGN_INSTALL_INCLUDEDIR}/lignum/fortran)
set(_files
    ${_moddir}/flignum_mod.mod
    ${_moddir}/flignum_joints_mod.mod
    ${_moddir}/flignum_sundials_mod.mod
    ${_libdir}/cmake/Lignum/LignumConfig.cmake
    ${_libdir}/cmake/Lignum/LignumTargets.cmake)
if(LGN_ENABLE_KLU)
  list(APPEND _files ${_moddir}/flignum_klu_mod.mod)
endif()
foreach(_file IN LISTS _files)
  if(NOT EXISTS ${_file})
    message(FATAL_ERROR "[install] missing installed file ${_file}")
  endif()
endforeach()
file(GLOB _libs ${_libdir}/liblignum_fortran.*)
if(NOT _libs)
  message(FATAL_ERROR "[install] no liblignum_fortran.* in ${_libdir}")
endif()

# --- (b) configure and build the outside project ---------------------------------
set(_configure_cmd ${CMAKE_COMMAND}
  -S ${LGN_CONSUMER_SOURCE_DIR} -B ${_consumer_build}
  -DCMAKE_PREFIX_PATH=${_prefix}
  -DCMAKE_Fortran_COMPILER=${LGN_Fortran_COMPILER}
  -DCMAKE_Fortran_FLAGS=${LGN_EXTRA_FLAGS})
if(LGN_GENERATOR)
  list(APPEND _configure_cmd -G ${LGN_GENERATOR})
endif()
if(LGN_MAKE_PROGRAM)
  list(APPEND _configure_cmd -DCMAKE_MAKE_PROGRAM=${LGN_MAKE_PROGRAM})
endif()
if(LGN_CONFIG)
  list(APPEND _configure_cmd -DCMAKE_BUILD_TYPE=${LGN_CONFIG})
endif()
lgn_run(consumer-configure ${_configure_cmd})
if(LGN_LAST_OUTPUT MATCHES "CMake Warning")
  message(FATAL_ERROR "[consumer-configure] warnings:\n${LGN_LAST_OUTPUT}")
endif()

set(_build_cmd ${CMAKE_COMMAND} --build ${_consumer_build})
if(LGN_CONFIG)
  list(APPEND _build_cmd --config ${LGN_CONFIG})
endif()
lgn_run(consumer-build ${_build_cmd})

# --- (c) run it -----------------------------------------------------------------
find_program(_exe lignum_consumer_fortran
  PATHS ${_consumer_build} ${_consumer_build}/${LGN_CONFIG}
  NO_DEFAULT_PATH NO_CACHE)
if(NOT _exe)
  message(FATAL_ERROR "[consumer-run] lignum_consumer_fortran not found in ${_consumer_build}")
endif()
lgn_run(consumer-run ${_exe} ${LGN_VERSION})
message(STATUS "[consumer-run] output:\n${LGN_LAST_OUTPUT}")
