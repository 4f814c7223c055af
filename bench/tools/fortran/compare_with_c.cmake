# Run a C example and its Fortran counterpart at the same options; the
# Fortran program compares its result with the C output (--compare FILE)
# and exits nonzero on a mismatch.
#   cmake -DLGN_C_EXE=... -DLGN_F_EXE=... "-DLGN_ARGS=--h 1e-3 ..."
#         -DLGN_REF_FILE=<C output> -P compare_with_c.cmake
cmake_minimum_required(VERSION 3.25)

foreach(_var LGN_C_EXE LGN_F_EXE LGN_REF_FILE)
  if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
    message(FATAL_ERROR "compare_with_c.cmake: -D${_var}=... is required")
  endif()
endforeach()
separate_arguments(_args UNIX_COMMAND "${LGN_ARGS}")

# The C program writes the reference (its exit status must be 0).
execute_process(COMMAND ${LGN_C_EXE} ${_args}
  OUTPUT_FILE ${LGN_REF_FILE} ERROR_VARIABLE _err RESULT_VARIABLE _rc)
file(READ ${LGN_REF_FILE} _c_out)
message(STATUS "C: ${LGN_C_EXE} ${LGN_ARGS}\n${_c_out}${_err}")
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "the C example failed (${_rc})")
endif()

# The Fortran program checks itself against it.
execute_process(COMMAND ${LGN_F_EXE} ${_args} --compare ${LGN_REF_FILE}
  OUTPUT_VARIABLE _out ERROR_VARIABLE _err RESULT_VARIABLE _rc)
message(STATUS "Fortran: ${LGN_F_EXE} ${LGN_ARGS} --compare ${LGN_REF_FILE}\n${_out}${_err}")
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "the Fortran example failed or differs from C (${_rc})")
endif()
