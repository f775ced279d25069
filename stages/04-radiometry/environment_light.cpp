#include "04-radiometry/environment_light.h"

#include "04-radiometry/warp.h"
#include "common/display_transform.h"
#include "common/spherical.h"
#include "common/task.h"

#include <algorithm>
#include <cmath>

namespace rt {

EnvironmentLight::EnvironmentLight(const Environment& environment, EnvironmentSampling strategy)
    : image_(environment.image),
      scale_(environment.scale),
      cos_rotation_(std::cos(radians(environment.rotation_degrees))),
      sin_rotation_(std::sin(radians(environment.rotation_degrees))) {
  if (!image_ || strategy == EnvironmentSampling::uniform) return;
  const int width = image_->width(), height = image_->height();
  std::vector<float> f(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y) {
    const float sin_theta = std::sin(kPi * (float(y) + 0.5f) / float(height));
    for (int x = 0; x < width; ++x) f[size_t(y) * size_t(width) + size_t(x)] = luminance(image_->at(x, y)) * sin_theta;
  }
  distribution_.emplace(f, width, height);
}

// A rotation by alpha about +y: x' = x cos(alpha) + z sin(alpha), z' = -x sin(alpha) + z cos(alpha).
Vec3 EnvironmentLight::to_world(Vec3 d) const {
  return Vec3(d.x * cos_rotation_ + d.z * sin_rotation_, d.y, -d.x * sin_rotation_ + d.z * cos_rotation_);
}
Vec3 EnvironmentLight::to_local(Vec3 w) const {
  return Vec3(w.x * cos_rotation_ - w.z * sin_rotation_, w.y, w.x * sin_rotation_ + w.z * cos_rotation_);
}

Color EnvironmentLight::texel(Vec2 st) const {
  const int x = std::clamp(int(st.x * float(image_->width())), 0, image_->width() - 1);
  const int y = std::clamp(int(st.y * float(image_->height())), 0, image_->height() - 1);
  return scale_ * image_->at(x, y);
}

Color EnvironmentLight::radiance(Vec3 w) const {
  if (!image_) return scale_;
  const Vec2 uv = latlong_uv(to_local(w));
  return texel(Vec2(uv.x, 1.0f - uv.y));
}

std::optional<EnvironmentSample> EnvironmentLight::sample(Vec2 u) const {
  if (!uses_table()) {
    const Vec3 w = sample_uniform_sphere(u);
    return EnvironmentSample{w, uniform_sphere_pdf(), radiance(w)};
  }
  // BEGIN TASK stage4.env.sample
  const PiecewiseConstant2D::Sample st = distribution_->sample(u);
  const float theta = kPi * st.st.y, phi = 2.0f * kPi * st.st.x;
  const float sin_theta = std::sin(theta);
  if (!(sin_theta > 0.0f) || !(st.pdf > 0.0f)) return std::nullopt;
  const Vec3 local(sin_theta * std::cos(phi), std::cos(theta), sin_theta * std::sin(phi));
  return EnvironmentSample{to_world(local), st.pdf / (2.0f * kPi * kPi * sin_theta), texel(st.st)};
  // PLACEHOLDER
  // report_unfinished_task("stage4.env.sample");
  // return EnvironmentSample{sample_uniform_sphere(u), uniform_sphere_pdf(), radiance(sample_uniform_sphere(u))};
  // END TASK
}

float EnvironmentLight::pdf(Vec3 w) const {
  if (!uses_table()) return uniform_sphere_pdf();
  // BEGIN TASK stage4.env.pdf
  const Vec3 d = to_local(w);
  const float sin_theta = std::sqrt(d.x * d.x + d.z * d.z);
  if (!(sin_theta > 0.0f)) return 0.0f;
  const Vec2 uv = latlong_uv(d);
  return distribution_->pdf(Vec2(uv.x, 1.0f - uv.y)) / (2.0f * kPi * kPi * sin_theta);
  // PLACEHOLDER
  // report_unfinished_task("stage4.env.pdf");
  // (void)w;
  // return uniform_sphere_pdf();
  // END TASK
}

float EnvironmentLight::power(float scene_radius) const {
  // integral L dw, texel by texel: a row from theta0 to theta1 spans 2 pi (cos theta0 - cos theta1)
  // steradians, shared by its columns.
  double integral = 0.0;
  if (!image_) {
    integral = 4.0 * double(kPi) * double(luminance(scale_));
  } else {
    const int width = image_->width(), height = image_->height();
    for (int y = 0; y < height; ++y) {
      const double band = 2.0 * double(kPi) *
                          (std::cos(double(kPi) * y / height) - std::cos(double(kPi) * (y + 1) / height)) / width;
      for (int x = 0; x < width; ++x) integral += double(luminance(scale_ * image_->at(x, y))) * band;
    }
  }
  return float(double(kPi) * double(scene_radius) * double(scene_radius) * integral);
}

}  // namespace rt
