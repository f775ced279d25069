#include "06-light-transport/bdpt.h"

#include "06-light-transport/camera_importance.h"
#include "06-light-transport/light_emission.h"
#include "common/task.h"

#include <array>

namespace rt {

float strategy_weight(std::span<const VertexDensity> camera, std::span<const VertexDensity> light) {
  // BEGIN TASK stage6.bdpt.mis_weight
  const auto remap = [](float pdf) { return double(pdf != 0.0f ? pdf : 1.0f); };
  double sum = 0.0, ratio = 1.0;
  for (size_t i = camera.size(); i-- > 1;) {
    ratio *= remap(camera[i].rev) / remap(camera[i].fwd);
    if (!camera[i].delta && !camera[i - 1].delta) sum += ratio * ratio;
  }
  ratio = 1.0;
  for (size_t i = light.size(); i-- > 0;) {
    ratio *= remap(light[i].rev) / remap(light[i].fwd);
    const bool after_delta = i > 0 && light[i - 1].delta;
    if (!light[i].delta && !after_delta) sum += ratio * ratio;
  }
  return float(1.0 / (1.0 + sum));
  // PLACEHOLDER
  // report_unfinished_task("stage6.bdpt.mis_weight");
  // return 1.0f / float(camera.size() + light.size() - 1);  // all strategies alike (wrong for deltas)
  // END TASK
}

float mis_weight(const LightingScene& scene, const Camera& camera, std::span<const PathVertex> camera_path,
                 std::span<const PathVertex> light_path, int s, int t, const PathVertex* sampled_light) {
  std::array<VertexDensity, kMaxSubpathVertices> z_density, y_density;
  for (int i = 0; i < t; ++i) {
    const PathVertex& v = camera_path[size_t(i)];
    z_density[size_t(i)] = {v.pdf_fwd, v.pdf_rev, v.delta};
  }
  const PathVertex* y = nullptr;
  for (int i = 0; i < s; ++i) {
    const PathVertex& v = (i == 0 && sampled_light) ? *sampled_light : light_path[size_t(i)];
    y_density[size_t(i)] = {v.pdf_fwd, v.pdf_rev, v.delta};
    y = &v;
  }
  // The densities the joined path gives the vertices at the connection (PBR 3rd ed. section
  // 16.3.4): z = z_t-1 and y = y_s-1 sampled from each other, and their predecessors from them.
  const PathVertex& z = camera_path[size_t(t - 1)];
  const PathVertex* z_before = t > 1 ? &camera_path[size_t(t - 2)] : nullptr;
  const PathVertex* y_before = s > 1 ? &light_path[size_t(s - 2)] : nullptr;
  VertexDensity& zd = z_density[size_t(t - 1)];
  zd.rev = s > 0 ? vertex_pdf(camera, *y, y_before, z) : light_origin_pdf(scene, z);
  zd.delta = false;
  if (z_before)
    z_density[size_t(t - 2)].rev = s > 0 ? vertex_pdf(camera, z, y, *z_before) : light_emission_pdf(scene, z, *z_before);
  if (s > 0) {
    VertexDensity& yd = y_density[size_t(s - 1)];
    yd.rev = vertex_pdf(camera, z, z_before, *y);
    yd.delta = false;
  }
  if (y_before) y_density[size_t(s - 2)].rev = vertex_pdf(camera, *y, &z, *y_before);
  return strategy_weight(std::span(z_density.data(), size_t(t)), std::span(y_density.data(), size_t(s)));
}

StrategySample connect_strategy(const LightingScene& scene, const Camera& camera,
                                std::span<const PathVertex> camera_path, std::span<const PathVertex> light_path,
                                int s, int t, const PathVertex* light_point, const OffsetPolicy& offset) {
  StrategySample out;
  // BEGIN TASK stage6.bdpt.connect
  const PathVertex& z = camera_path[size_t(t - 1)];
  if (s == 0) {
    if (t >= 2 && z.emitter >= 0) out.value = z.beta * scene.emitted(z.hit);
    return out;
  }
  const PathVertex& y = light_point ? *light_point : light_path[size_t(s - 1)];
  if (y.delta || z.delta) return out;
  if (t == 1) {
    // The light tracer's connection: y as the pinhole sees it.
    const std::optional<Vec2> film = project_to_film(camera, y.point());
    if (!film) return out;
    const Vec3 to_camera = camera.position - y.point();
    const float distance2 = glm::dot(to_camera, to_camera);
    const Vec3 w = to_camera / std::sqrt(distance2);
    const Color f = y.kind == VertexKind::light ? emission_towards(y, w)
                                                : scattering(y, w, y.direction_to(light_path[size_t(s - 2)]));
    const float cos_camera = glm::dot(camera.forward, -w);
    const Color value = y.beta * f *
                        (std::abs(glm::dot(y.normal(), w)) * camera_importance(camera, -w) * cos_camera / distance2);
    if (value == Color(0.0f)) return out;
    const ShadowRay shadow = spawn_shadow_ray(y.hit, camera.position, offset);
    if (scene.occluded(shadow.ray, shadow.range)) return out;
    out.value = value;
    out.film_point = film;
    return out;
  }
  const Vec3 d = y.point() - z.point();
  const float distance2 = glm::dot(d, d);
  if (!(distance2 > 0.0f)) return out;
  const Vec3 w = d / std::sqrt(distance2);  // from z towards y
  const Color fz = scattering(z, z.direction_to(camera_path[size_t(t - 2)]), w);
  const Color fy = y.kind == VertexKind::light ? emission_towards(y, -w)
                                               : scattering(y, -w, y.direction_to(light_path[size_t(s - 2)]));
  const float g = std::abs(glm::dot(z.normal(), w)) * std::abs(glm::dot(y.normal(), w)) / distance2;
  const Color value = z.beta * fz * fy * y.beta * g;
  if (value == Color(0.0f)) return out;
  const ShadowRay shadow = spawn_shadow_ray(z.hit, y.point(), offset);
  if (scene.occluded(shadow.ray, shadow.range)) return out;
  out.value = value;
  return out;
  // PLACEHOLDER
  // report_unfinished_task("stage6.bdpt.connect");
  // (void)scene, (void)camera, (void)camera_path, (void)light_path, (void)s, (void)t, (void)light_point;
  // (void)offset;
  // return out;
  // END TASK
}

std::optional<PathVertex> sample_light_vertex(const LightingScene& scene, float u_choice, Vec2 u) {
  if (scene.emitter_distribution().empty()) return std::nullopt;
  const int index = scene.emitter_distribution().sample(u_choice).index;
  if (index < 0 || size_t(index) >= scene.emitters().size()) return std::nullopt;
  const AreaEmitter& emitter = scene.emitters()[size_t(index)];
  const float pdf_position = emission_position_pdf(scene, index);
  if (!(pdf_position > 0.0f)) return std::nullopt;
  return light_vertex(sample_emitter_point(emitter, index, u), emitter.radiance, pdf_position);
}

template <SamplerType S>
Color bdpt_sample(const LightingScene& scene, const Camera& camera, const Ray& camera_ray, const BdptOptions& options,
                  S& sampler, std::vector<PathVertex>& camera_path, std::vector<PathVertex>& light_path,
                  std::vector<Splat>& splats) {
  camera_path.clear();
  light_path.clear();
  camera_path.push_back(camera_vertex(camera));
  // One strategy alone needs subpaths no longer than its own (a light subpath of one vertex, the
  // light point, costs no ray).
  WalkSettings camera_walk = options.walk, light_walk = options.walk;
  camera_walk.mode = TransportMode::radiance;
  light_walk.mode = TransportMode::importance;
  if (!options.only.all()) {
    camera_walk.max_vertices = options.only.t;
    light_walk.max_vertices = std::max(options.only.s, 1);
  }
  random_walk(scene, camera_ray, Color(1.0f), camera_direction_pdf(camera, camera_ray.direction), camera_walk, sampler,
              camera_path);
  if (const std::optional<LightSubpathStart> start = start_light_subpath(scene, sampler, light_walk.offset)) {
    light_path.push_back(start->origin);
    random_walk(scene, start->ray, start->beta, start->pdf_w, light_walk, sampler, light_path);
  }
  const OffsetPolicy& offset = options.walk.offset;

  Color radiance(0.0f);
  const int nc = int(camera_path.size()), nl = int(light_path.size());
  for (int t = 1; t <= nc; ++t)
    for (int s = 0; s <= nl; ++s) {
      if (s + t < 2 || (!options.only.all() && (s != options.only.s || t != options.only.t))) continue;
      // s = 1 with t >= 2 is next-event estimation: a fresh light point for each camera vertex, as
      // a path tracer samples one; t = 1 connects the light subpath's own start.
      std::optional<PathVertex> fresh;
      if (s == 1 && t >= 2) {
        if (camera_path[size_t(t - 1)].delta) continue;  // no numbers drawn for a connection that cannot be
        const float u_choice = sampler.uniform();
        fresh = sample_light_vertex(scene, u_choice, sampler.uniform2());
        if (!fresh) continue;
      }
      const PathVertex* light_point = fresh ? &*fresh : nullptr;
      const StrategySample r = connect_strategy(scene, camera, camera_path, light_path, s, t, light_point, offset);
      if (r.value == Color(0.0f)) continue;
      const float w = options.only.all() ? mis_weight(scene, camera, camera_path, light_path, s, t, light_point) : 1.0f;
      if (t == 1) {
        splats.push_back(Splat{*r.film_point, r.value * w});
      } else {
        radiance += r.value * w;
      }
    }
  return radiance;
}

template Color bdpt_sample(const LightingScene&, const Camera&, const Ray&, const BdptOptions&, Rng&,
                           std::vector<PathVertex>&, std::vector<PathVertex>&, std::vector<Splat>&);
// Any sampler behind the interface: stage 7's primary sample space.
template Color bdpt_sample(const LightingScene&, const Camera&, const Ray&, const BdptOptions&, Sampler&,
                           std::vector<PathVertex>&, std::vector<PathVertex>&, std::vector<Splat>&);

}  // namespace rt
