// Four floats as one SSE register, for the few short kernels that test four things at once (stage
// 3's four boxes of a wide node; stage 2's three corners of a triangle, and four triangles of a
// leaf). GCC's and Clang's vector extensions: +, -, * and comparisons act lane by lane,
// `c ? a : b` with a lane mask c picks per lane, and each line of such a kernel compiles to one
// instruction for all lanes. Lane by lane the arithmetic is IEEE single precision, the same as a
// float's, so a kernel written this way gives bit for bit what its one-at-a-time version gives.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace rt {

using Float4 = float __attribute__((vector_size(16)));
using Int4 = std::int32_t __attribute__((vector_size(16)));  // what a comparison of Float4s gives

inline Float4 load4(const float* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline Float4 broadcast(float x) { return Float4{x, x, x, x}; }
inline Float4 abs4(Float4 v) {
  return reinterpret_cast<Float4>(reinterpret_cast<Int4>(v) & (Int4{} + 0x7fffffff));  // the sign bits cleared
}
// Lane by lane the larger of a and b (for numbers, not NaNs: a NaN lane gives b).
inline Float4 max4(Float4 a, Float4 b) { return a > b ? a : b; }
inline Float4 min4(Float4 a, Float4 b) { return a < b ? a : b; }
// The largest of lanes 0, 1 and 2 (a row of three).
inline float max3(Float4 v) { return std::max(std::max(v[0], v[1]), v[2]); }

// One bit per lane, set where the comparison's lane is true (its sign bit).
inline unsigned lane_mask(Int4 comparison) {
#if defined(__SSE__)
  return unsigned(__builtin_ia32_movmskps(reinterpret_cast<Float4>(comparison)));
#else
  return unsigned(comparison[0] & 1) | unsigned(comparison[1] & 2) | unsigned(comparison[2] & 4) |
         unsigned(comparison[3] & 8);
#endif
}

}  // namespace rt
