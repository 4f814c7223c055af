# Runs check_owners.sh on the planted sources and fails unless it exits 1,
# reports each planted write by a file that does not own the sub-record,
# and reports nothing else (the owner's writes, reads, comparisons,
# comments and strings are no violations).
#   cmake -DSCRIPT=... -DDOC=... -DSRC=... -P expect_owner_rejections.cmake
execute_process(COMMAND sh ${SCRIPT} ${DOC} ${SRC}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "check_owners said:\n${out}${err}")
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "check_owners exited ${rc} on planted violations (expected 1)")
endif()
set(expected
    "intruder.c:5 writes ->ec.hnext; the owners of ec are root_owner.c"
    "intruder.c:6 writes ->rt.nge; the owners of rt are root_owner.c"
    "intruder.c:7 writes ->rt.glo; the owners of rt are root_owner.c")
foreach(e ${expected})
  string(FIND "${out}" "${e}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "check_owners did not report: ${e}")
  endif()
endforeach()
string(REGEX MATCHALL "check_owners: [^\n]*writes" lines "${out}")
list(LENGTH lines n)
if(NOT n EQUAL 3)
  message(FATAL_ERROR "check_owners reported ${n} writes, expected the 3 planted ones")
endif()
