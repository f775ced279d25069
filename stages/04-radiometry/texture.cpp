#include "04-radiometry/texture.h"

#include "common/task.h"

#include <algorithm>
#include <cmath>

namespace rt {

int wrap_texel(int i, int n, TextureWrap wrap) {
  // BEGIN TASK stage4.texture.wrap
  if (wrap == TextureWrap::clamp) return std::clamp(i, 0, n - 1);
  const int r = i % n;  // C++'s % keeps the sign of i: -1 % 4 is -1, which is texel 3
  return r < 0 ? r + n : r;
  // PLACEHOLDER
  // report_unfinished_task("stage4.texture.wrap");
  // (void)wrap;
  // return std::clamp(i, 0, n - 1);
  // END TASK
}

Color texture_lookup(const ImageTexture& texture, Vec2 uv) {
  const Image& texels = *texture.texels;
  const int width = texels.width(), height = texels.height();
  // One period first: any float (a plane's coordinates reach 1e18) then makes a small texel index,
  // and a NaN (which no hit should carry) reads texel 0 instead of overflowing an int.
  auto reduce = [&](float c) {
    if (!std::isfinite(c)) return 0.0f;
    return texture.wrap == TextureWrap::repeat ? c - std::floor(c) : std::clamp(c, 0.0f, 1.0f);
  };
  const float x = reduce(uv.x) * float(width), y = (1.0f - reduce(uv.y)) * float(height);
  auto at = [&](int i, int j) {
    return texels.at(wrap_texel(i, width, texture.wrap), wrap_texel(j, height, texture.wrap));
  };
  // BEGIN TASK stage4.texture.lookup
  if (texture.filter == TextureFilter::nearest) return at(int(std::floor(x)), int(std::floor(y)));
  const float xc = x - 0.5f, yc = y - 0.5f;  // in coordinates where texel centres are integers
  const float i0 = std::floor(xc), j0 = std::floor(yc);
  const float fx = xc - i0, fy = yc - j0;
  const int i = int(i0), j = int(j0);
  const Color top = at(i, j) + fx * (at(i + 1, j) - at(i, j));
  const Color bottom = at(i, j + 1) + fx * (at(i + 1, j + 1) - at(i, j + 1));
  return top + fy * (bottom - top);
  // PLACEHOLDER
  // report_unfinished_task("stage4.texture.lookup");
  // (void)x, (void)y, (void)at;
  // return texture.mean;
  // END TASK
}

}  // namespace rt
