# Flags every target of the project gets, through the interface target rt::flags.
#
# Speed without breaking IEEE reasoning (see docs/build.md):
#  - never -ffast-math: it implies -ffinite-math-only, under which std::isnan(NaN) is false and the
#    slab test's reasoning about +-infinity is undefined;
#  - -ffp-contract=off: GCC otherwise fuses a*b+c into one FMA wherever the target has it, which
#    makes the same expression round differently in different places and breaks watertightness
#    and the antisymmetry the robust intersection tests rely on.
# Tests and benchmarks share these flags, so the robustness tests check the code that is timed.
add_library(rt_flags INTERFACE)
add_library(rt::flags ALIAS rt_flags)

target_compile_options(rt_flags INTERFACE -Wall -Wextra -Wpedantic -ffp-contract=off)
if(RT_WARNINGS_AS_ERRORS)
  target_compile_options(rt_flags INTERFACE -Werror)
endif()

if(RT_SANITIZE)
  set(rt_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_compile_options(rt_flags INTERFACE ${rt_sanitizers})
  target_link_options(rt_flags INTERFACE ${rt_sanitizers})
endif()

if(RT_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "RT_FUZZ needs clang (libFuzzer): use the preset fuzz")
  endif()
  # Coverage instrumentation for every target, so the fuzzer is guided through common/ as well;
  # the fuzz targets themselves link -fsanitize=fuzzer (tests/fuzz/CMakeLists.txt).
  set(rt_fuzz_flags -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_compile_options(rt_flags INTERFACE ${rt_fuzz_flags})
  target_link_options(rt_flags INTERFACE -fsanitize=address,undefined)
endif()

find_package(Threads REQUIRED)
target_link_libraries(rt_flags INTERFACE Threads::Threads)
