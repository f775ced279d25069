// The main of every test program: GoogleTest's own, except that a failing test prints its first
// few failures and then only how many more there were. A check inside a loop over a thousand
// samples would otherwise print a thousand failure messages (tens of thousands of lines for one
// wrong formula), burying the first one, which says what is wrong. The XML report, which the
// grader reads, still holds every failure. RT_TEST_ALL_FAILURES=1 prints them all.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>

namespace {

constexpr int kFailuresShown = 8;

// Forwards every event to GoogleTest's printer but the failures of a test past the first few.
class FirstFailuresPrinter : public testing::TestEventListener {
 public:
  explicit FirstFailuresPrinter(testing::TestEventListener* printer) : printer_(printer) {}

  void OnTestStart(const testing::TestInfo& info) override {
    shown_ = 0;
    left_out_ = 0;
    printer_->OnTestStart(info);
  }
  void OnTestPartResult(const testing::TestPartResult& result) override {
    if (result.failed() && shown_ >= kFailuresShown) {
      ++left_out_;
      return;
    }
    if (result.failed()) ++shown_;
    printer_->OnTestPartResult(result);
  }
  void OnTestEnd(const testing::TestInfo& info) override {
    if (left_out_ > 0)
      std::printf("... and %d more failures of this test, not shown (RT_TEST_ALL_FAILURES=1 shows them)\n",
                  left_out_);
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
  return RUN_ALL_TESTS();
}
