#include "common/progress.h"
#include "common/task.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

namespace rt {
namespace {

TEST(ProgressBar, SilentWhenDisabled) {
  ::testing::internal::CaptureStderr();
  {
    ProgressBar bar(100, "samples", false);
    bar.advance(50);
    bar.advance(50);
    bar.finish();
    EXPECT_EQ(bar.done(), 100u);
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(ProgressBar, FinalLineShowsCompletionAndRate) {
  ::testing::internal::CaptureStderr();
  {
    ProgressBar bar(1000, "samples", true);
    bar.advance(1000);
    bar.finish();
  }
  const std::string out = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(out.find("100%"), std::string::npos) << out;
  EXPECT_NE(out.find("samples/s"), std::string::npos) << out;
  EXPECT_EQ(out.back(), '\n');
}

TEST(FormatSi, Prefixes) {
  EXPECT_EQ(format_si(950.0), "950 ");
  EXPECT_EQ(format_si(1.5e6), "1.5 M");
  EXPECT_EQ(format_si(2.25e9), "2.25 G");
}

TEST(UnfinishedTask, ReportedOncePerTaskId) {
  ::testing::internal::CaptureStderr();
  EXPECT_TRUE(report_unfinished_task("test.task.a"));
  EXPECT_FALSE(report_unfinished_task("test.task.a"));
  EXPECT_TRUE(report_unfinished_task("test.task.b"));
  const std::string out = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(out.find("task test.task.a is not implemented"), std::string::npos);
  EXPECT_EQ(out.find("test.task.a"), out.rfind("test.task.a")) << "printed twice: " << out;
}

TEST(UnfinishedTask, OncePerIdWhateverItsAddressAndThread) {
  // The same id from another file may be another string at another address: still reported once.
  const std::string copy = "test.task.c";
  ::testing::internal::CaptureStderr();
  EXPECT_TRUE(report_unfinished_task("test.task.c"));
  EXPECT_FALSE(report_unfinished_task(copy.c_str()));
  std::atomic<int> first_calls{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&] {
      for (int i = 0; i < 10000; ++i) first_calls += report_unfinished_task("test.task.d") ? 1 : 0;
    });
  for (std::thread& thread : threads) thread.join();
  const std::string out = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(first_calls.load(), 1);
  EXPECT_EQ(out.find("test.task.c"), out.rfind("test.task.c")) << "printed twice: " << out;
  EXPECT_EQ(out.find("test.task.d"), out.rfind("test.task.d")) << "printed twice: " << out;
  EXPECT_NE(out.find("test.task.d"), std::string::npos) << out;
}

}  // namespace
}  // namespace rt
