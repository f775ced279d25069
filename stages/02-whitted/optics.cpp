#include "02-whitted/optics.h"

#include "common/task.h"

namespace rt {
namespace {

// sin^2 of the transmitted angle by Snell's law; above 1 means total internal reflection.
// [[maybe_unused]]: only the solutions call it, and the starter tree must build warning-free.
[[maybe_unused]] float sin2_transmitted(float cos_i, float eta_i, float eta_t) {
  const float eta = eta_i / eta_t;
  return eta * eta * std::max(0.0f, 1.0f - cos_i * cos_i);
}

}  // namespace

Vec3 reflect(Vec3 d, Vec3 n) {
  // BEGIN TASK stage2.optics.reflect
  return d - 2.0f * glm::dot(d, n) * n;
  // PLACEHOLDER
  // report_unfinished_task("stage2.optics.reflect");
  // (void)n;
  // return d;
  // END TASK
}

std::optional<Vec3> refract(Vec3 d, Vec3 n, float eta_i, float eta_t) {
  // BEGIN TASK stage2.optics.refract
  const float cos_i = -glm::dot(d, n);
  const float sin2_t = sin2_transmitted(cos_i, eta_i, eta_t);
  if (sin2_t > 1.0f) return std::nullopt;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  const float eta = eta_i / eta_t;
  return glm::normalize(eta * d + (eta * cos_i - cos_t) * n);
  // PLACEHOLDER
  // report_unfinished_task("stage2.optics.refract");
  // (void)n, (void)eta_i, (void)eta_t;
  // return d;  // straight through
  // END TASK
}

float fresnel_dielectric(float cos_i, float eta_i, float eta_t) {
  // BEGIN TASK stage2.optics.fresnel
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = sin2_transmitted(cos_i, eta_i, eta_t);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  const float r_s = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  const float r_p = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  return 0.5f * (r_s * r_s + r_p * r_p);
  // PLACEHOLDER
  // report_unfinished_task("stage2.optics.fresnel");
  // (void)cos_i, (void)eta_i, (void)eta_t;
  // return 0.0f;  // all light refracted
  // END TASK
}

float fresnel_schlick(float cos_i, float eta_i, float eta_t) {
  // BEGIN TASK stage2.optics.schlick
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = sin2_transmitted(cos_i, eta_i, eta_t);
  if (sin2_t >= 1.0f) return 1.0f;
  const float r0 = (eta_t - eta_i) / (eta_t + eta_i);
  // The curve is Schlick's fit in the angle on the thinner side; leaving glass that is theta_t.
  return schlick(r0 * r0, eta_i > eta_t ? std::sqrt(1.0f - sin2_t) : cos_i);
  // PLACEHOLDER
  // report_unfinished_task("stage2.optics.schlick");
  // (void)cos_i, (void)eta_i, (void)eta_t;
  // return 0.0f;  // all light refracted
  // END TASK
}

}  // namespace rt
