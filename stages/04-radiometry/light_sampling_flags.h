// Stage 4: the command-line flags for how rectangle lights and the environment are sampled, shared
// by stage4 and stage5.
#pragma once

#include "04-radiometry/lighting_scene.h"
#include "common/cli.h"

#include <map>

namespace rt {

inline void add_rectangle_sampling_flag(CLI::App& app, LightingOptions& lighting) {
  app.add_option("--rectangle-sampling", lighting.rectangle_sampling,
                 "How rectangular quad lights are sampled: area (uniform over their area, the lecture's method and "
                 "the default) or solid-angle (uniform over the directions they subtend)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, RectangleSampling>{
          {"solid-angle", RectangleSampling::solid_angle}, {"area", RectangleSampling::area}}));
}

inline void add_environment_sampling_flag(CLI::App& app, LightingOptions& lighting) {
  app.add_option("--environment-sampling", lighting.environment_sampling,
                 "How an environment map is sampled: importance (by its luminance, the default) or uniform (over "
                 "the sphere)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, EnvironmentSampling>{
          {"importance", EnvironmentSampling::importance}, {"uniform", EnvironmentSampling::uniform}}));
}

}  // namespace rt
