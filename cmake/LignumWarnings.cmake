# Warning and sanitizer flags, applied to every Lignum target through
# the interface library lignum_build_flags (not exported). C and Fortran
# get their own warning sets; -Werror and the sanitizers apply to both, so
# that C and Fortran objects of one program are instrumented alike.
#
# The C compiler may be GCC or Clang (CI builds with both), the Fortran
# compiler gfortran. Sanitizers (LGN_ENABLE_SANITIZERS): AddressSanitizer
# and UBSan, pointer-overflow named explicitly (part of `undefined` in both;
# Clang's also stops on an offset applied to a null pointer), every report
# fatal.
add_library(lignum_build_flags INTERFACE)
# The fuzz target (LGN_BUILD_FUZZ, test/fuzz): Clang's libFuzzer; every
# object is compiled with its coverage instrumentation and with ASan + UBSan.
if(LGN_BUILD_FUZZ)
  if(NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "LGN_BUILD_FUZZ needs Clang (-DCMAKE_C_COMPILER=clang)")
  endif()
  set(LGN_ENABLE_SANITIZERS ON)
  target_compile_options(lignum_build_flags INTERFACE
    $<$<COMPILE_LANGUAGE:C>:-fsanitize=fuzzer-no-link>)
endif()
# ThreadSanitizer (LGN_ENABLE_TSAN): GCC or Clang; excludes ASan.
if(LGN_ENABLE_TSAN)
  if(LGN_ENABLE_SANITIZERS)
    message(FATAL_ERROR "LGN_ENABLE_TSAN and LGN_ENABLE_SANITIZERS exclude each other")
  endif()
  target_compile_options(lignum_build_flags INTERFACE
    $<$<COMPILE_LANGUAGE:C>:-fsanitize=thread -fno-omit-frame-pointer>)
  target_link_options(lignum_build_flags INTERFACE -fsanitize=thread)
endif()
set(LGN_SANITIZE_FLAG -fsanitize=address,undefined,pointer-overflow)
if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
  target_compile_options(lignum_build_flags INTERFACE
    $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes>)
  if(LGN_WARNINGS_AS_ERRORS)
    target_compile_options(lignum_build_flags INTERFACE $<$<COMPILE_LANGUAGE:C>:-Werror>)
  endif()
  if(LGN_ENABLE_SANITIZERS)
    target_compile_options(lignum_build_flags INTERFACE
      $<$<COMPILE_LANGUAGE:C>:${LGN_SANITIZE_FLAG} -fno-sanitize-recover=all -fno-omit-frame-pointer>)
    target_link_options(lignum_build_flags INTERFACE ${LGN_SANITIZE_FLAG})
  endif()
endif()

# Fortran (LGN_ENABLE_FORTRAN): standard Fortran 2008 with gfortran's
# warnings. Callbacks have fixed bind(C) signatures, so unused dummy
# arguments are not warned about.
if(LGN_ENABLE_FORTRAN AND CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
  target_compile_options(lignum_build_flags INTERFACE
    $<$<COMPILE_LANGUAGE:Fortran>:-std=f2008 -fimplicit-none -Wall -Wextra -Wimplicit-interface -Wimplicit-procedure -Wno-unused-dummy-argument>)
  if(LGN_WARNINGS_AS_ERRORS)
    target_compile_options(lignum_build_flags INTERFACE $<$<COMPILE_LANGUAGE:Fortran>:-Werror>)
  endif()
  if(LGN_ENABLE_SANITIZERS)
    # plus gfortran's own run-time checks (array bounds, pointers, loops)
    target_compile_options(lignum_build_flags INTERFACE
      $<$<COMPILE_LANGUAGE:Fortran>:${LGN_SANITIZE_FLAG} -fno-sanitize-recover=all -fno-omit-frame-pointer -fcheck=bounds,do,mem,pointer,recursion>)
  endif()
endif()
