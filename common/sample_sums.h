// What a render accumulates before it divides: per pixel, the sum of its samples' radiance and how
// many samples there were. The image is their quotient, I(x, y) = (1/N) sum_k L_k (stage 1's pixel
// estimator); keeping the two apart is what lets batches rendered on different machines be added
// first and divided once (common/sample_batch.h, docs/scale-out.md).
#pragma once

#include "common/image.h"

#include <cstdint>
#include <vector>

namespace rt {

class SampleSums {
 public:
  SampleSums() = default;
  SampleSums(int width, int height) : sum_(width, height), count_(sum_.pixel_count(), 0) {}

  int width() const { return sum_.width(); }
  int height() const { return sum_.height(); }

  void set(int x, int y, Color sum, std::uint32_t count) {
    sum_.at(x, y) = sum;
    count_[index(x, y)] = count;
  }
  const Color& sum(int x, int y) const { return sum_.at(x, y); }
  std::uint32_t count(int x, int y) const { return count_[index(x, y)]; }

  const Image& sums() const { return sum_; }
  Image& sums() { return sum_; }
  const std::vector<std::uint32_t>& counts() const { return count_; }
  std::vector<std::uint32_t>& counts() { return count_; }

  // The mean of each pixel's samples, black where it has none. Divided in float, the same
  // operation whether the sum came from one run or from merged batches.
  Image mean() const {
    Image image(width(), height());
    for (size_t i = 0; i < count_.size(); ++i)
      if (count_[i] > 0) image.pixels()[i] = sum_.pixels()[i] / float(count_[i]);
    return image;
  }

  std::uint64_t total_count() const {
    std::uint64_t total = 0;
    for (const std::uint32_t n : count_) total += n;
    return total;
  }

 private:
  size_t index(int x, int y) const { return size_t(y) * size_t(width()) + size_t(x); }

  Image sum_;
  std::vector<std::uint32_t> count_;
};

}  // namespace rt
