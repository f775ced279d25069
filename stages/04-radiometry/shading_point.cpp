#include "04-radiometry/shading_point.h"

namespace rt {

std::optional<BsdfSample> ShadingPoint::sample(Vec2 u, float u_lobe, TransportMode mode) const {
  std::optional<BsdfSample> s = bsdf.sample(wo, u, u_lobe, mode);
  if (!s || mode == TransportMode::radiance || hit.shading_normal == hit.normal) return s;
  // The shading frame's z is n_s, so |wo.n_s| = |wo.z|; the geometric normal in that frame gives
  // the other two.
  const Vec3 ng = frame.to_local(hit.normal);
  const float denominator = std::abs(glm::dot(wo, ng)) * std::abs(s->wi.z);
  s->weight *= denominator > 0.0f ? std::abs(wo.z) * std::abs(glm::dot(s->wi, ng)) / denominator : 0.0f;
  return s;
}

ShadingPoint make_shading_point(const LightingScene& scene, const Hit& hit, Vec3 towards_viewer) {
  const Frame frame = Frame::from_normal(hit.shading_normal);
  return ShadingPoint{hit, make_bsdf(scene.material(hit), hit), frame, frame.to_local(towards_viewer)};
}

}  // namespace rt
