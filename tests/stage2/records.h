// The plain-data forms (tests/support/record.h) of stage 2's results that its graded tests record.
#pragma once

#include "02-whitted/triangle_pack.h"
#include "02-whitted/triangle_ray.h"
#include "support/record.h"

namespace rt {

inline auto record_fields(TriangleHit& h) { return std::tie(h.t, h.b1, h.b2); }
inline auto record_fields(PackHit& h) { return std::tie(h.t, h.b1, h.b2, h.lane); }

}  // namespace rt
