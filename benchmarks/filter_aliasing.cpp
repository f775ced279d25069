// The pixel filters' trade, measured (docs/stage1.md, "Pixel reconstruction filters"): each filter
// renders the zone plate of tests/experiments/filter_aliasing.h, 256 x 256 at 256 samples per pixel,
// and is scored by the energy that folded back from above Nyquist (aliasing) and by the share of
// the passband's contrast it keeps (sharpness), with the render's time; with a folder, also writes
// each render there as stage1-zone-plate-FILTER.png.
//   filter_aliasing OUT.csv [IMAGE_FOLDER]
#include "experiments/filter_aliasing.h"

#include "common/image_io.h"

#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::fprintf(stderr, "usage: filter_aliasing OUT.csv [IMAGE_FOLDER]\n");
    return 2;
  }
  std::FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::fprintf(stderr, "filter_aliasing: cannot write %s\n", argv[1]);
    return 1;
  }
  std::fprintf(out, "filter,aliasing,passband,seconds\n");
  for (const auto& [type, name] : rt::kPixelFilterNames) {
    const auto start = std::chrono::steady_clock::now();
    const rt::ZonePlateScores s = rt::measure_zone_plate(type, 256, 256, 1);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(out, "%s,%.6f,%.6f,%.3f\n", name, s.aliasing, s.passband, seconds);
    std::printf("%-16s aliasing %.4f  passband %.4f  %.2f s\n", name, s.aliasing, s.passband, seconds);
    if (argc == 3) {
      try {
        rt::write_image(std::string(argv[2]) + "/stage1-zone-plate-" + name + ".png", s.image);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "filter_aliasing: %s\n", e.what());
        return 1;
      }
    }
  }
  return std::fclose(out) == 0 ? 0 : 1;
}
