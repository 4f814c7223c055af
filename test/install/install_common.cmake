# The steps shared by the install tests (run_install_test.cmake for C,
# run_install_fortran_test.cmake for Fortran), included by both:
#
#   lgn_install_setup(<script> <required vars...>)
#       check the -D variables, make a fresh work directory and set
#       LGN_PREFIX, LGN_LIBDIR, LGN_INCDIR, LGN_CONSUMER_BUILD;
#   lgn_run(<step> <command...>)
#       run a command, echo it, stop with its output on failure; its
#       standard output is left in LGN_LAST_OUTPUT, its standard error in
#       LGN_LAST_ERROR;
#   lgn_install()
#       cmake --install <LGN_BUILD_DIR> --prefix <LGN_PREFIX>;
#   lgn_expect_files(<files...>)
#       stop unless every file exists;
#   lgn_build_consumer(<configure arguments...>)
#       configure LGN_CONSUMER_SOURCE_DIR against LGN_PREFIX
#       (CMAKE_PREFIX_PATH) with the generator, make program and build type
#       of Lignum's build, then build it; what the configuration printed
#       (standard output and error: CMake warnings go to the latter) is
#       left in LGN_CONFIGURE_OUTPUT;
#   lgn_run_consumer(<executable name> <arguments...>)
#       find the executable in the consumer build and run it;
#   lgn_check_exports(<library> <check_exports.cmake arguments...>)
#       if <library> is installed as a shared library (lib<library>.so) and
#       LGN_NM and LGN_CHECK_EXPORTS are given: check what it exports
#       (test/symbols/check_exports.cmake).
#
# Common -D variables: LGN_BUILD_DIR, LGN_WORK_DIR, LGN_CONSUMER_SOURCE_DIR,
# LGN_INSTALL_LIBDIR, LGN_INSTALL_INCLUDEDIR, LGN_VERSION (required), and
# LGN_CONFIG, LGN_GENERATOR, LGN_MAKE_PROGRAM, LGN_NM, LGN_CHECK_EXPORTS
# (optional).

# Check the required -D variables and start from an empty work directory.
function(lgn_install_setup script)
  foreach(_var LGN_BUILD_DIR LGN_WORK_DIR LGN_CONSUMER_SOURCE_DIR
               LGN_INSTALL_LIBDIR LGN_INSTALL_INCLUDEDIR LGN_VERSION ${ARGN})
    if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
      message(FATAL_ERROR "${script}: -D${_var}=... is required")
    endif()
  endforeach()
  file(REMOVE_RECURSE ${LGN_WORK_DIR})
  file(MAKE_DIRECTORY ${LGN_WORK_DIR})
  set(LGN_PREFIX ${LGN_WORK_DIR}/prefix PARENT_SCOPE)
  set(LGN_LIBDIR ${LGN_WORK_DIR}/prefix/${LGN_INSTALL_LIBDIR} PARENT_SCOPE)
  set(LGN_INCDIR ${LGN_WORK_DIR}/prefix/${LGN_INSTALL_INCLUDEDIR} PARENT_SCOPE)
  set(LGN_CONSUMER_BUILD ${LGN_WORK_DIR}/consumer-build PARENT_SCOPE)
endfunction()

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
  set(LGN_LAST_ERROR "${_err}" PARENT_SCOPE)
endfunction()

# Install the build tree into the scratch prefix.
function(lgn_install)
  set(_cmd ${CMAKE_COMMAND} --install ${LGN_BUILD_DIR} --prefix ${LGN_PREFIX})
  if(LGN_CONFIG)
    list(APPEND _cmd --config ${LGN_CONFIG})
  endif()
  lgn_run(install ${_cmd})
endfunction()

# Stop unless every file exists.
function(lgn_expect_files)
  foreach(_file IN LISTS ARGN)
    if(NOT EXISTS ${_file})
      message(FATAL_ERROR "[install] missing installed file ${_file}")
    endif()
  endforeach()
endfunction()

# Configure the outside project against the prefix, then build it; the
# configure output (stdout and stderr) is left in LGN_CONFIGURE_OUTPUT.
function(lgn_build_consumer)
  set(_cmd ${CMAKE_COMMAND}
    -S ${LGN_CONSUMER_SOURCE_DIR} -B ${LGN_CONSUMER_BUILD}
    -DCMAKE_PREFIX_PATH=${LGN_PREFIX} ${ARGN})
  if(LGN_GENERATOR)
    list(APPEND _cmd -G ${LGN_GENERATOR})
  endif()
  if(LGN_MAKE_PROGRAM)
    list(APPEND _cmd -DCMAKE_MAKE_PROGRAM=${LGN_MAKE_PROGRAM})
  endif()
  if(LGN_CONFIG)
    list(APPEND _cmd -DCMAKE_BUILD_TYPE=${LGN_CONFIG})
  endif()
  lgn_run(consumer-configure ${_cmd})
  set(LGN_CONFIGURE_OUTPUT "${LGN_LAST_OUTPUT}${LGN_LAST_ERROR}" PARENT_SCOPE)

  set(_cmd ${CMAKE_COMMAND} --build ${LGN_CONSUMER_BUILD})
  if(LGN_CONFIG)
    list(APPEND _cmd --config ${LGN_CONFIG})
  endif()
  lgn_run(consumer-build ${_cmd})
endfunction()

# Find the consumer's executable and run it with the given arguments.
function(lgn_run_consumer name)
  find_program(_exe ${name}
    PATHS ${LGN_CONSUMER_BUILD} ${LGN_CONSUMER_BUILD}/${LGN_CONFIG}
    NO_DEFAULT_PATH NO_CACHE)
  if(NOT _exe)
    message(FATAL_ERROR "[consumer-run] ${name} not found in ${LGN_CONSUMER_BUILD}")
  endif()
  lgn_run(consumer-run ${_exe} ${ARGN})
  message(STATUS "[consumer-run] output:\n${LGN_LAST_OUTPUT}")
endfunction()

# Check the exports of an installed shared library (skipped for a static one).
function(lgn_check_exports library)
  set(_lib ${LGN_LIBDIR}/lib${library}.so)
  if(NOT EXISTS ${_lib})
    message(STATUS "[exports] ${_lib} not installed (static build): check skipped")
    return()
  endif()
  if(NOT LGN_NM OR NOT LGN_CHECK_EXPORTS)
    message(STATUS "[exports] no nm: check skipped")
    return()
  endif()
  lgn_run(exports ${CMAKE_COMMAND} -DLGN_NM=${LGN_NM} -DLGN_LIBRARY=${_lib} ${ARGN}
    -P ${LGN_CHECK_EXPORTS})
  message(STATUS "[exports] ${LGN_LAST_OUTPUT}")
endfunction()
