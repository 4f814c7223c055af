# Tests of programs across MPI ranks (test/mpi, test/petsc, the example
# tops_on_ranks):
#
#   lgn_add_rank_tests(<prefix> <target> <label>)
#     <prefix>_np1 runs <target> without mpiexec (one rank), <prefix>_np2
#     and <prefix>_np4 under mpiexec (when MPIEXEC_EXECUTABLE is found and
#     the count is at most LGN_RANK_TEST_MAX_NP, below); the properties of
#     lgn_rank_test_properties.
#   LGN_RANK_TEST_MAX_NP (cache option): the largest number of ranks a test
#     runs on: 1, 2 or 4. Default 4 on a machine with at least 4 logical
#     cores, else 2, and 2 in the sanitizer builds. Ranks beyond the cores
#     wait for each other's collectives through the scheduler, so their
#     time is the machine's load, not their work: at load 19 on 2 cores
#     mpi_ranks took 1.4 s on one rank, 102 s on two and 247 s on four
#     (Release). The 4-rank runs test the same code paths as the 2-rank
#     runs (a rank with neighbours on both sides needs 3); pass
#     -DLGN_RANK_TEST_MAX_NP=4 to run them on a small machine.
#   lgn_rank_test_properties(<label> <tests...>)
#     Open MPI refuses to run as root unless told (the variables below
#     allow it and change nothing for other users) and --oversubscribe lets
#     4 ranks run on fewer cores; ranks waiting in a collective yield the
#     core; the tests run alone (RUN_SERIAL: beside other tests petsc_ls_np4,
#     3 s alone, once passed its 240-second timeout and petsc_ls_np2 took
#     118 s under ASan); LeakSanitizer is off, as it reports Open MPI's own
#     allocations in plugins it unloads again (no suppression can name
#     them), every other check of ASan and UBSan stays on.
#   LGN_MPIEXEC_FLAGS: MPIEXEC_PREFLAGS, and --oversubscribe for Open MPI.
#   LGN_RANK_TEST_TIMEOUT: 600 s, 900 s in the sanitizer builds. On 2 and 4
#     ranks these tests wait on each other's collectives, and their time is
#     the machine's load, not their work: on a loaded 2-core machine
#     mpi_ranks took 2.8 s on one rank, 56 s on two and 135 s on four,
#     mpi_chain 6.9, 81 and 178 s, in the Release build; under ASan three of
#     them passed 240 s (issue 31), and mpi_ranks_np2 at load 22 used 16 s
#     of CPU per rank in 900 s, and mpi_ranks_np4 passed 240 s in the
#     Release build. The sanitizer builds therefore run 1 and 2 ranks (the
#     same code paths; 4 ranks run in the Release build).

set(LGN_MPIEXEC_FLAGS ${MPIEXEC_PREFLAGS})
if(MPIEXEC_EXECUTABLE)
  execute_process(COMMAND ${MPIEXEC_EXECUTABLE} --version
    OUTPUT_VARIABLE _lgn_mpiexec_version ERROR_QUIET)
  if(_lgn_mpiexec_version MATCHES "Open MPI|OpenRTE")
    list(APPEND LGN_MPIEXEC_FLAGS --oversubscribe)
  endif()
endif()

if(LGN_ENABLE_SANITIZERS OR LGN_ENABLE_TSAN)
  set(LGN_RANK_TEST_TIMEOUT 900)
else()
  set(LGN_RANK_TEST_TIMEOUT 600)
endif()

function(lgn_rank_test_properties label)
  set_tests_properties(${ARGN} PROPERTIES
    LABELS "${label}"
    TIMEOUT ${LGN_RANK_TEST_TIMEOUT}
    RUN_SERIAL TRUE
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1;OMPI_MCA_mpi_yield_when_idle=1;ASAN_OPTIONS=detect_leaks=0")
endfunction()

cmake_host_system_information(RESULT _lgn_host_cores QUERY NUMBER_OF_LOGICAL_CORES)
if(LGN_ENABLE_SANITIZERS OR LGN_ENABLE_TSAN OR _lgn_host_cores LESS 4)
  set(_lgn_default_max_np 2)
else()
  set(_lgn_default_max_np 4)
endif()
set(LGN_RANK_TEST_MAX_NP ${_lgn_default_max_np} CACHE STRING
  "Largest number of MPI ranks a test runs on (1, 2 or 4)")
set_property(CACHE LGN_RANK_TEST_MAX_NP PROPERTY STRINGS 1 2 4)
if(NOT LGN_RANK_TEST_MAX_NP MATCHES "^(1|2|4)$")
  message(FATAL_ERROR "LGN_RANK_TEST_MAX_NP must be 1, 2 or 4 (got '${LGN_RANK_TEST_MAX_NP}')")
endif()

function(lgn_add_rank_tests prefix target label)
  add_test(NAME ${prefix}_np1 COMMAND ${target})
  set(_tests ${prefix}_np1)
  set(_nps)
  foreach(_np 2 4)
    if(NOT _np GREATER LGN_RANK_TEST_MAX_NP)
      list(APPEND _nps ${_np})
    endif()
  endforeach()
  if(MPIEXEC_EXECUTABLE)
    foreach(_np ${_nps})
      add_test(NAME ${prefix}_np${_np}
        COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${_np} ${LGN_MPIEXEC_FLAGS}
                $<TARGET_FILE:${target}> ${MPIEXEC_POSTFLAGS})
      list(APPEND _tests ${prefix}_np${_np})
    endforeach()
  endif()
  lgn_rank_test_properties("${label}" ${_tests})
endfunction()
