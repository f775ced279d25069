// Stage 1, task stage1.plane.intersect: ray-plane intersection.
#pragma once

#include "common/interval.h"
#include "common/ray.h"
#include "common/scene.h"

#include <optional>

namespace rt {

// The plane (p - p0).n = 0 meets o + t d at t = (p0 - o).n / (d.n). A ray parallel to the plane
// (d.n = 0) never hits it, not even when it lies inside the plane; the division must not be
// allowed to produce inf or NaN hits.
std::optional<float> intersect_plane(const Ray& ray, const Plane& plane, Interval range);

}  // namespace rt
