// Stage 4: the command-line flags for how rectangle lights and the environment are sampled, shared
// by stage4 and stage5.
#pragma once

#include "04-radiometry/lighting_scene.h"
#include "common/stage_program.h"

namespace rt {

inline void add_rectangle_sampling_flag(StageFlags& flags, LightingOptions& lighting) {
  flags.add_choice("--rectangle-sampling", lighting.rectangle_sampling,
                   {{"solid-angle", RectangleSampling::solid_angle}, {"area", RectangleSampling::area}},
                   "How rectangular quad lights are sampled: area (uniform over their area, the lecture's method "
                   "and the default) or solid-angle (uniform over the directions they subtend)");
}

inline void add_environment_sampling_flag(StageFlags& flags, LightingOptions& lighting) {
  flags.add_choice("--environment-sampling", lighting.environment_sampling,
                   {{"importance", EnvironmentSampling::importance}, {"uniform", EnvironmentSampling::uniform}},
                   "How an environment map is sampled: importance (by its luminance, the default) or uniform (over "
                   "the sphere)");
}

}  // namespace rt
