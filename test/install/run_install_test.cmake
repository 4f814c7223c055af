# Driver of the CTest test install_find_package (see CMakeLists.txt here).
# Run as: cmake -DLGN_BUILD_DIR=... -DLGN_WORK_DIR=... -P run_install_test.cmake
#
#  (a) cmake --install <build dir> --prefix <work>/prefix
#  (b) configure + build test/install/consumer with
#      -DCMAKE_PREFIX_PATH=<work>/prefix (find_package(Lignum REQUIRED))
#  (c) run it
#  (d) if pkg-config (pkgconf) is found: compile main.c with the flags of
#      `pkg-config --cflags --libs lignum` and run that program too.
cmake_minimum_required(VERSION 3.25)

foreach(_var LGN_BUILD_DIR LGN_WORK_DIR LGN_CONSUMER_SOURCE_DIR
             LGN_INSTALL_LIBDIR LGN_INSTALL_INCLUDEDIR LGN_VERSION)
  if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
    message(FATAL_ERROR "run_install_test.cmake: -D${_var}=... is required")
  endif()
endforeach()
if(NOT LGN_C_COMPILER)
  set(LGN_C_COMPILER cc)
endif()

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
set(_incdir ${_prefix}/${LGN_INSTALL_INCLUDEDIR})
foreach(_file
    ${_incdir}/lignum/lignum.h
    ${_incdir}/lignum/lignum_group.h
    ${_incdir}/lignum/lignum_config.h
    ${_libdir}/cmake/Lignum/LignumConfig.cmake
    ${_libdir}/cmake/Lignum/LignumConfigVersion.cmake
    ${_libdir}/cmake/Lignum/LignumTargets.cmake
    ${_libdir}/pkgconfig/lignum.pc)
  if(NOT EXISTS ${_file})
    message(FATAL_ERROR "[install] missing installed file ${_file}")
  endif()
endforeach()
file(GLOB _libs ${_libdir}/liblignum.*)
if(NOT _libs)
  message(FATAL_ERROR "[install] no liblignum.* in ${_libdir}")
endif()

# --- (b) configure and build the outside project ---------------------------------
set(_configure_cmd ${CMAKE_COMMAND}
  -S ${LGN_CONSUMER_SOURCE_DIR} -B ${_consumer_build}
  -DCMAKE_PREFIX_PATH=${_prefix}
  -DCMAKE_C_COMPILER=${LGN_C_COMPILER}
  -DCMAKE_C_FLAGS=${LGN_C_FLAGS}
  -DLIGNUM_EXPECTED_VERSION=${LGN_VERSION})
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

set(_build_cmd ${CMAKE_COMMAND} --build ${_consumer_build})
if(LGN_CONFIG)
  list(APPEND _build_cmd --config ${LGN_CONFIG})
endif()
lgn_run(consumer-build ${_build_cmd})

# --- (c) run it -----------------------------------------------------------------
find_program(_exe lignum_consumer
  PATHS ${_consumer_build} ${_consumer_build}/${LGN_CONFIG}
  NO_DEFAULT_PATH NO_CACHE)
if(NOT _exe)
  message(FATAL_ERROR "[consumer-run] lignum_consumer not found in ${_consumer_build}")
endif()
lgn_run(consumer-run ${_exe})
message(STATUS "[consumer-run] output:\n${LGN_LAST_OUTPUT}")

# --- (d) pkg-config -------------------------------------------------------------
find_program(_pkgconfig NAMES pkgconf pkg-config NO_CACHE)
if(NOT _pkgconfig)
  message(STATUS "[pkg-config] pkgconf/pkg-config not found: check skipped")
  return()
endif()
set(ENV{PKG_CONFIG_PATH} "${_libdir}/pkgconfig")
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
  -Wl,-rpath,${_libdir})
lgn_run(pkg-config-run ${_pc_exe})
message(STATUS "[pkg-config-run] output:\n${LGN_LAST_OUTPUT}")
