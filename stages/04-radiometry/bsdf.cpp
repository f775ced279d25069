#include "04-radiometry/bsdf.h"

#include "04-radiometry/texture.h"

namespace rt {

namespace {

// A reflectance at the hit: its texture's value at the hit's (u, v), or the constant.
Color albedo_at(const Material& material, const Hit& hit) {
  return material.albedo_texture ? texture_lookup(*material.albedo_texture, hit.uv) : material.albedo_at(hit.point);
}
Color specular_at(const Material& material, const Hit& hit) {
  return material.specular_texture ? texture_lookup(*material.specular_texture, hit.uv) : material.specular;
}

}  // namespace

Bsdf make_bsdf(const Material& material, const Hit& hit) {
  switch (material.type) {
    case MaterialType::diffuse:
      return Bsdf(LambertBrdf{albedo_at(material, hit)});
    case MaterialType::phong:
      return Bsdf(PhongBrdf{albedo_at(material, hit), specular_at(material, hit), material.shininess});
    case MaterialType::microfacet:
      return Bsdf(MicrofacetBrdf{specular_at(material, hit), GgxDistribution{material.roughness}});
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
