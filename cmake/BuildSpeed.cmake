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
# Each is optional: a plain `cmake -S . -B build` without ccache or mold builds the same programs.
option(RT_PRECOMPILED_HEADERS "Parse the common third-party and standard headers once per build" ON)
option(RT_USE_CCACHE "Compile through ccache when it is installed" ON)
option(RT_USE_MOLD "Link with mold when it is installed" ON)

if(RT_USE_CCACHE)
  find_program(RT_CCACHE ccache)
  if(RT_CCACHE)
    # ccache hashes the precompiled header's inputs; these sloppiness settings let it reuse results
    # compiled with one (the ccache manual, "Precompiled headers").
    set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env
        "CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime" ${RT_CCACHE})
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

# The targets whose precompiled headers the others reuse. Each carries rt::flags, so that its
# compile flags are those of every target that reuses it: GCC ignores a header precompiled with
# other flags and parses the headers instead (slower, never wrong).
if(RT_PRECOMPILED_HEADERS)
  add_library(rt_pch_library OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch/empty.cpp)
  target_link_libraries(rt_pch_library PRIVATE rt::flags glm::glm pcg)
  target_precompile_headers(rt_pch_library PRIVATE ${PROJECT_SOURCE_DIR}/cmake/pch/library.h)
  if(RT_BUILD_TESTS)
    add_library(rt_pch_test OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch/empty.cpp)
    target_link_libraries(rt_pch_test PRIVATE rt::flags glm::glm pcg GTest::gtest)
    target_precompile_headers(rt_pch_test PRIVATE ${PROJECT_SOURCE_DIR}/cmake/pch/test.h)
  endif()
endif()

# rt_use_precompiled_headers(DIRECTORY): every C++ library and program defined under DIRECTORY
# reuses the shared headers: a test program (name ending in _tests) the test set, any other the
# library set. Called once, after every target exists, so no CMakeLists.txt has to remember it.
function(rt_use_precompiled_headers directory)
  if(NOT RT_PRECOMPILED_HEADERS)
    return()
  endif()
  get_property(targets DIRECTORY ${directory} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target ${targets})
    get_target_property(type ${target} TYPE)
    if(target MATCHES "^rt_pch_" OR NOT type MATCHES "^(STATIC_LIBRARY|EXECUTABLE|OBJECT_LIBRARY)$")
      continue()
    endif()
    if(target MATCHES "_tests$")
      target_precompile_headers(${target} REUSE_FROM rt_pch_test)
    else()
      target_precompile_headers(${target} REUSE_FROM rt_pch_library)
    endif()
  endforeach()
  get_property(children DIRECTORY ${directory} PROPERTY SUBDIRECTORIES)
  foreach(child ${children})
    rt_use_precompiled_headers(${child})
  endforeach()
endfunction()
