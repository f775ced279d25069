// A scene of assets/scenes with its camera at a given film size, loaded once per test program:
// the scenes the stage-6 tests render.
#pragma once

#include "04-radiometry/lighting_scene.h"
#include "common/camera.h"
#include "common/scene.h"
#include "support/test_support.h"

namespace rt::testing {

struct LoadedScene {
  LoadedScene(const char* file, int width, int height)
      : description(load_scene(source_path(file))), scene(description), camera(description.camera, width, height) {}
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

}  // namespace rt::testing
