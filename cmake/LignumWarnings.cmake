# Warning and sanitizer flags, applied to every Lignum target through
# the interface library lignum_build_flags (not exported). C and Fortran
# get their own warning sets; -Werror and the sanitizers apply to both, so
# that C and Fortran objects of one program are instrumented alike.
add_library(lignum_build_flags INTERFACE)
if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
  target_compile_options(lignum_build_flags INTERFACE
    $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes>)
  if(LGN_WARNINGS_AS_ERRORS)
    target_compile_options(lignum_build_flags INTERFACE $<$<COMPILE_LANGUAGE:C>:-Werror>)
  endif()
  if(LGN_ENABLE_SANITIZERS)
    target_compile_options(lignum_build_flags INTERFACE
      $<$<COMPILE_LANGUAGE:C>:-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer>)
    target_link_options(lignum_build_flags INTERFACE -fsanitize=address,undefined)
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
      $<$<COMPILE_LANGUAGE:Fortran>:-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -fcheck=bounds,do,mem,pointer,recursion>)
  endif()
endif()
