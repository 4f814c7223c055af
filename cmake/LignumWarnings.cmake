# Warning and sanitizer flags, applied to every Lignum target through
# the interface library lignum_build_flags (not exported).
add_library(lignum_build_flags INTERFACE)
if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
  target_compile_options(lignum_build_flags INTERFACE -Wall -Wextra -Wpedantic
    -Wshadow -Wstrict-prototypes -Wmissing-prototypes)
  if(LGN_WARNINGS_AS_ERRORS)
    target_compile_options(lignum_build_flags INTERFACE -Werror)
  endif()
  if(LGN_ENABLE_SANITIZERS)
    target_compile_options(lignum_build_flags INTERFACE
      -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(lignum_build_flags INTERFACE -fsanitize=address,undefined)
  endif()
endif()
