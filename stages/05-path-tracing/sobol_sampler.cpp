#include "05-path-tracing/sobol_sampler.h"

#include "common/task.h"

namespace rt {

const SobolSampler::Tables& SobolSampler::dimension1_tables() {
  static const Tables tables = [] {
    Tables t{};
    std::uint32_t column[32];
    std::uint32_t v = 1u << 31;
    for (int k = 0; k < 32; ++k, v ^= v >> 1) column[k] = v;
    for (int byte = 0; byte < 4; ++byte)
      for (std::uint32_t value = 0; value < 256; ++value)
        for (int bit = 0; bit < 8; ++bit)
          if (value >> bit & 1u) t[size_t(byte)][value] ^= reverse_bits(column[8 * byte + bit]);
    return t;
  }();
  return tables;
}

std::uint32_t SobolSampler::laine_karras(std::uint32_t x, std::uint32_t seed) {
  // BEGIN TASK stage5.sampler.owen_scramble
  // Laine and Karras's hash with Burley's constants (JCGT 9(4), 2020, listing 2): each
  // multiplication by an even constant only carries bits upwards, so bit k ends up depending on
  // bits 0..k and the seed: a nested uniform scramble in reversed-bit order.
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
  // PLACEHOLDER
  // report_unfinished_task("stage5.sampler.owen_scramble");
  // return x ^ seed;  // a random digital shift: still unbiased, less well stratified
  // END TASK
}

Vec2 SobolSampler::uniform2() {
  const std::uint32_t call = call_++;
  const std::uint32_t i = shuffled_index(call);
  return Vec2(to_unit(reverse_bits(laine_karras(i, hash(call, 1)))),
              to_unit(reverse_bits(laine_karras(reversed_sobol_dimension1(i), hash(call, 2)))));
}

float SobolSampler::uniform() {
  const std::uint32_t call = call_++;
  return to_unit(reverse_bits(laine_karras(shuffled_index(call), hash(call, 1))));
}

}  // namespace rt
