#include "common/metrics.h"

#include <cmath>
#include <stdexcept>

namespace rt {
namespace {

void require_same_size(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.pixel_count() == 0)
    throw std::invalid_argument("image metrics need two non-empty images of the same size");
}

template <class PerChannel>
double mean_over_channels(const Image& a, const Image& b, PerChannel per_channel) {
  require_same_size(a, b);
  double sum = 0.0;
  for (size_t i = 0; i < a.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) sum += per_channel(double(a.pixels()[i][c]), double(b.pixels()[i][c]));
  return sum / (3.0 * double(a.pixel_count()));
}

}  // namespace

double mse(const Image& image, const Image& reference) {
  return mean_over_channels(image, reference, [](double a, double b) { return (a - b) * (a - b); });
}

double rmse(const Image& image, const Image& reference) { return std::sqrt(mse(image, reference)); }

double rmse(const Image& image, const Image& reference, PixelRect r) {
  require_same_size(image, reference);
  if (r.x0 < 0 || r.y0 < 0 || r.x1 > image.width() || r.y1 > image.height() || r.x0 >= r.x1 || r.y0 >= r.y1)
    throw std::invalid_argument("rmse: rectangle is empty or outside the image");
  double sum = 0.0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x)
      for (int c = 0; c < 3; ++c) {
        const double d = double(image.at(x, y)[c]) - double(reference.at(x, y)[c]);
        sum += d * d;
      }
  return std::sqrt(sum / (3.0 * double(r.area())));
}

double relative_mse(const Image& image, const Image& reference, double epsilon) {
  return mean_over_channels(image, reference, [epsilon](double a, double b) {
    return (a - b) * (a - b) / (b * b + epsilon);
  });
}

DVec3 mean_over(const Image& image, PixelRect r) {
  if (r.x0 < 0 || r.y0 < 0 || r.x1 > image.width() || r.y1 > image.height() || r.x0 >= r.x1 ||
      r.y0 >= r.y1)
    throw std::invalid_argument("mean_over: rectangle is empty or outside the image");
  DVec3 sum(0.0);
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) sum += DVec3(image.at(x, y));
  return sum / double((r.x1 - r.x0) * (r.y1 - r.y0));
}

Image downsample(const Image& image, int factor) {
  if (factor < 1 || image.width() % factor != 0 || image.height() % factor != 0)
    throw std::invalid_argument("downsample: the factor must divide the image's width and height");
  Image small(image.width() / factor, image.height() / factor);
  for (int y = 0; y < small.height(); ++y)
    for (int x = 0; x < small.width(); ++x) {
      const DVec3 mean = mean_over(image, {x * factor, y * factor, (x + 1) * factor, (y + 1) * factor});
      small.at(x, y) = Color(mean);
    }
  return small;
}

}  // namespace rt
