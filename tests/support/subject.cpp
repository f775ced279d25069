// The record channel between a graded test's two runs (tests/support/subject.h). A record is
//   u32 tag length, tag ("file:line:column" of the subject() call), u64 payload length, payload,
// appended by the subject run to RT_GRADING_RECORD and read back in order by the judge from
// RT_GRADING_REPLAY. The judge trusts none of it: a record that is not the next one the test asks
// for, or whose lengths run past the file, ends the judge with exit code kReplayFailed and no
// report (tools/grading/build.py then fails the test with the line printed here).
#include "support/subject.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <string_view>

namespace rt::testing {
namespace {

constexpr int kReplayFailed = 86;  // tools/grading/build.py, REPLAY_FAILED
constexpr std::uint64_t kLargestRecordFile = std::uint64_t(1) << 30;

std::string tag_of(const std::source_location& where) {
  std::string_view file = where.file_name();
  if (const auto slash = file.rfind('/'); slash != std::string_view::npos) file.remove_prefix(slash + 1);
  return std::string(file) + ":" + std::to_string(where.line()) + ":" + std::to_string(where.column());
}

[[noreturn]] void end_run(const std::string& why) {
  std::fflush(stdout);
  std::fprintf(stderr, "grading: %s\n", why.c_str());
  std::fflush(stderr);
  std::_Exit(kReplayFailed);
}

struct Channel {
  GradingRole role = GradingRole::kLocal;
  std::FILE* record = nullptr;  // subject
  std::string replay;           // judge: the whole file
  std::size_t next = 0;         // judge: where the next record starts
  std::mutex lock;

  Channel() {
    const char* record_path = std::getenv("RT_GRADING_RECORD");
    const char* replay_path = std::getenv("RT_GRADING_REPLAY");
    if (record_path && replay_path) end_run("RT_GRADING_RECORD and RT_GRADING_REPLAY are both set");
    if (record_path) {
      role = GradingRole::kSubject;
      record = std::fopen(record_path, "wb");
      if (!record) end_run(std::string("cannot write the record file ") + record_path);
      std::setvbuf(record, nullptr, _IOFBF, std::size_t(1) << 20);  // written out when the program exits
    } else if (replay_path) {
      role = GradingRole::kJudge;
      std::ifstream in(replay_path, std::ios::binary | std::ios::ate);
      if (!in) end_run(std::string("cannot read the record file ") + replay_path);
      const auto size = std::uint64_t(in.tellg());
      if (size > kLargestRecordFile) end_run("the record file is larger than 1 GiB");
      replay.resize(size);
      in.seekg(0);
      in.read(replay.data(), std::streamsize(size));
      if (!in) end_run("the record file could not be read whole");
    }
  }

  template <class T>
  T take_number(const char* what) {
    T v{};
    if (replay.size() - next < sizeof v) end_run(std::string("the record file ends inside ") + what);
    std::memcpy(&v, replay.data() + next, sizeof v);
    next += sizeof v;
    return v;
  }
  std::string take_bytes(std::uint64_t n, const char* what) {
    if (n > replay.size() - next) end_run(std::string("the record file ends inside ") + what);
    std::string bytes = replay.substr(next, std::size_t(n));
    next += std::size_t(n);
    return bytes;
  }
};

Channel& channel() {
  static Channel c;
  return c;
}

}  // namespace

GradingRole grading_role() { return channel().role; }

void record_value(const std::source_location& where, const std::string& bytes) {
  Channel& c = channel();
  const std::lock_guard guard(c.lock);
  const std::string tag = tag_of(where);
  const auto tag_size = std::uint32_t(tag.size());
  const auto size = std::uint64_t(bytes.size());
  std::fwrite(&tag_size, sizeof tag_size, 1, c.record);
  std::fwrite(tag.data(), 1, tag.size(), c.record);
  std::fwrite(&size, sizeof size, 1, c.record);
  std::fwrite(bytes.data(), 1, bytes.size(), c.record);
}

std::string replay_value(const std::source_location& where) {
  Channel& c = channel();
  const std::lock_guard guard(c.lock);
  const std::string wanted = tag_of(where);
  if (c.next == c.replay.size())
    end_run("the submission's run ended before it gave the value at " + wanted +
            " (a crash, an exit, a kill or a time-out in its code)");
  const std::string tag = c.take_bytes(c.take_number<std::uint32_t>("a tag's length"), "a tag");
  if (tag != wanted) end_run("the submission's run gave a value at " + tag + " where the test asked for one at " + wanted);
  return c.take_bytes(c.take_number<std::uint64_t>("a value's length"), "a value");
}

void malformed_value(const std::source_location& where, const char* why) {
  end_run("the value recorded at " + tag_of(where) + " is malformed: " + why);
}

bool judge_used_every_record() {
  const Channel& c = channel();
  return c.role != GradingRole::kJudge || c.next == c.replay.size();
}

}  // namespace rt::testing
