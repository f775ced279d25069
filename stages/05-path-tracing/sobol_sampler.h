// Stage 5: a low-discrepancy sampler, for comparison with independent random numbers (common/random.h).
//
// Each uniform2() takes the next two dimensions of the sample from the first two dimensions of
// Sobol's sequence, a (0,2)-sequence: any 2^k consecutive points put exactly one point in every
// elementary box of area 2^-k. So a pixel's 2^k samples are stratified in every 2D projection a path
// uses (pixel area, light point, BRDF direction), which removes the variance of edges and of smooth
// integrands faster than N^-1. A single uniform() takes the first dimension alone (a stratified 1D
// pattern). Each call's dimensions are Owen-scrambled and their point order shuffled by a hash of
// (seed, pixel, call number), so calls are independent of each other and the estimate stays
// unbiased ("padded" Sobol). Scrambling and shuffling use Burley's hash-based nested uniform
// scramble (Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020).
//
// Same interface as Rng, so the integrators take either. Determinism is kept: every number is a
// function of (seed, pixel, sample index, call number).
#pragma once

#include "common/math.h"
#include "common/random.h"

#include <array>
#include <cstdint>

namespace rt {

class SobolSampler final : public Sampler {
 public:
  SobolSampler(std::uint64_t seed, std::uint64_t pixel_index, std::uint64_t sample_index)
      : key_(std::uint32_t(Rng::mix(Rng::mix(seed) ^ pixel_index))),
        reversed_index_(reverse_bits(std::uint32_t(sample_index))) {}

  // Both coordinates are scramble(sobol_dimension(i), seed) = reverse(LK(reverse(sobol(i)))),
  // computed without reversing twice: sobol_dimension0 is itself a reversal, and dimension 1 is
  // tabulated with its bits already reversed.
  // Defined in sobol_sampler.cpp, beside laine_karras, so that each compiles its calls to it in.
  Vec2 uniform2() override;
  float uniform() override;

  // Sobol's first dimension is the van der Corput sequence in base 2: the bits of i reversed.
  static std::uint32_t sobol_dimension0(std::uint32_t i) { return reverse_bits(i); }
  // The second: the generator matrix with columns v_k = 2^31 >> k folded by v ^= v >> 1, applied
  // over GF(2) (XOR of the columns of i's set bits). The map is linear, so it is tabulated (with
  // its output bits reversed) one byte of i at a time: four lookups instead of a loop with a
  // branch per bit.
  static std::uint32_t sobol_dimension1(std::uint32_t i) { return reverse_bits(reversed_sobol_dimension1(i)); }
  static std::uint32_t reversed_sobol_dimension1(std::uint32_t i) {
    const auto& t = dimension1_tables();
    return t[0][i & 0xffu] ^ t[1][(i >> 8) & 0xffu] ^ t[2][(i >> 16) & 0xffu] ^ t[3][i >> 24];
  }
  // Task stage5.sampler.owen_scramble. Nested uniform (Owen) scrambling of a 32-bit fraction: flip
  // each bit by a hash of the bits above it. Reversing the bits turns that into "each bit depends
  // on the bits below", which the Laine-Karras hash does in one pass of multiplications.
  static std::uint32_t scramble(std::uint32_t x, std::uint32_t seed) {
    return reverse_bits(laine_karras(reverse_bits(x), seed));
  }
  static std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed);

  // The byte order reversed in one instruction (bswap), then the bits within each byte: nibbles,
  // pairs, single bits swapped by masks.
  static std::uint32_t reverse_bits(std::uint32_t x) {
    x = __builtin_bswap32(x);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    return ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  }

 private:
  using Tables = std::array<std::array<std::uint32_t, 256>, 4>;
  static const Tables& dimension1_tables();

  // The sample index with its order shuffled (an Owen scramble of the index itself, Burley
  // section 4), so that each call visits the pixel's points in its own order. reverse(LK(reverse))
  // with the first reversal done once per sample.
  std::uint32_t shuffled_index(std::uint32_t call) const {
    return reverse_bits(laine_karras(reversed_index_, hash(call, 0)));
  }
  // The top 24 bits as a float in [0, 1), like Rng::uniform.
  static float to_unit(std::uint32_t x) { return float(x >> 8) * 0x1p-24f; }
  // Wellons's "lowbias32" integer hash, a bijection on 32 bits with low avalanche bias.
  std::uint32_t hash(std::uint32_t call, std::uint32_t which) const {
    std::uint32_t x = key_ ^ (call * 4u + which) * 0x9e3779b9u;
    x ^= x >> 16;
    x *= 0x21f0aaadu;
    x ^= x >> 15;
    x *= 0x735a2d97u;
    x ^= x >> 15;
    return x;
  }

  std::uint32_t key_;
  std::uint32_t reversed_index_;
  std::uint32_t call_ = 0;
};

}  // namespace rt
