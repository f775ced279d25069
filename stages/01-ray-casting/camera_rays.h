// Stage 1, tasks stage1.camera.ray and stage1.camera.thin_lens: from a point on the film (and a
// point on the lens) to a ray into the scene.
#pragma once

#include "common/camera.h"
#include "common/ray.h"

namespace rt {

// Task stage1.camera.ray: the pinhole.
// `film_point` is in pixel units: (0, 0) is the top-left corner of the image, (width, height) the
// bottom-right corner, so pixel (x, y) covers [x, x+1) x [y, y+1) and its centre is (x+.5, y+.5).
// Returns the ray from the camera position through that point, with a normalized direction.
//
// The film sits at distance 1 in front of the pinhole. Its half height is tan(vfov / 2) and its half
// width is aspect times that, so the point maps to
//   s_x = (2 x / W - 1) * aspect * tan(vfov/2),   s_y = (1 - 2 y / H) * tan(vfov/2)
//   d   = normalize(forward + s_x * right + s_y * up)
// (s_y flips sign because image rows grow downwards while `up` points up).
Ray generate_camera_ray(const Camera& camera, Vec2 film_point);

// Task stage1.camera.thin_lens: the thin lens (Kolb, Mitchell and Hanrahan, "A Realistic Camera
// Model for Computer Graphics", SIGGRAPH 1995, section 3; PBR 4th ed. section 5.2.3).
// An ideal thin lens brings every ray from one film point to one point of the focal plane, the
// plane at `focus_distance` along `forward`. That point is where the pinhole ray through the film
// point meets the plane, so the lens ray starts at a point of the lens, a disk of radius
// `aperture_radius` about `position` spanned by `right` and `up`, and aims at it:
//   p_focus = position + (focus_distance / dot(d, forward)) d      (d: the pinhole ray's direction)
//   (l_x, l_y) = aperture_radius * sample_uniform_disk(lens_sample)  (01-ray-casting/disk_sampling.h)
//   origin = position + l_x right + l_y up,   direction = normalize(p_focus - origin).
// A point at distance z along `forward` is therefore seen from a disk of film points, its circle
// of confusion, of diameter 2 a |1/s - 1/z| at the film's distance 1 (a the aperture radius, s the
// focus distance): the thin-lens formula C = A f |z - s| / (z (s - f)) with the film scaled to
// distance 1 (docs/stage1.md, "The thin lens"). With aperture_radius == 0 this is exactly the
// pinhole ray (the same bits), so every pinhole scene renders as it did.
Ray generate_lens_ray(const Camera& camera, Vec2 film_point, Vec2 lens_sample);

}  // namespace rt
