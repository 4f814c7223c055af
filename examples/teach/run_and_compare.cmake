# Run a teaching example and compare its standard output with its answer
# file (compare_output: numbers field by field, |a - b| <= atol + rtol |b|,
# other text equal), as SUNDIALS' examples are tested.
#
#   cmake -DEXE=<example> -DCOMPARE=<compare_output> -DANSWER=<name>.out
#         -DOUTPUT=<file to write> [-DRTOL=1e-5] [-DATOL=1e-6]
#         [-DLAUNCH="mpiexec|-n|2"] [-DARGS="--a|1"] -P run_and_compare.cmake
#
# The example must exit with 0; its output is kept in OUTPUT (to refresh an
# answer file, copy it over <name>.out after checking it).
cmake_minimum_required(VERSION 3.16)
foreach(_var EXE COMPARE ANSWER OUTPUT)
  if(NOT DEFINED ${_var})
    message(FATAL_ERROR "run_and_compare.cmake: -D${_var}=... is required")
  endif()
endforeach()
if(NOT DEFINED RTOL)
  set(RTOL 1e-5)
endif()
if(NOT DEFINED ATOL)
  set(ATOL 1e-6)
endif()
# LAUNCH: a launcher and its arguments separated by '|' (mpiexec|-n|2)
set(_launch "")
if(DEFINED LAUNCH AND NOT LAUNCH STREQUAL "")
  string(REPLACE "|" ";" _launch "${LAUNCH}")
endif()
# ARGS: the example's arguments separated by '|'
set(_args "")
if(DEFINED ARGS AND NOT ARGS STREQUAL "")
  string(REPLACE "|" ";" _args "${ARGS}")
endif()
execute_process(COMMAND ${_launch} ${EXE} ${_args} RESULT_VARIABLE _rc OUTPUT_FILE ${OUTPUT} ERROR_VARIABLE _err)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "${EXE} failed (${_rc}):\n${_err}")
endif()
execute_process(COMMAND ${COMPARE} ${OUTPUT} ${ANSWER} ${RTOL} ${ATOL}
  RESULT_VARIABLE _rc OUTPUT_VARIABLE _out)
message("${_out}")
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "${OUTPUT} differs from ${ANSWER}")
endif()
