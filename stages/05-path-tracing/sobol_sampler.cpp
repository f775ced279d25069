#include "05-path-tracing/sobol_sampler.h"

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

}  // namespace rt
