#include "04-radiometry/bsdf.h"

namespace rt {

Bsdf make_bsdf(const Material& material, const Hit& hit) {
  switch (material.type) {
    case MaterialType::diffuse:
      return Bsdf(LambertBrdf{material.albedo_at(hit.point)});
    case MaterialType::phong:
      return Bsdf(PhongBrdf{material.albedo_at(hit.point), material.specular, material.shininess});
    case MaterialType::microfacet:
      return Bsdf(MicrofacetBrdf{material.specular, GgxDistribution{material.roughness}});
    case MaterialType::mirror:
      return Bsdf(MirrorBrdf{material.reflectance});
    case MaterialType::dielectric:
      // The hit's normal faces the incoming ray, so wo is on the outside exactly when the ray hit
      // the front face.
      return hit.front_face ? Bsdf(DielectricBsdf{1.0f, material.ior}) : Bsdf(DielectricBsdf{material.ior, 1.0f});
  }
  return Bsdf(LambertBrdf{Color(0.0f)});
}

}  // namespace rt
