# The dynamic symbols a Lignum library exports (nm -D --defined-only) are
# its public interface and nothing else.
#
#   cmake -DLGN_NM=nm -DLGN_LIBRARY=liblignum.so
#         "-DLGN_HEADER_DIRS=include/lignum|build/include/lignum"
#         ["-DLGN_HEADER_EXCLUDE=lignum_petsc.h|..."] -P check_exports.cmake
#       liblignum: every exported symbol is a function declared in the
#       public headers (*.h of LGN_HEADER_DIRS), every declared function is
#       exported, and all of them start with LGN. Each declaration must carry
#       LGN_EXPORT (the number of LGN_EXPORTs is checked against the number
#       of declarations found, which also guards the parsing). The headers
#       named in LGN_HEADER_EXCLUDE (whose functions another library
#       exports, e.g. lignum_petsc.h: lignum_petsc) are not read.
#
#   cmake -DLGN_NM=nm -DLGN_LIBRARY=liblignum_fortran.so -DLGN_FORTRAN=ON
#         "-DLGN_FORTRAN_SOURCES=a.f90|b.f90" [-DLGN_C_LIBRARY=liblignum.so]
#         -P check_exports.cmake
#       liblignum_fortran (gfortran's name mangling): every exported symbol
#       is an entity of one of the modules of LGN_FORTRAN_SOURCES
#       (__<module>_MOD_<name>: module procedures and the compiler's
#       helpers of derived types) or a C helper named FLGN* that the modules
#       bind to with bind(C, name="FLGN..."). Every such FLGN* name is
#       exported, and with LGN_C_LIBRARY every LGN* name the modules bind to
#       is exported by liblignum.
#
# Header declarations are recognised as `name(` outside comments and
# preprocessor lines; function pointer declarators (*name)( are not
# functions.
cmake_minimum_required(VERSION 3.25)

foreach(_var LGN_NM LGN_LIBRARY)
  if(NOT ${_var})
    message(FATAL_ERROR "check_exports.cmake: -D${_var}=... is required")
  endif()
endforeach()

# Names the toolchain may put into any shared library's dynamic symbol table.
set(_lgn_toolchain_symbols _init _fini _edata _end __bss_start)

# The defined dynamic symbols of a library, in <out>.
function(lgn_exported_symbols lib out)
  if(NOT EXISTS "${lib}")
    message(FATAL_ERROR "check_exports.cmake: no library ${lib}")
  endif()
  execute_process(COMMAND ${LGN_NM} -D --defined-only "${lib}"
    RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _err)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "${LGN_NM} -D --defined-only ${lib} failed (${_rc}):\n${_err}")
  endif()
  string(REGEX REPLACE "\n$" "" _out "${_out}")
  string(REPLACE "\n" ";" _lines "${_out}")
  set(_syms "")
  foreach(_line IN LISTS _lines)
    # "<address> <type> <name>[@version]"
    if(_line MATCHES "^[0-9a-fA-F]* *[A-Za-z] ([^ @]+)")
      set(_name "${CMAKE_MATCH_1}")
      if(NOT _name IN_LIST _lgn_toolchain_symbols)
        list(APPEND _syms "${_name}")
      endif()
    endif()
  endforeach()
  list(REMOVE_DUPLICATES _syms)
  set(${out} "${_syms}" PARENT_SCOPE)
endfunction()

# Report the list <var> (if not empty) under <title>, and count a failure.
set(_lgn_failures 0)
macro(lgn_report var title)
  if(${var})
    list(SORT ${var})
    string(REPLACE ";" "\n  " _lgn_text "${${var}}")
    message(SEND_ERROR "${title}:\n  ${_lgn_text}")
    math(EXPR _lgn_failures "${_lgn_failures} + 1")
  endif()
endmacro()

lgn_exported_symbols("${LGN_LIBRARY}" _exported)
list(LENGTH _exported _nexported)
get_filename_component(_libname "${LGN_LIBRARY}" NAME)

if(NOT LGN_FORTRAN)
  # --- liblignum and the public headers -----------------------------------
  if(NOT LGN_HEADER_DIRS)
    message(FATAL_ERROR "check_exports.cmake: -DLGN_HEADER_DIRS=... is required")
  endif()
  string(REPLACE "|" ";" _dirs "${LGN_HEADER_DIRS}")
  string(REPLACE "|" ";" _lgn_exclude "${LGN_HEADER_EXCLUDE}")
  set(_declared "")
  set(_nmarked 0)
  foreach(_dir IN LISTS _dirs)
    file(GLOB _headers "${_dir}/*.h")
    foreach(_h IN LISTS _headers)
      # headers of another library's functions
      get_filename_component(_hname "${_h}" NAME)
      if(_hname IN_LIST _lgn_exclude)
        continue()
      endif()
      file(READ "${_h}" _text)
      # comments, line continuations, then preprocessor lines
      string(REGEX REPLACE "/\\*([^*]|\\*+[^*/])*\\*+/" " " _text "${_text}")
      string(REGEX REPLACE "//[^\n]*" "" _text "${_text}")
      string(REGEX REPLACE "\\\\\n" " " _text "${_text}")
      string(REGEX REPLACE "(^|\n)[ \t]*#[^\n]*" "\\1" _text "${_text}")
      # function pointers: "(*name)(" is no function declaration
      string(REGEX REPLACE "\\([ \t]*\\*[ \t]*[A-Za-z0-9_]*[ \t]*\\)[ \t\n]*\\(" "; (" _text "${_text}")
      string(REGEX MATCHALL "[A-Za-z_][A-Za-z0-9_]*[ \t\n]*\\(" _decls "${_text}")
      foreach(_d IN LISTS _decls)
        string(REGEX REPLACE "[ \t\n]*\\($" "" _d "${_d}")
        list(APPEND _declared "${_d}")
      endforeach()
      string(REGEX MATCHALL "(^|[^A-Za-z0-9_])LGN_EXPORT[^A-Za-z0-9_]" _marks "${_text}")
      list(LENGTH _marks _n)
      math(EXPR _nmarked "${_nmarked} + ${_n}")
    endforeach()
  endforeach()
  list(LENGTH _declared _ndeclared)
  list(REMOVE_DUPLICATES _declared)
  list(LENGTH _declared _ndistinct)
  message(STATUS "${_libname}: ${_nexported} exported symbols; "
                 "${_ndeclared} functions declared in the public headers, ${_nmarked} LGN_EXPORT")
  if(_ndeclared LESS 50)
    message(FATAL_ERROR "only ${_ndeclared} function declarations found in ${LGN_HEADER_DIRS}: is the parsing broken?")
  endif()
  if(NOT _ndeclared EQUAL _nmarked)
    message(SEND_ERROR "${_ndeclared} function declarations but ${_nmarked} LGN_EXPORT in the public "
                       "headers: every declaration (and nothing else) carries LGN_EXPORT")
    math(EXPR _lgn_failures "${_lgn_failures} + 1")
  endif()
  if(NOT _ndeclared EQUAL _ndistinct)
    message(STATUS "(some functions are declared more than once)")
  endif()

  set(_leaked "")
  set(_not_lgn "")
  foreach(_s IN LISTS _exported)
    if(NOT _s IN_LIST _declared)
      list(APPEND _leaked "${_s}")
    endif()
    if(NOT _s MATCHES "^LGN")
      list(APPEND _not_lgn "${_s}")
    endif()
  endforeach()
  set(_missing "")
  set(_declared_not_lgn "")
  foreach(_d IN LISTS _declared)
    if(NOT _d IN_LIST _exported)
      list(APPEND _missing "${_d}")
    endif()
    if(NOT _d MATCHES "^LGN")
      list(APPEND _declared_not_lgn "${_d}")
    endif()
  endforeach()
  lgn_report(_leaked "${_libname} exports symbols not declared in the public headers (internal symbols leak)")
  lgn_report(_not_lgn "${_libname} exports symbols that do not start with LGN")
  lgn_report(_missing "functions declared in the public headers that ${_libname} does not export (LGN_EXPORT missing, or not defined)")
  lgn_report(_declared_not_lgn "functions declared in the public headers whose names do not start with LGN")
else()
  # --- liblignum_fortran and its modules ----------------------------------
  if(NOT LGN_FORTRAN_SOURCES)
    message(FATAL_ERROR "check_exports.cmake: -DLGN_FORTRAN_SOURCES=... is required")
  endif()
  string(REPLACE "|" ";" _sources "${LGN_FORTRAN_SOURCES}")
  set(_modules "")
  set(_bound "")
  foreach(_f IN LISTS _sources)
    file(READ "${_f}" _text)
    string(TOLOWER "${_text}" _lc)
    string(REGEX MATCHALL "(^|\n)[ \t]*module[ \t]+[a-z0-9_]+" _m "${_lc}")
    foreach(_x IN LISTS _m)
      string(REGEX REPLACE ".*module[ \t]+" "" _x "${_x}")
      if(NOT _x STREQUAL "procedure")
        list(APPEND _modules "${_x}")
      endif()
    endforeach()
    string(REGEX MATCHALL "[bB][iI][nN][dD][ \t]*\\([ \t]*[cC][ \t]*,[ \t]*[nN][aA][mM][eE][ \t]*=[ \t]*['\"][A-Za-z0-9_]+['\"]" _b "${_text}")
    foreach(_x IN LISTS _b)
      string(REGEX REPLACE ".*['\"]([A-Za-z0-9_]+)['\"]$" "\\1" _x "${_x}")
      list(APPEND _bound "${_x}")
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES _modules)
  list(REMOVE_DUPLICATES _bound)
  if(NOT _modules)
    message(FATAL_ERROR "no module found in ${LGN_FORTRAN_SOURCES}")
  endif()
  string(REPLACE ";" "|" _mod_alt "${_modules}")
  set(_bound_flgn "")
  set(_bound_lgn "")
  foreach(_x IN LISTS _bound)
    if(_x MATCHES "^FLGN")
      list(APPEND _bound_flgn "${_x}")
    elseif(_x MATCHES "^LGN")
      list(APPEND _bound_lgn "${_x}")
    endif()
  endforeach()

  set(_foreign "")
  set(_nmodule 0)
  foreach(_s IN LISTS _exported)
    if(_s MATCHES "^__(${_mod_alt})_MOD_")
      math(EXPR _nmodule "${_nmodule} + 1")
    elseif(NOT _s IN_LIST _bound_flgn)
      list(APPEND _foreign "${_s}")
    endif()
  endforeach()
  string(REPLACE ";" ", " _mod_list "${_modules}")
  string(REPLACE ";" ", " _flgn_list "${_bound_flgn}")
  message(STATUS "${_libname}: ${_nexported} exported symbols, ${_nmodule} of the modules ${_mod_list}; "
                 "the modules bind to its ${_flgn_list}")
  if(_nmodule EQUAL 0)
    message(SEND_ERROR "${_libname} exports nothing of the modules ${_mod_list}: not gfortran's mangling?")
    math(EXPR _lgn_failures "${_lgn_failures} + 1")
  endif()
  set(_missing "")
  foreach(_x IN LISTS _bound_flgn)
    if(NOT _x IN_LIST _exported)
      list(APPEND _missing "${_x}")
    endif()
  endforeach()
  lgn_report(_foreign "${_libname} exports symbols that are neither module entities nor FLGN* helpers bound by the modules")
  lgn_report(_missing "FLGN* helpers the modules bind to that ${_libname} does not export")
  if(LGN_C_LIBRARY)
    lgn_exported_symbols("${LGN_C_LIBRARY}" _c_exported)
    set(_unreachable "")
    foreach(_x IN LISTS _bound_lgn)
      if(NOT _x IN_LIST _c_exported)
        list(APPEND _unreachable "${_x}")
      endif()
    endforeach()
    list(LENGTH _bound_lgn _nbound)
    get_filename_component(_cname "${LGN_C_LIBRARY}" NAME)
    message(STATUS "the modules bind to ${_nbound} LGN* functions of ${_cname}")
    lgn_report(_unreachable "LGN* functions the modules bind to that ${_cname} does not export")
  endif()
endif()

if(_lgn_failures GREATER 0)
  message(FATAL_ERROR "${_libname}: ${_lgn_failures} check(s) failed")
endif()
message(STATUS "${_libname}: exports exactly its public interface")
