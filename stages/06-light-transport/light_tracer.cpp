#include "06-light-transport/light_tracer.h"

#include "common/task.h"

namespace rt {

template <SamplerType S>
void light_tracing_sample(const LightingScene& scene, const Camera& camera, const WalkSettings& walk, S& sampler,
                          std::vector<PathVertex>& light_path, std::vector<Splat>& splats) {
  light_path.clear();
  // BEGIN TASK stage6.lt.sample
  const std::optional<LightSubpathStart> start = start_light_subpath(scene, sampler, walk.offset);
  if (!start) return;
  light_path.push_back(start->origin);
  WalkSettings importance = walk;
  importance.mode = TransportMode::importance;
  random_walk(scene, start->ray, start->beta, start->pdf_w, importance, sampler, light_path);
  // The camera "subpath" is the pinhole alone.
  const PathVertex eye = camera_vertex(camera);
  for (int s = 1; s <= int(light_path.size()); ++s) {
    const StrategySample r = connect_strategy(scene, camera, std::span(&eye, 1), light_path, s, 1, nullptr, walk.offset);
    if (r.film_point) splats.push_back(Splat{*r.film_point, r.value});
  }
  // PLACEHOLDER
  // report_unfinished_task("stage6.lt.sample");
  // (void)scene, (void)camera, (void)walk, (void)sampler, (void)splats;
  // END TASK
}

template void light_tracing_sample(const LightingScene&, const Camera&, const WalkSettings&, Rng&,
                                   std::vector<PathVertex>&, std::vector<Splat>&);

}  // namespace rt
