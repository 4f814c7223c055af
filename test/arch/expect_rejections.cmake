# Runs check_layers.sh on the planted sources and fails unless it exits 1
# and reports each planted violation.
#   cmake -DSCRIPT=... -DDOC=... -DSRC=... -DOBJECTS=a.o;b.o -P expect_rejections.cmake
execute_process(COMMAND sh ${SCRIPT} ${DOC} ${SRC} ${OBJECTS}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "check_layers said:\n${out}${err}")
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "check_layers exited ${rc} on planted violations (expected 1)")
endif()
foreach(expected
    "upward call arch/planted/bottom.c (layer 0) -> arch/planted/top.c (layer 2) through plantTop"
    "circle arch/planted/middle_"
    "arch/planted/pure.c is a pure helper")
  string(FIND "${out}" "${expected}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "check_layers did not report: ${expected}")
  endif()
endforeach()
