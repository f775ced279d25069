# What makes a clean build take minutes rather than ten (docs/build.md, "Where the build time goes").
#
#  - Precompiled headers. A translation unit of this project is mostly headers it did not write:
#    GoogleTest preprocesses to 104,000 lines, the standard library, GLM and PCG to 60,000 more.
#    Two header sets are parsed once per build and reused by every target (REUSE_FROM):
#    cmake/pch/library.h for libraries and programs, cmake/pch/test.h (the same and GoogleTest)
#    for test programs. GoogleTest's macros stay out of the code students write.
#  - mold, Debian's fast linker, when installed (GCC 12 takes -fuse-ld=mold).
#  - ccache, Debian's compiler cache, when installed: a second build of the same sources (a new
#    build folder, CI on a machine that built before) compiles nothing.
#  - A unity build of each test program (RT_UNITY_TESTS): its test files compiled as one
#    translation unit, so the GoogleTest and stage templates they share are instantiated and
#    optimized once, not once per file. A clean release build went from 228 s to 149 s on 2 cores
#    (batches of 4 files: 177 s). It asks one thing of the test files: a file-local name is unique
#    within its test program (helpers two files need live in a shared header instead). The
#    sanitize preset builds the files one by one, so CI still proves each compiles on its own.
# Each is optional: a plain `cmake -S . -B build` without ccache or mold builds the same programs.
option(RT_PRECOMPILED_HEADERS "Parse the common third-party and standard headers once per build (GCC)" ON)
# GCC only: Clang (the fuzz preset) refuses a precompiled header that expands __DATE__ or
# __TIME__ (-Wpch-date-time), as PCG's pcg_extras.hpp does, and its builds here are small.
if(RT_PRECOMPILED_HEADERS AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  set(rt_precompiled_headers TRUE)
endif()
option(RT_UNITY_TESTS "Compile each test program's files as one translation unit" ON)
option(RT_USE_CCACHE "Compile through ccache when it is installed" ON)
option(RT_USE_MOLD "Link with mold when it is installed" ON)

if(RT_USE_CCACHE)
  find_program(RT_CCACHE ccache)
  if(RT_CCACHE)
    # The sloppiness settings let ccache reuse results compiled with a precompiled header (the
    # ccache manual, "Precompiled headers"). Hashing the header itself (about 100 MB) for every
    # file cost 0.6 s a file, a minute of a clean build; with pch_external_checksum ccache hashes
    # the small checksum file rt_precompiled_header_checksum writes next to it instead.
    set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env
        "CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime" CCACHE_PCH_EXTSUM=true
        ${RT_CCACHE})
    set(rt_compiles_through_ccache TRUE)
    message(STATUS "ccache found: ${RT_CCACHE}")
  endif()
endif()

if(RT_USE_MOLD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_GREATER_EQUAL 12.1)
  find_program(RT_MOLD mold)
  if(RT_MOLD)
    add_link_options(-fuse-ld=mold)
    message(STATUS "mold found: linking with ${RT_MOLD}")
  endif()
endif()

# Test programs compile at -O1 in a release build (RT_TEST_OPTIMIZATION): a test computes values and
# compares them, and -O1 computes the same values as -O3, since the project allows no fast-math and
# no contraction (-ffp-contract=off, cmake/CompilerSettings.cmake), so no -O level changes a
# floating-point result. It cut a clean build from 3 min 30 s to 2 min 57 s, and the tests ran no
# slower (60 s, 56 s): their heavy work runs in the stage libraries, which keep -O3 with the
# programs and the benchmarks. Other build types keep their own level (debug -O0, sanitize -O1).
set(RT_TEST_OPTIMIZATION "-O1" CACHE STRING "Optimization of the test programs' own files in a release build")
add_library(rt_test_flags INTERFACE)
target_compile_options(rt_test_flags INTERFACE $<$<CONFIG:Release>:${RT_TEST_OPTIMIZATION}>)

# The targets whose precompiled headers the others reuse. Each carries rt::flags, so that its
# compile flags are those of every target that reuses it: GCC ignores a header precompiled with
# other flags and parses the headers instead (slower, never wrong).
if(rt_precompiled_headers)
  add_library(rt_pch_library OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch/empty.cpp)
  target_link_libraries(rt_pch_library PRIVATE rt::flags glm::glm pcg)
  target_precompile_headers(rt_pch_library PRIVATE ${PROJECT_SOURCE_DIR}/cmake/pch/library.h)
  if(RT_BUILD_TESTS)
    add_library(rt_pch_test OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch/empty.cpp)
    target_link_libraries(rt_pch_test PRIVATE rt::flags rt_test_flags glm::glm pcg GTest::gtest)
    target_precompile_headers(rt_pch_test PRIVATE ${PROJECT_SOURCE_DIR}/cmake/pch/test.h)
  endif()
endif()

# rt_precompiled_header_checksum(TARGET): writes the checksum of TARGET's precompiled header
# beside it (HEADER.gch.sum), for ccache's pch_external_checksum, in a target TARGET_sum that
# every target reusing the header depends on. Only where ccache compiles.
function(rt_precompiled_header_checksum target)
  set(header ${CMAKE_CURRENT_BINARY_DIR}/CMakeFiles/${target}.dir/cmake_pch.hxx.gch)
  add_custom_command(OUTPUT ${header}.sum COMMAND ${CMAKE_COMMAND} -E sha256sum ${header} > ${header}.sum
                     DEPENDS ${target} ${header})
  add_custom_target(${target}_sum DEPENDS ${header}.sum)
endfunction()

if(rt_precompiled_headers AND rt_compiles_through_ccache)
  rt_precompiled_header_checksum(rt_pch_library)
  if(RT_BUILD_TESTS)
    rt_precompiled_header_checksum(rt_pch_test)
  endif()
endif()

# rt_use_precompiled_headers(DIRECTORY): every C++ library and program defined under DIRECTORY
# reuses the shared headers: a test program (name ending in _tests) the test set, any other the
# library set. Called once, after every target exists, so no CMakeLists.txt has to remember it.
function(rt_use_precompiled_headers directory)
  if(NOT rt_precompiled_headers)
    return()
  endif()
  get_property(targets DIRECTORY ${directory} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target ${targets})
    get_target_property(type ${target} TYPE)
    if(target MATCHES "^rt_pch_" OR NOT type MATCHES "^(STATIC_LIBRARY|EXECUTABLE|OBJECT_LIBRARY)$")
      continue()
    endif()
    if(target MATCHES "_tests$")
      set(header_target rt_pch_test)
    else()
      set(header_target rt_pch_library)
    endif()
    target_precompile_headers(${target} REUSE_FROM ${header_target})
    if(TARGET ${header_target}_sum)
      add_dependencies(${target} ${header_target}_sum)
    endif()
  endforeach()
  get_property(children DIRECTORY ${directory} PROPERTY SUBDIRECTORIES)
  foreach(child ${children})
    rt_use_precompiled_headers(${child})
  endforeach()
endfunction()
