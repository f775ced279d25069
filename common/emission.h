// The one emission rule of every stage: an emitting surface is one-sided, Lambertian. Its radiance
// Le leaves the front (outward) side, the same in every direction there, and nothing leaves the
// back: a quad light on a ceiling lights the room, not the attic, and an emitter seen from behind
// is black.
#pragma once

#include "common/hit.h"
#include "common/scene.h"

namespace rt {

// Le leaving a surface towards a point on its front side (front_side true), or from its back.
inline Color front_side_emission(const Color& emission, bool front_side) { return front_side ? emission : Color(0.0f); }

// Le leaving a hit point back along the ray that found it.
inline Color front_side_emission(const Material& material, const Hit& hit) {
  return front_side_emission(material.emission, hit.front_face);
}

}  // namespace rt
