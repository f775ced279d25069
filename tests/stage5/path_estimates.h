// Shared by the stage-5 tests (and the hidden ones): many paths along one ray with their mean and
// standard error, and the furnace scene, whose radiance is known in closed form.
#pragma once

#include "05-path-tracing/path_tracer.h"
#include "common/scene.h"
#include "support/sample_mean.h"
#include "support/subject.h"

#include <string>

namespace rt {

using testing::Estimate;

// `paths` independent paths along one ray: mean and standard error of one channel.
inline Estimate estimate(const LightingScene& scene, const Ray& ray, const PathOptions& options, int paths,
                         std::uint64_t seed = 1, int channel = 0) {
  return testing::subject([&] {
    testing::SampleMean m;
    for (int k = 0; k < paths; ++k) {
      Rng rng(seed, 0, std::uint64_t(k));
      m.add(path_radiance(scene, ray, options, rng)[channel]);
    }
    return m.estimate();
  });
}

// A closed cube [-s, s]^3, every wall facing in, of albedo rho and emission Le: L = Le / (1 - rho)
// everywhere inside.
inline LightingScene furnace(float albedo, float emission, float s = 1.0f) {
  const std::string a = std::to_string(albedo), e = std::to_string(emission);
  // The six walls as corner signs, each corner scaled by s.
  const char* const walls[6][4] = {{"-,-,+", "+,-,+", "+,-,-", "-,-,-"}, {"+,+,-", "+,+,+", "-,+,+", "-,+,-"},
                                   {"-,+,-", "-,+,+", "-,-,+", "-,-,-"}, {"+,-,+", "+,+,+", "+,+,-", "+,-,-"},
                                   {"+,-,-", "+,+,-", "-,+,-", "-,-,-"}, {"-,+,+", "+,+,+", "+,-,+", "-,-,+"}};
  std::string shapes;
  for (const auto& wall : walls) {
    shapes += std::string(shapes.empty() ? "" : ",") + R"({"type": "quad", "material": "wall", "vertices": [)";
    for (int corner = 0; corner < 4; ++corner) {
      std::string xyz;
      for (const char* c = wall[corner]; *c; ++c)
        xyz += *c == '+' ? std::to_string(s) : *c == '-' ? std::to_string(-s) : std::string(1, *c);
      shapes += std::string(corner ? "," : "") + "[" + xyz + "]";
    }
    shapes += "]}";
  }
  const std::string json = R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "vfov": 40},
    "materials": {"wall": {"albedo": [)" + a + "," + a + "," + a + R"(], "emission": [)" + e + "," + e + "," + e +
                           R"(]}}, "shapes": [)" + shapes + "]}";
  return LightingScene(parse_scene(json, "furnace.json"));
}

}  // namespace rt
