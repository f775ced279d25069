#include "01-ray-casting/program.h"

namespace rt {

void scale_depth_for_png(Image& image) {
  float farthest = 0.0f;
  for (const Color& c : image.pixels()) farthest = std::max(farthest, c.r);
  if (farthest > 0.0f)
    for (Color& c : image.pixels()) c /= farthest;
}

}  // namespace rt
