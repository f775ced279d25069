// Headers parsed once per build for every library and program (cmake/BuildSpeed.cmake). Only
// headers that no file of the project writes, and that change no meaning by being seen early.
// Not CLI11: in a precompiled header GCC compiles its inline functions into every file that
// loads it (measured: a small test file took 2.0 s with this set, 9.1 s with CLI11 added).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <pcg_random.hpp>
