# Driver of the CTest test install_examples (see CMakeLists.txt here): the
# teaching examples installed to share/lignum/examples build against the
# installed package and pass their answer-file tests.
#
#  (a) cmake --install <build dir> --prefix <work>/prefix; the examples'
#      sources, answer files, comparator and CMakeLists.txt are there
#  (b) configure + build <prefix>/share/lignum/examples with
#      -DCMAKE_PREFIX_PATH=<work>/prefix (find_package(Lignum REQUIRED));
#      with LGN_EXAMPLES_FORTRAN (Lignum built with Fortran) the Fortran
#      twins in fortran/ too
#  (c) run pendulum_so3 from that build, then its whole ctest (every example
#      against its answer file)
# LGN_CONSUMER_SOURCE_DIR is set here to the installed examples directory.
cmake_minimum_required(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/install_common.cmake)

lgn_install_setup(run_install_examples_test.cmake LGN_INSTALL_DATADIR)
if(NOT LGN_C_COMPILER)
  set(LGN_C_COMPILER cc)
endif()

# --- (a) install --------------------------------------------------------------
lgn_install()
set(LGN_CONSUMER_SOURCE_DIR ${LGN_PREFIX}/${LGN_INSTALL_DATADIR}/lignum/examples)
set(_files CMakeLists.txt README.md compare_output.c run_and_compare.cmake)
foreach(_ex pendulum_so3 heavy_top chain_klu four_bar slider_crank custom_group
    torque_free_top bouncing_pendulum tutorial_double_pendulum)
  list(APPEND _files ${_ex}.c ${_ex}.out)
endforeach()
list(TRANSFORM _files PREPEND ${LGN_CONSUMER_SOURCE_DIR}/)
lgn_expect_files(${_files})

# --- (b) configure and build the installed examples -------------------------------
# with the Fortran interface, the Fortran twins too (fortran/)
set(_fortran_args "")
if(LGN_EXAMPLES_FORTRAN)
  lgn_expect_files(${LGN_CONSUMER_SOURCE_DIR}/fortran/CMakeLists.txt
    ${LGN_CONSUMER_SOURCE_DIR}/fortran/pendulum_so3_f.f90
    ${LGN_CONSUMER_SOURCE_DIR}/fortran/heavy_top_f.f90)
  set(_fortran_args -DLGN_EXAMPLES_FORTRAN=ON -DCMAKE_Fortran_FLAGS=${LGN_C_FLAGS})
  if(LGN_Fortran_COMPILER)
    list(APPEND _fortran_args -DCMAKE_Fortran_COMPILER=${LGN_Fortran_COMPILER})
  endif()
endif()
lgn_build_consumer(
  -DCMAKE_C_COMPILER=${LGN_C_COMPILER}
  -DCMAKE_C_FLAGS=${LGN_C_FLAGS}
  ${_fortran_args})

# --- (c) run one, then all against their answer files ---------------------------
lgn_run_consumer(pendulum_so3)
get_filename_component(_bindir ${CMAKE_COMMAND} DIRECTORY)
find_program(_ctest ctest HINTS ${_bindir} NO_CACHE REQUIRED)
set(_cmd ${_ctest} --test-dir ${LGN_CONSUMER_BUILD} --output-on-failure)
if(LGN_CONFIG)
  list(APPEND _cmd -C ${LGN_CONFIG})
endif()
lgn_run(examples-ctest ${_cmd})
message(STATUS "[examples-ctest] ${LGN_LAST_OUTPUT}")
