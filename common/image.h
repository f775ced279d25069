// A linear RGB float image. Pixel (x, y) has row y = 0 at the TOP (docs/design.md).
#pragma once

#include "common/math.h"

#include <algorithm>
#include <cassert>
#include <vector>

namespace rt {

// The half-open rectangle of pixels [x0, x1) x [y0, y1) (a crop window, a tile, a region).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  size_t area() const { return empty() ? 0 : size_t(width()) * size_t(height()); }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(const PixelRect& r) const { return x0 <= r.x0 && r.x1 <= x1 && y0 <= r.y0 && r.y1 <= y1; }
  bool contains(int x, int y) const { return x0 <= x && x < x1 && y0 <= y && y < y1; }
  PixelRect intersection(const PixelRect& r) const {
    return {std::max(x0, r.x0), std::max(y0, r.y0), std::min(x1, r.x1), std::min(y1, r.y1)};
  }
  friend bool operator==(const PixelRect&, const PixelRect&) = default;
};

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
