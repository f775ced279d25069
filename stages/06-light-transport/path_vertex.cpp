#include "06-light-transport/path_vertex.h"

#include "05-path-tracing/path_tracer.h"
#include "06-light-transport/camera_importance.h"
#include "06-light-transport/light_emission.h"
#include "common/task.h"

namespace rt {

PathVertex camera_vertex(const Camera& camera) {
  PathVertex eye;
  eye.kind = VertexKind::camera;
  eye.hit.point = camera.position;
  eye.hit.normal = eye.hit.shading_normal = camera.forward;
  return eye;
}

float to_area_density(float pdf_w, const PathVertex& from, const PathVertex& to) {
  // BEGIN TASK stage6.bdpt.area_density
  const Vec3 d = to.point() - from.point();
  const float distance2 = glm::dot(d, d);
  if (!(distance2 > 0.0f)) return 0.0f;
  float pdf = pdf_w / distance2;
  if (to.kind != VertexKind::camera) pdf *= std::abs(glm::dot(to.normal(), d)) / std::sqrt(distance2);
  return pdf;
  // PLACEHOLDER
  // report_unfinished_task("stage6.bdpt.area_density");
  // (void)from, (void)to;
  // return pdf_w;
  // END TASK
}

float vertex_pdf(const Camera& camera, const PathVertex& v, const PathVertex* prev, const PathVertex& next) {
  const Vec3 w = v.direction_to(next);
  float pdf_w = 0.0f;
  if (v.kind == VertexKind::camera) {
    pdf_w = camera_direction_pdf(camera, w);
  } else if (v.kind == VertexKind::light) {
    pdf_w = emission_direction_pdf(v.normal(), w);
  } else if (v.delta) {
    pdf_w = delta_lobe_density(v, w);
  } else if (prev) {
    const ShadingPoint& at = *v.at;
    pdf_w = at.bsdf.pdf(at.frame.to_local(v.direction_to(*prev)), at.frame.to_local(w));
  }
  return to_area_density(pdf_w, v, next);
}

float delta_lobe_density(const PathVertex& v, Vec3 w) { return std::abs(glm::dot(v.hit.normal, w)); }

float light_origin_pdf(const LightingScene& scene, const PathVertex& v) {
  return v.emitter >= 0 ? emission_position_pdf(scene, v.emitter) : 0.0f;
}

float light_emission_pdf(const LightingScene& scene, const PathVertex& v, const PathVertex& next) {
  if (v.emitter < 0) return 0.0f;
  const Vec3 front = scene.emitters()[size_t(v.emitter)].normal_at(v.point());
  return to_area_density(emission_direction_pdf(front, v.direction_to(next)), v, next);
}

Color scattering(const PathVertex& v, Vec3 towards_camera, Vec3 towards_light) {
  const ShadingPoint& at = *v.at;
  const float cos_geometric = std::abs(glm::dot(v.hit.normal, towards_light));
  if (!(cos_geometric > 0.0f)) return Color(0.0f);
  const Color f = at.bsdf.eval(at.frame.to_local(towards_camera), at.frame.to_local(towards_light));
  return f * (std::abs(glm::dot(v.hit.shading_normal, towards_light)) / cos_geometric);
}

template <SamplerType S>
void random_walk(const LightingScene& scene, Ray ray, Color beta, float pdf_w, const WalkSettings& settings, S& sampler,
                 std::vector<PathVertex>& path) {
  const float beta_start = max_component(beta);
  if (!(beta_start > 0.0f)) return;
  const int max_vertices = std::min(settings.max_vertices, kMaxSubpathVertices);
  // BEGIN TASK stage6.bdpt.random_walk
  for (int bounce = 0; int(path.size()) < max_vertices; ++bounce) {
    const Vec2 u = sampler.uniform2();
    const std::optional<Hit> hit = scene.closest_hit(ray, Interval::positive());
    if (!hit) break;
    PathVertex v;
    v.hit = *hit;
    v.beta = beta;
    v.emitter = scene.emitter_index(*hit);
    v.pdf_fwd = to_area_density(pdf_w, path.back(), v);
    v.at = make_shading_point(scene, *hit, -ray.direction);
    v.delta = v.at->bsdf.is_delta();
    path.push_back(v);
    if (int(path.size()) >= max_vertices) break;

    const ShadingPoint& at = *path.back().at;
    const float u_lobe = at.bsdf.has_lobe_choice() ? sampler.uniform() : 0.5f;
    const std::optional<BsdfSample> s = at.sample(u, u_lobe, settings.mode);
    if (!s) break;
    const Vec3 wi = at.frame.to_world(s->wi);
    // The density of the way back: the BSDF sampling wo after arriving along wi.
    const float pdf_back = s->delta ? delta_lobe_density(path.back(), -ray.direction) : at.bsdf.pdf(s->wi, at.wo);
    pdf_w = s->delta ? delta_lobe_density(path.back(), wi) : s->pdf;
    beta *= s->weight;
    PathVertex& previous = path[path.size() - 2];
    previous.pdf_rev = to_area_density(pdf_back, path.back(), previous);
    ray = spawn_ray(*hit, wi, settings.offset);

    if (bounce + 1 >= settings.roulette_start) {
      const float p = survival_probability(Color(max_component(beta) / beta_start));
      if (!(sampler.uniform() < p)) break;
      beta /= p;
    }
  }
  // PLACEHOLDER
  // report_unfinished_task("stage6.bdpt.random_walk");
  // (void)scene, (void)ray, (void)beta, (void)pdf_w, (void)settings, (void)sampler, (void)path, (void)beta_start;
  // (void)max_vertices;
  // END TASK
}

template void random_walk(const LightingScene&, Ray, Color, float, const WalkSettings&, Rng&, std::vector<PathVertex>&);
// Any sampler behind the interface: stage 7's primary sample space.
template void random_walk(const LightingScene&, Ray, Color, float, const WalkSettings&, Sampler&,
                          std::vector<PathVertex>&);

}  // namespace rt
