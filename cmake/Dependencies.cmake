# Every dependency is a Debian package found on the system; nothing is vendored or downloaded.
# tools/setup.sh installs the packages named here.
find_package(glm REQUIRED)                 # libglm-dev
find_package(nlohmann_json 3 REQUIRED)     # nlohmann-json3-dev
find_package(CLI11 2 REQUIRED)             # libcli11-dev
find_package(tinyobjloader REQUIRED)       # libtinyobjloader-dev (OBJ meshes, from stage 2 on)
find_package(tinyexr REQUIRED)             # libtinyexr-dev (OpenEXR output)

# libpcg-cpp-dev: header-only, no CMake package.
find_path(PCG_INCLUDE_DIR pcg_random.hpp REQUIRED)
add_library(pcg INTERFACE)
target_include_directories(pcg SYSTEM INTERFACE ${PCG_INCLUDE_DIR})

# libstb-dev: Debian ships the stb implementations compiled into libstb.
find_path(STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb REQUIRED)
find_library(STB_LIBRARY stb REQUIRED)
add_library(stb INTERFACE)
target_include_directories(stb SYSTEM INTERFACE ${STB_INCLUDE_DIR})
target_link_libraries(stb INTERFACE ${STB_LIBRARY})

if(RT_BUILD_TESTS)
  find_package(GTest REQUIRED)             # libgtest-dev
endif()
if(RT_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)         # libbenchmark-dev
endif()
