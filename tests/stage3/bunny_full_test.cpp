#include "stage3/bvh_test_support.h"

namespace rt {
namespace {

// The full check: every builder against brute force on 100,000 rays through
// the bunny (about 7e9 ray-triangle tests; minutes, hence the "slow" label).
TEST(BunnyFull, EveryBuilderAgreesWithNaiveOnHundredThousandRays) {
  expect_builders_agree_with_naive(bunny(), random_rays(*bunny(), 100000, 5));
}

}  // namespace
}  // namespace rt
