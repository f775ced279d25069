// The pixel rectangles stage 6's scenes are about, at 128 x 96 (shared by the tests and by
// benchmarks/transport_error_vs_time.cpp). Found on the converged references
// (assets/references/README.md).
#pragma once

#include "common/image.h"

namespace rt {

// caustic.json: the bright caustic on the floor in front of the ball, below its silhouette (the
// rows above show the caustic through the ball's lower edge, light -> glass -> floor -> glass ->
// eye, which only photon mapping samples). In caustic-through-glass.json the same pixels show the
// caustic through the pane of glass.
inline constexpr PixelRect kCausticRegion{46, 67, 66, 71};
// caustic.json: inside the ball's silhouette, where every path to the camera leaves glass.
inline constexpr PixelRect kBallRegion{56, 30, 72, 44};

// light-through-gap.json: the floor and wall left of the gap, lit only after bounces on the far
// side of the partition.
inline constexpr PixelRect kRoomRegion{0, 48, 64, 96};

}  // namespace rt
