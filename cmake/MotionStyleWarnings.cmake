# Shared compile settings for every MotionStyle target: warnings, sanitizers and the CPU target.
add_library(motionstyle_settings INTERFACE)
add_library(MotionStyle::settings ALIAS motionstyle_settings)

target_compile_options(motionstyle_settings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
    -Wnon-virtual-dtor -Woverloaded-virtual -Wcast-align -Wdouble-promotion
    -Wimplicit-fallthrough>
  # GCC 12 warns inside its own AVX-512 intrinsic headers when Eigen vectorises with -march=native
  # (GCC bug 105593, a false positive); it would break -Werror builds on AVX-512 machines.
  $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>
  # GCC 12 at -O3 reports impossible memcpy overlaps inside std::string concatenation (GCC bug 105329).
  $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
if(MOTIONSTYLE_STRICT_WARNINGS)
  target_compile_options(motionstyle_settings INTERFACE $<$<CXX_COMPILER_ID:GNU,Clang>:-Werror>)
endif()

if(MOTIONSTYLE_SANITIZE)
  target_compile_options(motionstyle_settings INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                       -fno-sanitize-recover=undefined)
  target_link_options(motionstyle_settings INTERFACE -fsanitize=address,undefined)
endif()

if(MOTIONSTYLE_ARCH STREQUAL "native")
  target_compile_options(motionstyle_settings INTERFACE -march=native)
elseif(MOTIONSTYLE_ARCH STREQUAL "x86-64-v3")
  target_compile_options(motionstyle_settings INTERFACE -march=x86-64-v3)
elseif(NOT MOTIONSTYLE_ARCH STREQUAL "portable")
  message(FATAL_ERROR "MOTIONSTYLE_ARCH must be native, x86-64-v3 or portable, not '${MOTIONSTYLE_ARCH}'")
endif()
