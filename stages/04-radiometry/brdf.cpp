#include "04-radiometry/brdf.h"

namespace rt {

Brdf make_brdf(const Material& material, const Hit& hit) {
  switch (material.type) {
    case MaterialType::diffuse:
      return Brdf(LambertBrdf{material.albedo_at(hit.point)});
    case MaterialType::phong:
      return Brdf(PhongBrdf{material.albedo, material.specular, material.shininess});
    case MaterialType::microfacet:
      return Brdf(MicrofacetBrdf{material.specular, material.roughness});
    case MaterialType::mirror:
      return Brdf(MirrorBrdf{material.reflectance});
    case MaterialType::dielectric:
      // The hit's normal faces the incoming ray, so wo is on the outside exactly when the ray hit
      // the front face.
      return hit.front_face ? Brdf(DielectricBsdf{1.0f, material.ior}) : Brdf(DielectricBsdf{material.ior, 1.0f});
  }
  return Brdf(LambertBrdf{Color(0.0f)});
}

}  // namespace rt
