// FNV-1a, 64 bits (Fowler, Noll and Vo; the parameters of the IETF draft "The FNV Non-Cryptographic
// Hash Algorithm"): a fingerprint that tells files apart, not a defence against forgery. Sample
// batches use it to tell whether two of them come from the same scene, and whether a batch's
// images are the ones its description was written with.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace rt {

class Fnv1a64 {
 public:
  Fnv1a64& add(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) state_ = (state_ ^ p[i]) * 0x100000001b3ull;
    return *this;
  }
  Fnv1a64& add(const std::string& text) { return add(text.data(), text.size()); }

  std::uint64_t value() const { return state_; }
  // Sixteen lowercase hex digits.
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(state_));
    return text;
  }

 private:
  std::uint64_t state_ = 0xcbf29ce484222325ull;
};

}  // namespace rt
