// Helpers shared by the test suites: paths into the source tree, scratch folders, running a program,
// bitwise float equality.
#pragma once

#include "support/subject.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <tuple>

namespace rt::testing {

inline std::filesystem::path source_path(const std::string& relative) {
  return std::filesystem::path(RT_SOURCE_DIR) / relative;
}

// A fresh, empty folder for one test, removed when the test ends. Under the grader, where each test
// runs alone, it has no process id in its name, so that both of a graded test's runs
// (support/subject.h) name the same folder.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("rt-test-" + std::string(info->test_suite_name()) + "-" + info->name() +
             (grading_role() == GradingRole::kLocal ? "-" + std::to_string(::getpid()) : ""));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ignored);
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// Equal bit for bit (so +0 and -0 differ and a NaN equals itself), where two computations must
// round identically.
inline bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// What `f` throws, as its message; "" when it throws nothing.
inline std::string error_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

struct CommandResult {
  int exit_code;
  std::string out;
  std::string err;
};
inline auto record_fields(CommandResult& r) { return std::tie(r.exit_code, r.out, r.err); }  // support/record.h

// Runs a shell command line with stdout and stderr captured to files in `scratch`.
inline CommandResult run_command(const std::string& command, const ScratchDir& scratch) {
  const auto out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  const int status =
      std::system((command + " >'" + out.string() + "' 2>'" + err.string() + "'").c_str());
  return CommandResult{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)};
}

// The command line that runs `program` (quoted: a build path may hold spaces) with `arguments`.
// Built by a stream: GCC 12 warns wrongly (-Wrestrict) on long chains of string additions.
inline std::string program_command(const char* program, const std::string& arguments) {
  std::ostringstream command;
  command << "'" << program << "' " << arguments;
  return command.str();
}

// "--scene" and the path of assets/scenes/NAME.
inline std::string scene_flag(const char* name) {
  std::ostringstream flag;
  flag << "--scene " << source_path(std::string("assets/scenes/") + name).string();
  return flag.str();
}

// A failed run as the command line promises it: exit `code`, and one line on stderr containing
// `fragment`.
inline void expect_one_line_error(const CommandResult& r, int code, const std::string& fragment) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << "stderr: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line, got: " << r.err;
}

}  // namespace rt::testing
