# Smoke test of the suite benchmark (cmake -DSUITE=exe -DCSV=file -P this):
# runs andrews, caraxis, top and chain at tol 1e-4, 1e-5, 1e-6 (one run
# each, no figure) and checks the CSV: the exact header, one row per
# problem, method and tol (4 x 7 x 3), every run successful (flag 0) with
# a finite error below 1 and at least one step. Never timing.
set(HEADER "problem,code,method,tol,flag,error,mescd,error_v,energy_drift,steps,rejected,lu,newton_iters,cpu_s,sundials")
if(NOT SUITE OR NOT CSV)
  message(FATAL_ERROR "usage: cmake -DSUITE=suite -DCSV=out.csv -P ${CMAKE_CURRENT_LIST_FILE}")
endif()
file(REMOVE "${CSV}")
execute_process(COMMAND "${SUITE}" --problems andrews,caraxis,top,chain --tol-max 1e-4
                        --tol-min 1e-6 --reps 1 --no-png --csv "${CSV}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "suite failed: ${rc}")
endif()
file(STRINGS "${CSV}" lines)
list(LENGTH lines n)
list(GET lines 0 first)
if(NOT first STREQUAL HEADER)
  message(FATAL_ERROR "${CSV}: header is\n  ${first}\nexpected\n  ${HEADER}")
endif()
math(EXPR nrows "${n} - 1")
if(NOT nrows EQUAL 84)
  message(FATAL_ERROR "${CSV}: ${nrows} rows, expected 84 (4 problems x 7 methods x 3 tol)")
endif()
list(REMOVE_AT lines 0)
foreach(line IN LISTS lines)
  string(REPLACE "," ";" f "${line}")
  list(GET f 4 flag)
  list(GET f 5 err)
  list(GET f 9 steps)
  if(NOT flag STREQUAL "0" OR err MATCHES "nan|inf" OR NOT err LESS 1.0 OR NOT steps GREATER 0)
    message(FATAL_ERROR "${CSV}: a failed or wrong run:\n  ${line}")
  endif()
endforeach()
message(STATUS "${CSV}: ${nrows} runs, all successful")
