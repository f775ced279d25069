// Closed-form answers for the stage-4 and stage-5 tests: configuration factors from a differential
// area element to an emitter, after Howell's catalogue ("A Catalog of Radiation Heat Transfer
// Configuration Factors", 3rd ed., University of Texas at Austin). For a Lambertian emitter of
// radiance L, the irradiance at the element is E = pi L F, and a Lambertian receiver of albedo rho
// sends back L_r = rho E / pi = rho L F.
#pragma once

#include <cmath>

namespace rt::testing {

// Howell B-3 (also Siegel & Howell): element parallel to a rectangle a x b at distance c, the
// element's normal passing through a corner of the rectangle. With A = a / c, B = b / c:
//   F = 1/(2 pi) [ A / sqrt(1 + A^2) atan(B / sqrt(1 + A^2)) + B / sqrt(1 + B^2) atan(A / sqrt(1 + B^2)) ].
inline double factor_to_corner_rectangle(double a, double b, double c) {
  const double A = a / c, B = b / c;
  const double sa = std::sqrt(1.0 + A * A), sb = std::sqrt(1.0 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * M_PI);
}

// A square of side s centred above the element at height h: four corner rectangles s/2 x s/2.
inline double factor_to_centred_square(double side, double h) {
  return 4.0 * factor_to_corner_rectangle(0.5 * side, 0.5 * side, h);
}

// Howell B-13: element parallel to a coaxial disk of radius R at distance h: F = R^2 / (R^2 + h^2).
inline double factor_to_coaxial_disk(double radius, double h) { return radius * radius / (radius * radius + h * h); }

// A sphere of radius R whose centre is at distance d along the element's normal (wholly above the
// element's plane): F = (R / d)^2 (Howell B-20 with the sphere on the normal).
inline double factor_to_sphere_on_normal(double radius, double d) { return (radius / d) * (radius / d); }

}  // namespace rt::testing
