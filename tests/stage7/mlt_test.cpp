// Stage 7's Metropolis light transport. The small step by hand at the wrap-around and after several
// steps at once; its offsets symmetric (chi-square); the primary sample space reproducible per index
// and restored by a rejection; a chain on a toy target over [0, 1]^2 with a known integral visits
// each bin in proportion to it (chi-square on batch means, so correlation cannot fake a pass) and
// its expected-value records weigh the same; and on the Cornell box the bootstrap's b and the
// image's region means against the reference, for both inner samplers and for large steps alone.
#include "07-vcm-mlt/mlt.h"
#include "common/image_io.h"

#include "stage6/cornell_regions.h"
#include "stage6/loaded_scene.h"
#include "stage6/transport_estimates.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rt {
namespace {

// The u that makes Box–Muller's normal number exactly `z` >= 0: u1 = 1 - exp(-z^2 / 2), u2 = 0.
Vec2 normal_of(float z) { return Vec2(1.0f - std::exp(-0.5f * z * z), 0.0f); }

TEST(SmallStep, ByHandAtTheWrapAndAfterSeveralSteps) {
  const std::vector<float> x = testing::subject([] {
    return std::vector<float>{small_step(0.5f, 1, 0.01f, normal_of(1.0f)),
                              small_step(0.995f, 4, 0.01f, normal_of(1.0f)),  // 0.995 + 0.02 wraps to 0.015
                              small_step(0.3f, 0, 0.01f, normal_of(1.0f)),    // no step: no move
                              small_step(0.005f, 1, 0.01f, Vec2(1.0f - std::exp(-0.5f), 0.5f)),  // z = -1: to 0.995
                              small_step(0.999999f, 1, 0.5f, normal_of(0.0f))};
  });
  ASSERT_EQ(x.size(), 5u);
  EXPECT_NEAR(x[0], 0.51f, 1e-5f);
  EXPECT_NEAR(x[1], 0.015f, 1e-5f);  // the deviation of 4 steps is 2 sigma
  EXPECT_EQ(x[2], 0.3f);
  EXPECT_NEAR(x[3], 0.995f, 1e-5f);
  EXPECT_LT(x[4], 1.0f);  // never 1, whatever the rounding
  for (const float v : x) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LT(v, 1.0f);
  }
}

TEST(SmallStep, OffsetsAreSymmetricWithTheirDeviation) {
  // T(u -> v) = T(v -> u) for a wrapped offset whose density is even: the offsets' histogram over
  // +-4 sigma, folded, has the same counts on both sides (chi-square, 8 bins a side), and their
  // deviation after n steps is sigma sqrt(n).
  const float sigma = 0.02f;
  const std::vector<float> offsets = testing::subject([&] {
    std::vector<float> out;
    Rng rng(42, 0, 0);
    for (int i = 0; i < 40000; ++i) {
      const float x = rng.uniform();
      const int n = 1 + i % 4;
      const float u1 = rng.uniform();
      float d = small_step(x, n, sigma, Vec2(u1, rng.uniform())) - x;
      d -= std::round(d);  // the shorter way round
      out.push_back(d / std::sqrt(float(n)));
    }
    return out;
  });
  ASSERT_EQ(offsets.size(), 40000u);
  double chi2 = 0.0, sum2 = 0.0;
  std::vector<double> left(8, 0.0), right(8, 0.0);
  for (const float d : offsets) {
    sum2 += double(d) * d;
    const int bin = int(std::abs(d) / (0.5f * sigma));
    if (bin < 8) (d < 0 ? left : right)[size_t(bin)] += 1.0;
  }
  for (int b = 0; b < 8; ++b)
    if (left[size_t(b)] + right[size_t(b)] > 0)
      chi2 += std::pow(left[size_t(b)] - right[size_t(b)], 2) / (left[size_t(b)] + right[size_t(b)]);
  EXPECT_LT(chi2, 26.1);  // chi-square with 8 degrees of freedom, 0.1 % above
  // The per-step deviation: sigma within 2 % (40,000 samples give the variance to 0.7 %).
  EXPECT_NEAR(std::sqrt(sum2 / double(offsets.size())), sigma, 0.02 * sigma);
}

TEST(PrimarySampleSpace, EachIndexItsOwnNumbersAndARejectionRestoresThem) {
  const auto [first, again, other, after_reject, kept] = testing::subject([] {
    const auto read = [](PrimarySampleSpace& s) {
      std::vector<float> v;
      for (const PrimarySampleSpace::Stream stream : {PrimarySampleSpace::camera, PrimarySampleSpace::light}) {
        s.start_stream(stream);
        for (int i = 0; i < 4; ++i) v.push_back(s.uniform());
      }
      return v;
    };
    PrimarySampleSpace a(7, 3, 0.01f, 0.0f), b(7, 3, 0.01f, 0.0f), c(7, 4, 0.01f, 0.0f);
    const std::vector<float> first = read(a), again = read(b), other = read(c);
    a.start_iteration();  // a small step (large steps have probability 0)
    read(a);
    a.reject();
    // Zero-length small steps from here on: what is read is the state the rejection left.
    PrimarySampleSpace still(7, 3, 0.0f, 0.0f);
    read(still);
    still.start_iteration();
    const std::vector<float> moved = read(still);
    still.reject();
    still.start_iteration();
    return std::tuple(first, again, other, read(still), moved);
  });
  EXPECT_EQ(first, again);  // a chain started from bootstrap sample i draws its numbers again
  EXPECT_NE(first, other);
  EXPECT_EQ(after_reject, kept);
}

// The toy target over [0, 1]^2: f(x, y) = 0.2 + x y^2, whose integral over a cell is
// 0.2 dx dy + (x1^2 - x0^2)(y1^3 - y0^3) / 6.
float toy(Vec2 p) { return 0.2f + p.x * p.y * p.y; }
double toy_integral(double x0, double x1, double y0, double y1) {
  return 0.2 * (x1 - x0) * (y1 - y0) + (x1 * x1 - x0 * x0) * (y1 * y1 * y1 - y0 * y0 * y0) / 6.0;
}

TEST(MetropolisChain, VisitsAToyTargetInProportionToIt) {
  // One long chain over 4 x 4 cells, its visits counted in 25 batches of 8,000 steps: batch means
  // are nearly independent although the steps are not, so the chi-square of the cells' batch means
  // against their expectations, each over its standard error, is near 16 for a chain that samples
  // f, and far above for a wrong acceptance (a = 1 gives the uniform density, 0.7 of f in some cells).
  constexpr int kCells = 4, kBatches = 25, kPerBatch = 8000;
  const auto [visits, recorded] = testing::subject([] {
    std::vector<std::vector<double>> v(kBatches, std::vector<double>(kCells * kCells, 0.0));
    std::vector<double> r(kCells * kCells, 0.0);
    PrimarySampleSpace sampler(11, 0, 0.05f, 0.2f);
    Rng choice(11, 1, 0);
    int step = 0;
    const auto cell = [](Vec2 p) { return size_t(int(p.y * kCells) * kCells + int(p.x * kCells)); };
    run_chain(
        sampler, choice, std::int64_t(kBatches) * kPerBatch,
        [](PrimarySampleSpace& s) {
          const Vec2 p = s.uniform2();
          return MltSample{{Splat{p, Color(toy(p))}}, toy(p)};
        },
        [&](const Splat& splat, float w) { r[cell(splat.film_point)] += double(w) * splat.value.x; },
        [&](const MltSample& current) { v[size_t(step++ / kPerBatch)][cell(current.splats[0].film_point)] += 1.0; });
    return std::pair(v, r);
  });
  ASSERT_EQ(visits.size(), size_t(kBatches));
  const double total = toy_integral(0, 1, 0, 1);
  double chi2 = 0.0, recorded_sum = 0.0;
  for (const double r : recorded) recorded_sum += r;
  for (int cy = 0; cy < kCells; ++cy)
    for (int cx = 0; cx < kCells; ++cx) {
      const size_t c = size_t(cy * kCells + cx);
      const double expected =
          toy_integral(double(cx) / kCells, double(cx + 1) / kCells, double(cy) / kCells, double(cy + 1) / kCells) /
          total;
      testing::SampleMean m;
      for (const auto& batch : visits) m.add(batch[c] / kPerBatch);
      chi2 += std::pow((m.mean() - expected) / m.standard_error(), 2);
      // The expected-value records: each step records weight 1 in all, shared by the two states.
      EXPECT_NEAR(recorded[c] / recorded_sum, expected, 0.1 * expected) << "cell " << c;
    }
  EXPECT_LT(chi2, 39.3);  // chi-square with 16 degrees of freedom, 0.1 % above
  EXPECT_GT(chi2, 5.1);   // and 0.1 % below: batch means that vary as little as that are not honest
  EXPECT_NEAR(recorded_sum, double(kBatches) * kPerBatch, 1e-3 * kBatches * kPerBatch);
}

TEST(Acceptance, TheRatioOfTargetsCappedAtOne) {
  const std::vector<float> a = testing::subject([] {
    return std::vector<float>{acceptance(2.0f, 1.0f), acceptance(1.0f, 3.0f), acceptance(0.0f, 0.5f),
                              acceptance(0.0f, 0.0f), acceptance(4.0f, 0.0f), acceptance(1.0f, 1.0f)};
  });
  ASSERT_EQ(a.size(), 6u);
  EXPECT_FLOAT_EQ(a[0], 0.5f);
  EXPECT_FLOAT_EQ(a[1], 1.0f);
  EXPECT_FLOAT_EQ(a[2], 1.0f);
  EXPECT_FLOAT_EQ(a[3], 1.0f);
  EXPECT_FLOAT_EQ(a[4], 0.0f);
  EXPECT_FLOAT_EQ(a[5], 1.0f);
}

struct MltRun {
  Image image;
  double b = 0.0, b_error = 0.0, accepted = 0.0;
};
inline auto record_fields(MltRun& r) { return std::tie(r.image, r.b, r.b_error, r.accepted); }

MltRun render_mlt_run(const MltOptions& options, std::uint64_t seed, int threads = 2) {
  const testing::LoadedScene& c = testing::cornell_box<64, 64>();
  RenderSettings settings;
  settings.width = settings.height = 64;
  settings.seed = seed;
  return testing::subject([&] {
    SampleGuard guard;
    MltReport report;
    MltRun r;
    r.image = render_mlt(c.scene, c.camera, settings, options, threads, guard, nullptr, &report).mean();
    r.b = report.b;
    r.b_error = report.b_standard_error;
    r.accepted = report.mutations > 0 ? double(report.accepted) / double(report.mutations) : 0.0;
    return r;
  });
}

MltOptions mlt_options(bool multiplexed, float large_step) {
  MltOptions o;
  o.multiplexed = multiplexed;
  o.large_step = large_step;
  o.mutations_per_pixel = multiplexed ? 32 : 16;
  // A multiplexed chain keeps its depth: with few chains, how many each depth draws is noise
  // of its own (64 chains left the regions' standard error at 14 %).
  o.chains = multiplexed ? 1024 : 64;
  o.bootstrap = 20000;
  o.max_depth = 10;
  return o;
}

// Region means over 8 runs (seeds 1 ... 8) within 4 standard errors of their spread: per-pixel
// tests would need independent pixels, and a chain's are not.
void expect_regions(const MltOptions& options, const char* what) {
  std::vector<testing::SampleMean> means(std::size(testing::kCornellRegions));
  testing::SampleMean b;
  double accepted = 0.0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const MltRun r = render_mlt_run(options, seed);
    for (size_t i = 0; i < std::size(testing::kCornellRegions); ++i)
      means[i].add(grey(mean_over(r.image, testing::kCornellRegions[i])));
    b.add(r.b);
    accepted += r.accepted / 8.0;
  }
  for (size_t i = 0; i < std::size(testing::kCornellRegions); ++i) {
    const double expected = grey(mean_over(testing::cornell_reference_64(), testing::kCornellRegions[i]));
    // Multiplexed paths stop at depth 10: the box's longer paths carry under 0.5 % of its light.
    EXPECT_NEAR(means[i].mean(), expected, 4.0 * means[i].standard_error() + 0.005 * expected)
        << what << ", " << testing::kCornellRegionNames[i] << ": standard error " << means[i].standard_error();
    EXPECT_LT(means[i].standard_error(), 0.05 * expected) << what << ", " << testing::kCornellRegionNames[i];
  }
  // b, the image's mean luminance, within 4 standard errors (of its 8 estimates) of the reference's.
  const Image& ref = testing::cornell_reference_64();
  double reference_b = 0.0;
  for (const Color& p : ref.pixels()) reference_b += luminance(p) / double(ref.pixels().size());
  EXPECT_NEAR(b.mean(), reference_b, 4.0 * b.standard_error() + 0.005 * reference_b) << what;
  EXPECT_GT(accepted, 0.05) << what;  // the chain moves
  EXPECT_LT(accepted, 0.999) << what;
}

TEST(MltCornell, MultiplexedFindsTheReference) { expect_regions(mlt_options(true, 0.3f), "mlt"); }
TEST(MltCornell, PrimarySampleSpaceOverBdptFindsTheReference) { expect_regions(mlt_options(false, 0.3f), "pssmlt"); }
TEST(MltCornell, LargeStepsAloneAreIndependentSamplesAndFindTheReference) {
  MltOptions o = mlt_options(true, 1.0f);
  o.mutations_per_pixel = 64;  // an independence sampler keeps a state longer than small steps do
  expect_regions(o, "mlt, large steps only");
}

TEST(MltRender, SameImageForAnyThreadCount) {
  for (const bool multiplexed : {true, false}) {
    MltOptions o = mlt_options(multiplexed, 0.3f);
    o.mutations_per_pixel = 2;
    o.bootstrap = 500;
    EXPECT_TRUE(render_mlt_run(o, 5, 1).image == render_mlt_run(o, 5, 2).image) << multiplexed;
  }
}

}  // namespace
}  // namespace rt
