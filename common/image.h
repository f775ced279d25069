// A linear RGB float image. Pixel (x, y) has row y = 0 at the TOP (DESIGN.md).
#pragma once

#include "common/math.h"

#include <cassert>
#include <vector>

namespace rt {

class Image {
 public:
  Image() = default;
  Image(int width, int height, Color fill = Color(0.0f))
      : width_(width), height_(height), pixels_(size_t(width) * size_t(height), fill) {}

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return pixels_.size(); }

  Color& at(int x, int y) {
    assert(x >= 0 && x < width_ && y >= 0 && y < height_);
    return pixels_[size_t(y) * size_t(width_) + size_t(x)];
  }
  const Color& at(int x, int y) const {
    assert(x >= 0 && x < width_ && y >= 0 && y < height_);
    return pixels_[size_t(y) * size_t(width_) + size_t(x)];
  }

  const std::vector<Color>& pixels() const { return pixels_; }
  std::vector<Color>& pixels() { return pixels_; }

  friend bool operator==(const Image&, const Image&) = default;

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Color> pixels_;
};

}  // namespace rt
