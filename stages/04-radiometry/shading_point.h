// Stage 4: a point where light scatters: the hit, its BSDF, its shading frame and wo in that frame.
#pragma once

#include "04-radiometry/bsdf.h"
#include "04-radiometry/lighting_scene.h"
#include "common/frame.h"

#include <optional>

namespace rt {

struct ShadingPoint {
  Hit hit;
  Bsdf bsdf;
  Frame frame;  // about the shading normal
  Vec3 wo;      // local, towards where the path came from (the viewer, for a camera path)

  // The BSDF sampled for a path carrying `mode`. An interpolated shading normal n_s makes even a
  // symmetric BSDF's scattering non-symmetric: an estimator weighs its cosines with n_s where the
  // geometry has n_g, so the adjoint of f_s(wo, wi) |wi.n_s| is f_s |wo.n_s| |wi.n_g| / |wo.n_g|
  // (Veach's thesis, section 5.3, eq. 5.19). For importance the weight therefore carries
  //     |wo.n_s| |wi.n_g| / (|wo.n_g| |wi.n_s|),
  // 1 where the two normals agree; only the cosines' magnitudes enter.
  std::optional<BsdfSample> sample(Vec2 u, float u_lobe, TransportMode mode = TransportMode::radiance) const;
};

ShadingPoint make_shading_point(const LightingScene& scene, const Hit& hit, Vec3 towards_viewer);

}  // namespace rt
