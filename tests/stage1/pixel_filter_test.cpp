// Stage 1: pixel reconstruction filters (pixel_filter.h). Each filter's samples follow its
// normalized shape (chi-square, against the shape integrated numerically, not against the closed
// forms the sampler inverts); the weights carry Mitchell's sign; and through the pixel loop a
// constant scene stays constant, a step edge gives each pixel the share of the filter beyond it,
// and a zone plate shows the trade between aliasing and blur.
#include "01-ray-casting/pixel_filter.h"
#include "01-ray-casting/render.h"
#include "experiments/filter_aliasing.h"
#include "support/chi_square.h"
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rt {

inline auto record_fields(FilterSample& s) { return std::tie(s.film_offset, s.weight); }

namespace {

using testing::subject;

constexpr PixelFilterType kAllFilters[] = {PixelFilterType::box, PixelFilterType::tent, PixelFilterType::gaussian,
                                           PixelFilterType::mitchell, PixelFilterType::blackman_harris};

// The integral of f1 (signed, or its absolute value) over [a, b] by composite Simpson, with the
// kinks of |f1| (0, +-1 and Mitchell's +-8/7) as interval ends.
double integrate_profile(const PixelFilter& f, double a, double b, bool absolute) {
  std::vector<double> cuts = {a, b};
  for (const double k : {-8.0 / 7.0, -1.0, 0.0, 1.0, 8.0 / 7.0})
    if (k > a && k < b) cuts.push_back(k);
  std::sort(cuts.begin(), cuts.end());
  double sum = 0.0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    std::vector<double> x, w;
    testing::simpson_nodes(cuts[i], cuts[i + 1], 200, x, w);
    for (size_t j = 0; j < x.size(); ++j) sum += w[j] * (absolute ? std::abs(f.profile(x[j])) : f.profile(x[j]));
  }
  return sum;
}

TEST(PixelFilter, ClosedFormIntegralsMatchTheShape) {
  for (const PixelFilterType type : kAllFilters) {
    const PixelFilter f(type);
    for (double x = 0.0; x <= f.radius(); x += f.radius() / 16.0)
      EXPECT_NEAR(f.abs_integral(x), integrate_profile(f, 0.0, x, true), 1e-9) << pixel_filter_name(type) << " at " << x;
    EXPECT_NEAR(f.signed_area(), integrate_profile(f, -f.radius(), f.radius(), false), 1e-9) << pixel_filter_name(type);
    EXPECT_EQ(f.profile(f.radius() * 1.01), 0.0) << pixel_filter_name(type) << ": no support beyond the radius";
  }
  // Mitchell-Netravali's cubics integrate to 1 and their absolute value to 1.0700: the negative
  // lobes hold 0.035 of it (0.0175 on each side).
  EXPECT_NEAR(PixelFilter(PixelFilterType::mitchell).abs_area(), 1.0699708454810, 1e-12);
}

// Bins of the square [-r, r]^2; each expects N times the bin's share of the integral of |f(s)|.
TEST(PixelFilter, SamplesFollowTheNormalizedShapeOfEveryFilter) {
  constexpr int kBins = 16, kSamples = 400000;
  for (const PixelFilterType type : kAllFilters) {
    const PixelFilter f(type);
    const double r = f.radius(), width = 2.0 * r / kBins;
    std::vector<double> axis(kBins);
    double total = 0.0;
    for (int i = 0; i < kBins; ++i) total += axis[size_t(i)] = integrate_profile(f, -r + i * width, -r + (i + 1) * width, true);
    std::vector<double> observed(kBins * kBins + 1, 0.0), expected(kBins * kBins + 1, 0.0);
    for (int i = 0; i < kBins; ++i)
      for (int j = 0; j < kBins; ++j) expected[size_t(i * kBins + j)] = kSamples * axis[size_t(i)] * axis[size_t(j)] / (total * total);
    const std::vector<FilterSample> samples = subject([&] {
      std::vector<FilterSample> drawn(kSamples);
      Rng rng(11, std::uint64_t(type), 0);
      for (FilterSample& d : drawn) d = f.sample(rng.uniform2());
      return drawn;
    });
    for (const FilterSample& sample : samples) {
      const Vec2 s = sample.film_offset - Vec2(0.5f);
      const int i = int(std::floor((s.x + r) / width)), j = int(std::floor((s.y + r) / width));
      if (i < 0 || j < 0 || i >= kBins || j >= kBins)
        observed.back() += 1.0;  // outside the filter's support, where its density is 0
      else
        observed[size_t(i * kBins + j)] += 1.0;
    }
    const auto result = testing::chi_square_test(observed, expected);
    EXPECT_TRUE(result.passed) << pixel_filter_name(type) << ": " << result.message;
  }
}

TEST(PixelFilter, SampleInvertsTheCumulativeDistribution) {
  for (const PixelFilterType type : kAllFilters) {
    const PixelFilter f(type);
    for (int i = 1; i < 32; ++i)
      for (int j = 1; j < 32; ++j) {
        const Vec2 u(float(i) / 32.0f, float(j) / 32.0f);
        const Vec2 back = f.invert(subject([&] { return f.sample(u); }).film_offset - Vec2(0.5f));
        EXPECT_NEAR(back.x, u.x, 1e-6f) << pixel_filter_name(type) << " at " << u.x << ", " << u.y;
        EXPECT_NEAR(back.y, u.y, 1e-6f) << pixel_filter_name(type) << " at " << u.x << ", " << u.y;
      }
  }
}

TEST(PixelFilter, BoxSamplesAreTheUniformNumbersThemselves) {
  const PixelFilter box(PixelFilterType::box);
  Rng rng(12, 0, 0);
  for (int k = 0; k < 1000; ++k) {
    const Vec2 u = rng.uniform2();
    const FilterSample s = subject([&] { return box.sample(u); });
    ASSERT_EQ(s.film_offset, u);
    ASSERT_EQ(s.weight, 1.0f);
  }
}

// f / (p integral f): exactly 1 for a filter that is never negative (its samples are then a plain
// mean), and sign(f(s)) (1.06997)^2 for Mitchell: negative exactly where f(s) is.
TEST(PixelFilter, WeightsCarryTheSignOfTheFilterAndOnlyThat) {
  Rng rng(13, 0, 0);
  for (const PixelFilterType type : kAllFilters) {
    const PixelFilter f(type);
    int negative = 0;
    constexpr int kSamples = 200000;
    for (int k = 0; k < kSamples; ++k) {
      const Vec2 u = rng.uniform2();
      const FilterSample s = subject([&] { return f.sample(u); });
      const double value = f.evaluate(s.film_offset - Vec2(0.5f));
      if (!f.has_negative_lobes()) {
        ASSERT_EQ(s.weight, 1.0f) << pixel_filter_name(type);
        continue;
      }
      const double c = f.abs_area() / f.signed_area();
      ASSERT_NEAR(s.weight, value < 0.0 ? -c * c : c * c, 1e-6) << "f(s) = " << value;
      negative += s.weight < 0.0f;
    }
    if (f.has_negative_lobes()) {
      // The share of |f| in the negative lobes: 2 q (1 - q), q = 0.0175 / 0.535 per axis.
      const double q = (f.abs_area() - f.signed_area()) / 2.0 / f.abs_area();
      const double expected = 2.0 * q * (1.0 - q) * kSamples;
      EXPECT_NEAR(negative, expected, 5.0 * std::sqrt(expected));
    }
  }
}

// A scene that is one constant radiance everywhere (the background).
constexpr float kConstant = 0.37f;
const Camera kFilterCamera(CameraSpec{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), Vec3(0.0f, 1.0f, 0.0f), 60.0f}, 16, 16);

RenderSettings settings_with(PixelFilterType type, int spp) {
  RenderSettings s;
  s.width = s.height = 16;
  s.spp = spp;
  s.seed = 5;
  s.filter = type;
  return s;
}

TEST(FilterRender, AConstantSceneGivesTheConstantThroughEveryFilter) {
  for (const PixelFilterType type : kAllFilters) {
    const PixelFilter f(type);
    const Image image = subject([&] {
      return render_image(kFilterCamera, settings_with(type, 64), 1, [](const Ray&, Rng&) { return Color(kConstant); });
    });
    double mean = 0.0;
    for (const Color& c : image.pixels()) {
      if (!f.has_negative_lobes()) {
        ASSERT_NEAR(c.r, kConstant, 64 * 1e-7f) << pixel_filter_name(type);  // every weight is 1
      } else {
        // (1/N) sum w_k L with w_k = +-c^2: the constant times c^2 (n+ - n-) / N, for whole n+.
        const double c2 = std::pow(f.abs_area() / f.signed_area(), 2.0);
        const double positives = (c.r / kConstant * 64.0 / c2 + 64.0) / 2.0;
        ASSERT_NEAR(positives, std::round(positives), 1e-3) << "pixel value " << c.r;
      }
      mean += c.r / double(image.pixel_count());
    }
    // Unbiased: the mean weight is 1, so over 16 x 16 x 64 samples the constant comes back.
    EXPECT_NEAR(mean, kConstant, f.has_negative_lobes() ? 0.02 : 1e-6) << pixel_filter_name(type);
  }
}

// A vertical step edge at the image's centre line (film x = 4 of 8), dark on the left, 1 on the
// right. A pixel whose centre lies d to the left of it expects the filter's share beyond the edge,
//   E(d) = integral_d^r f1 / integral_-r^r f1,
// and the one d to its right 1 - E(d). Mitchell's negative lobe makes E(1.5) < 0 and 1 - E(1.5) > 1:
// the dark and light bands that sharpen an edge (the ringing). Checked per column against the
// spread of its 64 pixels.
TEST(FilterRender, AStepEdgeGivesEachPixelTheFiltersShareBeyondIt) {
  const Camera camera(CameraSpec{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), Vec3(0.0f, 1.0f, 0.0f), 60.0f}, 8, 64);
  for (const PixelFilterType type : kAllFilters) {
    const PixelFilter f(type);
    RenderSettings s = settings_with(type, 512);
    s.width = 8, s.height = 64;
    // Film x > 4 looks to the camera's right, -x: the step is the sign of the direction's x.
    const Image image = subject([&] {
      return render_image(camera, s, 2,
                          [](const Ray& ray, Rng&) { return Color(ray.direction.x < 0.0f ? 1.0f : 0.0f); });
    });
    for (int column = 1; column < 7; ++column) {
      const double d = 4.0 - (column + 0.5);  // the edge's distance from the centre, > 0 on the dark side
      const double beyond = integrate_profile(f, std::min(std::abs(d), f.radius()), f.radius(), false) / f.signed_area();
      const double expected = d > 0.0 ? beyond : 1.0 - beyond;
      double mean = 0.0, square = 0.0;
      for (int y = 0; y < 64; ++y) {
        mean += image.at(column, y).r / 64.0;
        square += double(image.at(column, y).r) * image.at(column, y).r / 64.0;
      }
      const double standard_error = std::sqrt(std::max(0.0, square - mean * mean) / 63.0);
      EXPECT_NEAR(mean, expected, 5.0 * standard_error + 1e-6)
          << pixel_filter_name(type) << ", column " << column << " (edge " << d << " px away)";
    }
  }
}

TEST(FilterRender, BitIdenticalForAnyThreadCountWithAFilterAndALens) {
  CameraSpec spec{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), Vec3(0.0f, 1.0f, 0.0f), 60.0f};
  spec.aperture_radius = 0.1f;
  const Camera camera(spec, 16, 16);
  auto radiance = [](const Ray& ray, Rng& rng) { return Color(ray.direction.x * ray.origin.y + rng.uniform()); };
  const RenderSettings s = settings_with(PixelFilterType::mitchell, 8);
  const Image one = subject([&] { return render_image(camera, s, 1, radiance); });
  const Image three = subject([&] { return render_image(camera, s, 3, radiance); });
  for (size_t i = 0; i < one.pixel_count(); ++i) ASSERT_EQ(one.pixels()[i], three.pixels()[i]);
}

// The zone plate (tests/experiments/filter_aliasing.h): the box keeps the most false rings beyond
// Nyquist and the most contrast within it; the Gaussian folds back the least and blurs the most;
// Mitchell's negative lobes keep more of the passband than the tent of a similar width.
TEST(ZonePlate, WiderFiltersTradeAliasingForBlur) {
  const ZonePlateScores box =
      score_zone_plate(subject([] { return render_zone_plate(PixelFilterType::box, 64, 64, 1); }));
  const ZonePlateScores tent =
      score_zone_plate(subject([] { return render_zone_plate(PixelFilterType::tent, 64, 64, 1); }));
  const ZonePlateScores gaussian =
      score_zone_plate(subject([] { return render_zone_plate(PixelFilterType::gaussian, 64, 64, 1); }));
  const ZonePlateScores mitchell =
      score_zone_plate(subject([] { return render_zone_plate(PixelFilterType::mitchell, 64, 64, 1); }));
  EXPECT_GT(box.aliasing, 2.0 * gaussian.aliasing);
  EXPECT_GT(box.aliasing, tent.aliasing);
  EXPECT_GT(box.passband, gaussian.passband);
  EXPECT_GT(mitchell.passband, gaussian.passband);
  EXPECT_LT(box.passband, 1.0) << "even the box averages the rings over a pixel";
}

}  // namespace
}  // namespace rt
