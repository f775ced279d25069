// A closed room whose six walls all glow (albedo 0.5, emission 1): every sample of every pixel is
// lit, so any finished sample shows, and every pixel's radiance is Le / (1 - albedo) = 2. The scene
// of the tests that stop renders part-way.
#pragma once

namespace rt::testing {

inline constexpr const char* kGlowingRoom = R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "vfov": 60},
  "materials": {"wall": {"albedo": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
  "shapes": [
    {"type": "quad", "material": "wall", "vertices": [[-1,-1,1], [1,-1,1], [1,-1,-1], [-1,-1,-1]]},
    {"type": "quad", "material": "wall", "vertices": [[1,1,-1], [1,1,1], [-1,1,1], [-1,1,-1]]},
    {"type": "quad", "material": "wall", "vertices": [[-1,1,-1], [-1,1,1], [-1,-1,1], [-1,-1,-1]]},
    {"type": "quad", "material": "wall", "vertices": [[1,-1,1], [1,1,1], [1,1,-1], [1,-1,-1]]},
    {"type": "quad", "material": "wall", "vertices": [[1,-1,-1], [1,1,-1], [-1,1,-1], [-1,-1,-1]]},
    {"type": "quad", "material": "wall", "vertices": [[-1,1,1], [1,1,1], [1,-1,1], [-1,-1,1]]}]})";

}  // namespace rt::testing
