// The plain-data forms (tests/support/record.h) of stage 6's results that its graded tests record.
#pragma once

#include "06-light-transport/bdpt.h"
#include "06-light-transport/light_emission.h"
#include "06-light-transport/sppm.h"
#include "support/record.h"

namespace rt {

inline auto record_fields(EmitterPoint& p) { return std::tie(p.hit, p.emitter); }
inline auto record_fields(EmissionSample& s) {
  return std::tie(s.origin, s.direction, s.radiance, s.pdf_position, s.pdf_direction);
}
inline auto record_fields(StrategySample& s) { return std::tie(s.value, s.film_point); }
inline auto record_fields(PhotonStatistics& s) { return std::tie(s.photons, s.radius, s.tau); }

}  // namespace rt
