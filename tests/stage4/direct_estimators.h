// The four direct-light estimators of stage 4 with their names, for the tests that check each one
// against the same closed form.
#pragma once

#include "04-radiometry/direct_lighting.h"

namespace rt::testing {

inline constexpr DirectEstimator kEstimators[] = {DirectEstimator::uniform_hemisphere, DirectEstimator::cosine_hemisphere,
                                                  DirectEstimator::brdf, DirectEstimator::light};

inline const char* estimator_name(DirectEstimator e) {
  switch (e) {
    case DirectEstimator::uniform_hemisphere: return "uniform";
    case DirectEstimator::cosine_hemisphere: return "cosine";
    case DirectEstimator::brdf: return "brdf";
    case DirectEstimator::light: return "light";
  }
  return "?";
}

}  // namespace rt::testing
