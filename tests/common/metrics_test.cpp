#include "common/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace rt {
namespace {

TEST(Metrics, MseAndRmseOfAKnownDifference) {
  const Image reference(4, 2, Color(1.0f));
  Image image = reference;
  image.at(0, 0) = Color(3.0f, 1.0f, 1.0f);  // one channel of one pixel off by 2: sum of squares 4
  EXPECT_DOUBLE_EQ(mse(image, reference), 4.0 / 24.0);
  EXPECT_DOUBLE_EQ(rmse(image, reference), std::sqrt(4.0 / 24.0));
  EXPECT_EQ(mse(reference, reference), 0.0);
}

TEST(Metrics, RelativeMseWeighsDarkAndBrightAlike) {
  const Image dark(1, 1, Color(0.1f)), bright(1, 1, Color(10.0f));
  const Image dark_off(1, 1, Color(0.11f)), bright_off(1, 1, Color(11.0f));  // both 10% off
  const double rel_dark = relative_mse(dark_off, dark, 0.0), rel_bright = relative_mse(bright_off, bright, 0.0);
  EXPECT_NEAR(rel_dark, 0.01, 1e-6);
  EXPECT_NEAR(rel_bright, 0.01, 1e-6);
  EXPECT_NEAR(relative_mse(dark_off, dark), 1e-4 / (0.01 + 0.01), 1e-8);  // default epsilon 0.01
}

TEST(Metrics, MeanOverARectangle) {
  Image image(4, 4, Color(0.0f));
  image.at(1, 1) = Color(4.0f, 8.0f, 0.0f);
  const DVec3 mean = mean_over(image, PixelRect{1, 1, 3, 3});
  EXPECT_DOUBLE_EQ(mean.x, 1.0);
  EXPECT_DOUBLE_EQ(mean.y, 2.0);
  EXPECT_THROW(mean_over(image, PixelRect{2, 2, 2, 3}), std::invalid_argument);
  EXPECT_THROW(mean_over(image, PixelRect{0, 0, 5, 1}), std::invalid_argument);
}

TEST(Metrics, DownsampleAveragesEachBlock) {
  Image image(4, 2, Color(0.0f));
  image.at(0, 0) = Color(4.0f);
  image.at(3, 1) = Color(8.0f, 0.0f, 4.0f);
  const Image small = downsample(image, 2);
  ASSERT_EQ(small.width(), 2);
  ASSERT_EQ(small.height(), 1);
  EXPECT_EQ(small.at(0, 0), Color(1.0f));
  EXPECT_EQ(small.at(1, 0), Color(2.0f, 0.0f, 1.0f));
  EXPECT_THROW(downsample(image, 3), std::invalid_argument);
  EXPECT_THROW(downsample(image, 0), std::invalid_argument);
}

TEST(Metrics, RmseOverARectangleCountsItsPixelsAlone) {
  Image a(4, 3, Color(1.0f)), b(4, 3, Color(1.0f));
  b.at(1, 1) = Color(3.0f, 1.0f, 1.0f);  // inside the rectangle: one channel of one pixel off by 2
  b.at(3, 2) = Color(100.0f);            // outside it
  const PixelRect rect{0, 0, 2, 2};
  EXPECT_DOUBLE_EQ(rmse(a, b, rect), std::sqrt(4.0 / 12.0));  // 4 pixels x 3 channels
  EXPECT_DOUBLE_EQ(rmse(a, b, PixelRect{0, 0, 1, 1}), 0.0);
  EXPECT_THROW(rmse(a, b, PixelRect{2, 0, 5, 1}), std::invalid_argument);  // past the right edge
  EXPECT_THROW(rmse(a, b, PixelRect{1, 1, 1, 2}), std::invalid_argument);  // empty
  EXPECT_THROW(rmse(a, Image(4, 4), rect), std::invalid_argument);
}

TEST(Metrics, SizeMismatchIsAnError) {
  EXPECT_THROW(mse(Image(2, 2), Image(2, 3)), std::invalid_argument);
}

}  // namespace
}  // namespace rt
