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

# The sanitizers instrument the product's code: the libraries (core, widgets) and the programs built
# from app/. Every program links their runtime (the allocator, the interceptors, the reports), so a
# test that drives core code aborts on core's first error; the test sources themselves are compiled
# without the checks (half the sanitizer build's compile time; they are the checks).
add_library(motionstyle_sanitized_code INTERFACE)
add_library(MotionStyle::sanitized_code ALIAS motionstyle_sanitized_code)
if(MOTIONSTYLE_SANITIZE)
  target_compile_options(motionstyle_sanitized_code INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                             -fno-sanitize-recover=undefined)
  # Eigen allocates with plain malloc where glibc's alignment suffices, unless the file is compiled
  # with ASan (Eigen/src/Core/util/Memory.h): a matrix allocated in a test file and freed in core
  # would then go through two allocators. One rule for every file: Eigen's own aligned allocator.
  target_compile_definitions(motionstyle_settings INTERFACE EIGEN_MALLOC_ALREADY_ALIGNED=0)
  target_compile_options(motionstyle_settings INTERFACE -fno-omit-frame-pointer)
  target_link_options(motionstyle_settings INTERFACE -fsanitize=address,undefined)
endif()

if(MOTIONSTYLE_ARCH STREQUAL "native")
  target_compile_options(motionstyle_settings INTERFACE -march=native)
elseif(MOTIONSTYLE_ARCH STREQUAL "x86-64-v3")
  target_compile_options(motionstyle_settings INTERFACE -march=x86-64-v3)
elseif(NOT MOTIONSTYLE_ARCH STREQUAL "portable")
  message(FATAL_ERROR "MOTIONSTYLE_ARCH must be native, x86-64-v3 or portable, not '${MOTIONSTYLE_ARCH}'")
endif()
