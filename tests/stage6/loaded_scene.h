// A scene of assets/scenes with its camera at a given film size, loaded once per test program:
// the scenes the stage-6 tests render.
#pragma once

#include "04-radiometry/lighting_scene.h"
#include "common/camera.h"
#include "common/scene.h"
#include "support/test_support.h"

#include <string>
#include <utility>

namespace rt::testing {

struct LoadedScene {
  LoadedScene(const char* file, int width, int height) : LoadedScene(load_scene(source_path(file)), width, height) {}
  LoadedScene(SceneDescription loaded, int width, int height)
      : description(std::move(loaded)), scene(description), camera(description.camera, width, height) {}
  SceneDescription description;
  LightingScene scene;
  Camera camera;
};

// The Cornell box on a W x H film, loaded on first use.
template <int W, int H>
const LoadedScene& cornell_box() {
  static const LoadedScene s("assets/scenes/cornell-box.json", W, H);
  return s;
}

// The same box with glossy white walls (a Phong lobe of exponent 20 beside a Lambertian part): a
// BSDF that depends on the direction towards the camera, which a Lambertian box never tests.
template <int W, int H>
const LoadedScene& glossy_cornell_box() {
  static const LoadedScene s = [] {
    std::string text = read_text(source_path("assets/scenes/cornell-box.json"));
    const std::string white = R"("white": { "albedo": [0.725, 0.71, 0.68] })";
    text.replace(text.find(white), white.size(),
                 R"("white": { "type": "phong", "albedo": [0.3, 0.3, 0.3], "specular": [0.4, 0.4, 0.4], "shininess": 20 })");
    return LoadedScene(parse_scene(text, "glossy-cornell-box.json"), W, H);
  }();
  return s;
}

}  // namespace rt::testing
