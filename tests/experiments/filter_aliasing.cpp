#include "experiments/filter_aliasing.h"

#include "01-ray-casting/render.h"

#include <cmath>

namespace rt {

namespace {

// The plate on a size x size film: it reaches Nyquist at r_N = size / 4.
struct ZonePlate {
  explicit ZonePlate(int size) : half(0.5 * size), r_nyquist(0.25 * size), k(1.0 / (2.0 * r_nyquist)) {}
  double at(double fx, double fy) const {
    constexpr double kPi = 3.14159265358979323846;
    const double r2 = (fx - half) * (fx - half) + (fy - half) * (fy - half);
    return 0.5 + 0.5 * std::cos(kPi * k * r2);
  }
  double half, r_nyquist, k;
};

}  // namespace

Image render_zone_plate(PixelFilterType filter, int size, int spp, std::uint64_t seed) {
  // A camera looking down +z: film x grows along right = -x, film y along -y. The plate is drawn
  // on the film itself, so the radiance of a ray is the plate at the ray's film point.
  const Camera camera(CameraSpec{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), Vec3(0.0f, 1.0f, 0.0f), 60.0f}, size, size);
  const ZonePlate plate(size);
  const double pixels_per_unit = plate.half / double(camera.tan_half_vfov);
  RenderSettings settings;
  settings.width = settings.height = size;
  settings.spp = spp;
  settings.seed = seed;
  settings.filter = filter;
  return render_image(camera, settings, 0, [&](const Ray& ray, Rng&) {
    const double fx = plate.half - pixels_per_unit * double(ray.direction.x) / double(ray.direction.z);
    const double fy = plate.half - pixels_per_unit * double(ray.direction.y) / double(ray.direction.z);
    return Color(float(plate.at(fx, fy)));
  });
}

ZonePlateScores score_zone_plate(const Image& image) {
  const ZonePlate plate(image.width());
  double alias_sum = 0.0, pass_sum = 0.0, signal_pass = 0.0;
  int alias_n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const double r = std::hypot(x + 0.5 - plate.half, y + 0.5 - plate.half);
      const double deviation = double(image.at(x, y).r) - 0.5;
      if (r > 1.25 * plate.r_nyquist) {
        alias_sum += deviation * deviation;
        ++alias_n;
      } else if (r < 0.5 * plate.r_nyquist) {
        pass_sum += deviation * deviation;
        const double signal = plate.at(x + 0.5, y + 0.5) - 0.5;
        signal_pass += signal * signal;
      }
    }
  return ZonePlateScores{alias_sum / alias_n / 0.125, pass_sum / signal_pass, image};
}

ZonePlateScores measure_zone_plate(PixelFilterType filter, int size, int spp, std::uint64_t seed) {
  return score_zone_plate(render_zone_plate(filter, size, spp, seed));
}

}  // namespace rt
