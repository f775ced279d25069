// The main of every test program: GoogleTest's own, except that a failing test prints its first
// few failures and how many more there were, and stops at its hundredth. A check inside a loop
// over many samples would otherwise print one failure per sample (a placeholder's glass lobe
// failed 200,001 times, a 150 MB XML report), burying the first one, which says what is wrong,
// and growing GoogleTest's XML report past what the grader reads. RT_TEST_ALL_FAILURES=1 prints
// every failure and never stops a test.
#include "support/subject.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <thread>

namespace {

constexpr int kFailuresShown = 8;
constexpr int kFailuresBeforeStopping = 100;

// Forwards every event to GoogleTest's printer but the failures of a test past the first few.
class FirstFailuresPrinter : public testing::TestEventListener {
 public:
  explicit FirstFailuresPrinter(testing::TestEventListener* printer) : printer_(printer) {}

  void OnTestStart(const testing::TestInfo& info) override {
    shown_ = 0;
    left_out_ = 0;
    printer_->OnTestStart(info);
  }
  // GoogleTest has recorded the failure before its listeners hear of it. AssertionException is
  // its documented way for a listener to end the test; thrown only on the test's own thread,
  // since a worker thread's exception would end the program (parallel_for carries a worker's
  // exception to the calling thread itself).
  void OnTestPartResult(const testing::TestPartResult& result) override {
    if (!result.failed()) {
      printer_->OnTestPartResult(result);
      return;
    }
    if (shown_ < kFailuresShown) {
      ++shown_;
      printer_->OnTestPartResult(result);
    } else {
      ++left_out_;
    }
    if (shown_ + left_out_ >= kFailuresBeforeStopping && std::this_thread::get_id() == test_thread_)
      throw testing::AssertionException(result);
  }
  void OnTestEnd(const testing::TestInfo& info) override {
    const bool stopped = shown_ + left_out_ >= kFailuresBeforeStopping;
    if (left_out_ > 0)
      std::printf("... and %d more failure%s of this test, not shown%s (RT_TEST_ALL_FAILURES=1 shows them all)\n",
                  left_out_, left_out_ == 1 ? "" : "s", stopped ? "; the test stopped there" : "");
    printer_->OnTestEnd(info);
  }

  void OnTestProgramStart(const testing::UnitTest& test) override { printer_->OnTestProgramStart(test); }
  void OnTestIterationStart(const testing::UnitTest& test, int i) override { printer_->OnTestIterationStart(test, i); }
  void OnEnvironmentsSetUpStart(const testing::UnitTest& test) override { printer_->OnEnvironmentsSetUpStart(test); }
  void OnEnvironmentsSetUpEnd(const testing::UnitTest& test) override { printer_->OnEnvironmentsSetUpEnd(test); }
  void OnTestSuiteStart(const testing::TestSuite& suite) override { printer_->OnTestSuiteStart(suite); }
  void OnTestDisabled(const testing::TestInfo& info) override { printer_->OnTestDisabled(info); }
  void OnTestSuiteEnd(const testing::TestSuite& suite) override { printer_->OnTestSuiteEnd(suite); }
  void OnEnvironmentsTearDownStart(const testing::UnitTest& test) override { printer_->OnEnvironmentsTearDownStart(test); }
  void OnEnvironmentsTearDownEnd(const testing::UnitTest& test) override { printer_->OnEnvironmentsTearDownEnd(test); }
  void OnTestIterationEnd(const testing::UnitTest& test, int i) override { printer_->OnTestIterationEnd(test, i); }
  void OnTestProgramEnd(const testing::UnitTest& test) override { printer_->OnTestProgramEnd(test); }

 private:
  std::unique_ptr<testing::TestEventListener> printer_;
  std::thread::id test_thread_ = std::this_thread::get_id();
  int shown_ = 0;
  int left_out_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  const char* all = std::getenv("RT_TEST_ALL_FAILURES");
  if (all == nullptr || all[0] != '1') {
    testing::TestEventListeners& listeners = testing::UnitTest::GetInstance()->listeners();
    if (testing::TestEventListener* printer = listeners.Release(listeners.default_result_printer()))
      listeners.Append(new FirstFailuresPrinter(printer));
  }
  const int failed = RUN_ALL_TESTS();
  if (!rt::testing::judge_used_every_record()) {
    std::fprintf(stderr, "grading: the submission's run gave more values than the test asked for\n");
    return 86;
  }
  return failed;
}
