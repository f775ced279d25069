// Stage 6: the camera as a sensor. Path tracing starts at the camera and never asks how sensitive it
// is; light tracing ends there, so it needs the camera's importance We: how much a unit of radiance
// arriving along a direction counts towards the image (Veach's thesis, section 4.5; PBR 4th ed.
// section 5.4). For the pinhole of stage 1, film at distance 1 of area A (in the pinhole's units),
// the image is I = integral over the film of L, and changing variables to the solid angle at the
// pinhole (dA = dw / cos^3(theta)) and then to projected solid angle gives
//     We(w) = 1 / (A cos^4(theta))   for w inside the film's frustum, 0 outside,
// theta the angle between w and the view direction. That counts the whole film as one
// measurement; a pixel's share is We times the number of pixels, which is why a light-tracing
// splat (one light path per camera path) is divided by the samples per pixel, not by the paths
// (docs/stage6.md, section 3). The camera also samples directions: uniformly over the film, a
// density of 1 / (A cos^3(theta)) per unit solid angle.
#pragma once

#include "common/camera.h"

#include <optional>

namespace rt {

// The film's area at distance 1 from the pinhole: (2 tan(vfov / 2) aspect) (2 tan(vfov / 2)).
float film_area(const Camera& camera);

// Task stage6.camera.project. The film point (in pixels, as stage 1's generate_camera_ray takes it)
// where the pinhole sees the world point p: the inverse of generate_camera_ray. Nothing when p is
// behind the camera or its film point falls outside [0, width) x [0, height).
std::optional<Vec2> project_to_film(const Camera& camera, Vec3 p);

// Task stage6.camera.importance. We(w) = 1 / (A cos^4(theta)) for a unit direction w leaving the
// pinhole inside the film's frustum, 0 otherwise (behind it, or outside the film).
float camera_importance(const Camera& camera, Vec3 w);

// The density per unit solid angle with which the pixel loop's rays (uniform over the film) leave
// the pinhole along w: 1 / (A cos^3(theta)) inside the frustum, 0 outside.
float camera_direction_pdf(const Camera& camera, Vec3 w);

}  // namespace rt
