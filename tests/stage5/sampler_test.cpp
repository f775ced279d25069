// Stage 5: the scrambled Sobol sampler keeps the (0,2)-sequence property in every pair of
// dimensions it hands out, and stays uniform.
#include "05-path-tracing/sobol_sampler.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <set>

namespace rt {
namespace {

TEST(SobolSampler, EveryElementaryBoxHoldsOnePoint) {
  // 2^k samples of one pixel: for every split of k into a + b, the 2^a x 2^b boxes each hold
  // exactly one point, in each of the first four dimension pairs.
  constexpr int k = 8, n = 1 << k;
  for (int pair = 0; pair < 4; ++pair) {
    std::vector<Vec2> points;
    for (int i = 0; i < n; ++i) {
      SobolSampler s(7, 123, std::uint64_t(i));
      Vec2 p(0.0f);
      for (int d = 0; d <= pair; ++d) p = RT_GRADED(s.uniform2)();
      points.push_back(p);
    }
    for (int a = 0; a <= k; ++a) {
      const int b = k - a;
      std::set<int> boxes;
      for (const Vec2 p : points) boxes.insert(int(p.x * float(1 << a)) * (1 << b) + int(p.y * float(1 << b)));
      EXPECT_EQ(int(boxes.size()), n) << "pair " << pair << ", boxes " << (1 << a) << " x " << (1 << b);
    }
  }
}

TEST(SobolSampler, PixelsAndPairsAreScrambledApart) {
  // Different pixels (and different pairs of one pixel) must not repeat the same points.
  SobolSampler a(1, 10, 5), b(1, 11, 5), c(2, 10, 5);
  const Vec2 pa = RT_GRADED(a.uniform2)(), pb = RT_GRADED(b.uniform2)(), pc = RT_GRADED(c.uniform2)();
  EXPECT_NE(pa, pb);
  EXPECT_NE(pa, pc);
  EXPECT_NE(pa, RT_GRADED(a.uniform2)());
}

TEST(SobolSampler, ScrambleIsNestedNotAShift) {
  // Owen scrambling flips bit k by a function of the bits above it: the top bit's flip is the same
  // for every x, the second bit's flip depends on the top bit only, and the map is a bijection.
  // A plain digital shift (x ^ seed) passes the first two but flips every x alike, so it fails
  // the third check, which asks that the flips of bit 30 differ between the two halves for most seeds.
  int seeds_where_halves_differ = 0;
  for (std::uint32_t seed = 1; seed <= 64; ++seed) {
    const std::uint32_t top_flip = (RT_GRADED(SobolSampler::scramble)(0u, seed) ^ 0u) >> 31;
    std::uint32_t second_flip[2] = {2, 2};
    Rng rng(seed, 0, 0);
    for (int k = 0; k < 256; ++k) {
      const std::uint32_t x = rng.next_u32();
      const std::uint32_t flips = RT_GRADED(SobolSampler::scramble)(x, seed) ^ x;
      EXPECT_EQ(flips >> 31, top_flip);
      const std::uint32_t half = x >> 31, flip = (flips >> 30) & 1u;
      if (second_flip[half] == 2) second_flip[half] = flip;
      EXPECT_EQ(second_flip[half], flip) << "bit 30 must depend on bit 31 alone";
    }
    ASSERT_NE(second_flip[0], 2u);  // both halves were drawn
    ASSERT_NE(second_flip[1], 2u);
    seeds_where_halves_differ += second_flip[0] != second_flip[1];
  }
  EXPECT_GT(seeds_where_halves_differ, 16);
}

TEST(SobolSampler, SecondDimensionTableMatchesTheGeneratorMatrix) {
  for (std::uint32_t i : {0u, 1u, 2u, 3u, 255u, 256u, 1000u, 65535u, 123456789u, 0xffffffffu}) {
    std::uint32_t expected = 0;
    std::uint32_t v = 1u << 31;
    for (std::uint32_t bits = i; bits != 0; bits >>= 1, v ^= v >> 1)
      if (bits & 1u) expected ^= v;
    EXPECT_EQ(SobolSampler::sobol_dimension1(i), expected) << i;
  }
  // The first points of Sobol's second dimension in index order: 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
  const double first[] = {0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (std::uint32_t i = 0; i < 8; ++i) EXPECT_EQ(SobolSampler::sobol_dimension1(i) * 0x1p-32, first[i]) << i;
}

TEST(SobolSampler, MeanOverManyPixelsIsOneHalf) {
  constexpr int kPixels = 4096, kSamples = 16;
  const double sum = testing::subject([] {
    double total = 0.0;
    for (int p = 0; p < kPixels; ++p)
      for (int i = 0; i < kSamples; ++i) {
        SobolSampler s(3, std::uint64_t(p), std::uint64_t(i));
        total += s.uniform() + s.uniform2().y;
      }
    return total;
  });
  // Uniform numbers have variance 1/12; the scrambled points are at least as good as independent.
  const double n = 2.0 * kPixels * kSamples;
  EXPECT_NEAR(sum / n, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n));
}

}  // namespace
}  // namespace rt
