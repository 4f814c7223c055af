# Every public function and callback type of the Lignum headers has a
# binding in one of the Fortran modules:
#  - a function LGNxxx( declared in a header -> an interface with
#    bind(c, name="LGNxxx") in a module, or bind(c, name="FLGNxxx") for a
#    C shim of the Fortran interface (an MPI_Comm taken as a Fortran handle);
#  - a callback typedef (*LGNxxxFn)( -> an abstract interface LGNxxxFn.
#   cmake "-DLGN_HEADERS=a.h|b.h" "-DLGN_MODULES=flignum_mod.f90|x.f90"
#         -P check_api_coverage.cmake
# Each header must declare at least one function (else its parsing broke).
cmake_minimum_required(VERSION 3.25)

string(REPLACE "|" ";" _headers "${LGN_HEADERS}")
string(REPLACE "|" ";" _modules "${LGN_MODULES}")
if(NOT _headers OR NOT _modules)
  message(FATAL_ERROR "check_api_coverage.cmake: -DLGN_HEADERS=... and -DLGN_MODULES=... are required")
endif()
set(_module "")
foreach(_m IN LISTS _modules)
  file(READ ${_m} _text)
  string(APPEND _module "${_text}\n")
endforeach()
string(TOLOWER "${_module}" _module_lc)

set(_nfun 0)
set(_ntype 0)
set(_missing "")
foreach(_h IN LISTS _headers)
  file(READ ${_h} _text)
  # drop comments: /* ... */ (non-greedy via a character class) and // ...
  string(REGEX REPLACE "/\\*([^*]|\\*+[^*/])*\\*+/" "" _text "${_text}")
  # functions: a name followed by "(" at the start of a declarator
  string(REGEX MATCHALL "[ *\n](LGN[A-Za-z0-9_]*)\\(" _calls "${_text}")
  list(LENGTH _calls _nh)
  get_filename_component(_hname ${_h} NAME)
  message(STATUS "${_hname}: ${_nh} functions")
  if(_nh EQUAL 0)
    message(FATAL_ERROR "no function found in ${_h}: is the header parsing broken?")
  endif()
  foreach(_c IN LISTS _calls)
    string(REGEX REPLACE "^.(LGN[A-Za-z0-9_]*)\\($" "\\1" _name "${_c}")
    math(EXPR _nfun "${_nfun} + 1")
    string(FIND "${_module}" "name=\"${_name}\"" _pos)
    if(_pos EQUAL -1)
      # a C shim FLGNxxx bound instead (an MPI_Comm argument taken as the
      # Fortran handle: fortran/flignum_mpi_shim.c, flignum_petsc_shim.c)
      string(FIND "${_module}" "name=\"F${_name}\"" _pos)
    endif()
    if(_pos EQUAL -1)
      list(APPEND _missing "function ${_name} (${_hname})")
    endif()
  endforeach()
  # callback types: typedef ... (*LGNxxxFn)(
  string(REGEX MATCHALL "\\(\\*(LGN[A-Za-z0-9_]*)\\)\\(" _types "${_text}")
  foreach(_t IN LISTS _types)
    string(REGEX REPLACE "^\\(\\*(LGN[A-Za-z0-9_]*)\\)\\($" "\\1" _name "${_t}")
    math(EXPR _ntype "${_ntype} + 1")
    string(TOLOWER "${_name}" _name_lc)
    string(REGEX MATCH "(function|subroutine) ${_name_lc}\\(" _found "${_module_lc}")
    if(NOT _found)
      list(APPEND _missing "callback type ${_name} (${_hname})")
    endif()
  endforeach()
endforeach()

message(STATUS "${_nfun} functions and ${_ntype} callback types in the headers")
if(_nfun LESS 60 OR _ntype LESS 8)
  message(FATAL_ERROR "too few declarations found: is the header parsing broken?")
endif()
string(REPLACE ";" ", " _mod_list "${_modules}")
if(_missing)
  string(REPLACE ";" "\n  " _list "${_missing}")
  message(FATAL_ERROR "not bound in ${_mod_list}:\n  ${_list}")
endif()
message(STATUS "all bound in ${_mod_list}")
