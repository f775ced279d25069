#include "06-light-transport/light_emission.h"

#include "02-whitted/ray_offset.h"
#include "04-radiometry/warp.h"
#include "common/frame.h"
#include "common/random.h"
#include "common/task.h"

namespace rt {

namespace {

// A sampled point is computed from a few products and sums of the shape's own coordinates; its
// rounding error is bounded by gamma_8 times the magnitudes involved (the same bound stage 2 gives a
// triangle's barycentric point, with room for the frame's extra products).
Vec3 sampled_point_error(Vec3 point, float extent) { return gamma_bound(8) * (glm::abs(point) + Vec3(extent)); }

}  // namespace

EmitterPoint sample_emitter_point(const AreaEmitter& emitter, int index, Vec2 u) {
  Vec3 point, normal;
  float extent = 0.0f;
  if (const auto* t = std::get_if<TriangleEmitter>(&emitter.geometry)) {
    const Vec3 b = sample_uniform_triangle(u);
    point = b.x * t->v0 + b.y * t->v1 + b.z * t->v2;
    normal = t->normal();
    extent = glm::length(t->v1 - t->v0) + glm::length(t->v2 - t->v0);
  } else if (const auto* r = std::get_if<RectangleEmitter>(&emitter.geometry)) {
    point = r->corner + u.x * r->edge_u + u.y * r->edge_v;
    normal = r->normal();
    extent = glm::length(r->edge_u) + glm::length(r->edge_v);
  } else if (const auto* d = std::get_if<DiskEmitter>(&emitter.geometry)) {
    const Frame frame = Frame::from_normal(d->normal);
    const Vec2 p = d->radius * sample_uniform_disk(u);
    point = d->center + p.x * frame.s + p.y * frame.t;
    normal = d->normal;
    extent = d->radius;
  } else {
    const SphereEmitter& s = std::get<SphereEmitter>(emitter.geometry);
    normal = sample_uniform_sphere(u);
    point = s.center + s.radius * normal;
    extent = s.radius;
  }
  EmitterPoint result;
  result.hit.point = point;
  result.hit.normal = result.hit.shading_normal = normal;
  result.hit.point_error = sampled_point_error(point, extent);
  result.hit.primitive = emitter.shape;
  result.emitter = index;
  return result;
}

std::optional<EmissionSample> sample_emission(const LightingScene& scene, float u_choice, Vec2 u_position,
                                              Vec2 u_direction) {
  if (scene.emitter_distribution().empty()) return std::nullopt;
  // BEGIN TASK stage6.light.emission
  const int index = scene.emitter_distribution().sample(u_choice).index;
  if (index < 0 || size_t(index) >= scene.emitters().size()) return std::nullopt;  // the environment's slot
  const AreaEmitter& emitter = scene.emitters()[size_t(index)];
  EmissionSample s;
  s.origin = sample_emitter_point(emitter, index, u_position);
  const Vec3 local = sample_cosine_hemisphere(u_direction);
  s.direction = Frame::from_normal(s.origin.hit.normal).to_world(local);
  s.radiance = emitter.radiance;
  s.pdf_position = emission_position_pdf(scene, index);
  s.pdf_direction = cosine_hemisphere_pdf(local);
  if (!(s.pdf_direction > 0.0f)) return std::nullopt;
  return s;
  // PLACEHOLDER
  // report_unfinished_task("stage6.light.emission");
  // (void)scene, (void)u_choice, (void)u_position, (void)u_direction;
  // return std::nullopt;  // no light leaves: light paths carry nothing
  // END TASK
}

float emission_position_pdf(const LightingScene& scene, int index) {
  if (index < 0 || size_t(index) >= scene.emitters().size()) return 0.0f;
  return scene.emitter_distribution().pmf(index) / scene.emitters()[size_t(index)].area();
}

float emission_direction_pdf(Vec3 front_normal, Vec3 w) { return std::max(0.0f, glm::dot(front_normal, w)) * kInvPi; }

PathVertex light_vertex(const EmitterPoint& point, Color radiance, float pdf_position) {
  PathVertex v;
  v.kind = VertexKind::light;
  v.hit = point.hit;
  v.emitter = point.emitter;
  v.pdf_fwd = pdf_position;
  v.beta = radiance / pdf_position;
  return v;
}

template <SamplerType S>
std::optional<LightSubpathStart> start_light_subpath(const LightingScene& scene, S& sampler,
                                                     const OffsetPolicy& offset) {
  const float u_choice = sampler.uniform();
  const Vec2 u_position = sampler.uniform2();
  const Vec2 u_direction = sampler.uniform2();
  const std::optional<EmissionSample> e = sample_emission(scene, u_choice, u_position, u_direction);
  if (!e || !(e->pdf_position > 0.0f)) return std::nullopt;
  LightSubpathStart start;
  start.origin = light_vertex(e->origin, e->radiance, e->pdf_position);
  start.ray = spawn_ray(e->origin.hit, e->direction, offset);
  const float cos_theta = glm::dot(e->origin.hit.normal, e->direction);
  start.beta = start.origin.beta * (cos_theta / e->pdf_direction);
  start.pdf_w = e->pdf_direction;
  return start;
}

template std::optional<LightSubpathStart> start_light_subpath(const LightingScene&, Rng&, const OffsetPolicy&);
template std::optional<LightSubpathStart> start_light_subpath(const LightingScene&, Sampler&, const OffsetPolicy&);

}  // namespace rt
