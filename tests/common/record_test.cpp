// The judge's side of grading (tests/support/subject.h, record.h): a value survives its record bit
// for bit, malformed bytes are refused before anything is allocated, and a judge that replays a
// record not made by the same test, or made and then tampered with, ends without passing.
#include "support/subject.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace rt::testing {
namespace {

template <class T>
std::string bytes_of(const T& value) {
  RecordWriter out;
  write_record(out, value);
  return out.out();
}

template <class T>
T read_back(const std::string& bytes) {
  RecordReader in(bytes);
  T value{};
  read_record(in, value);
  if (in.left() != 0) throw MalformedRecord{"bytes are left over"};
  return value;
}

template <class T>
std::string refusal(const std::string& bytes) {
  try {
    read_back<T>(bytes);
  } catch (const MalformedRecord& e) {
    return e.what;
  }
  return "";
}

TEST(Record, ValuesComeBackBitForBit) {
  using Value = std::tuple<float, std::optional<Vec3>, std::vector<int>, std::string, bool, std::pair<double, Ray>>;
  const Value value{std::numeric_limits<float>::quiet_NaN(), Vec3(1, -0.0f, 3), {4, 5, 6}, std::string("a\0b", 3), true,
                    {1e300, Ray{Vec3(1, 2, 3), Vec3(0, 0, 1)}}};
  const Value back = read_back<Value>(bytes_of(value));
  EXPECT_TRUE(same_bits(std::get<0>(back), std::get<0>(value)));
  EXPECT_TRUE(same_bits(std::get<1>(back)->y, -0.0f));
  EXPECT_EQ(std::get<2>(back), std::get<2>(value));
  EXPECT_EQ(std::get<3>(back), std::get<3>(value));
  EXPECT_TRUE(std::get<4>(back));
  EXPECT_EQ(std::get<5>(back).second.origin, Vec3(1, 2, 3));
  Image image(3, 2, Color(0.5f));
  image.at(2, 1) = Color(1, 2, 3);
  EXPECT_EQ(read_back<Image>(bytes_of(image)), image);
  EXPECT_FALSE(read_back<std::optional<Hit>>(bytes_of(std::optional<Hit>())));
}

TEST(Record, MalformedBytesAreRefusedBeforeAnythingIsAllocated) {
  // A count of 2^60 floats: refused from the count alone, where believing it would allocate 8 EiB.
  EXPECT_EQ(refusal<std::vector<float>>(bytes_of(std::uint64_t(1) << 60)), "a count larger than the bytes that follow");
  // A count one more than the bytes that follow hold.
  std::string three = bytes_of(std::vector<std::uint8_t>{1, 2, 3});
  three[0] = 4;
  EXPECT_EQ(refusal<std::vector<std::uint8_t>>(three), "a count larger than the bytes that follow");
  EXPECT_EQ(refusal<bool>(std::string(1, '\2')), "a bool that is neither 0 nor 1");
  EXPECT_EQ(refusal<Vec3>(bytes_of(Vec2(1, 2))), "it ends early");
  EXPECT_EQ(refusal<float>(bytes_of(1.0)), "bytes are left over");
  // An image whose size says 2 x 2 over three pixels.
  RecordWriter image;
  write_record(image, 2);
  write_record(image, 2);
  write_record(image, std::vector<Color>(3));
  EXPECT_EQ(refusal<Image>(image.out()), "an image whose size does not match its pixels");
  RecordWriter sums;
  write_record(sums, Image(2, 1));
  write_record(sums, std::vector<std::uint32_t>{1});
  EXPECT_EQ(refusal<SampleSums>(sums.out()), "sample sums whose counts do not match its pixels");
}

// The probe the channel tests run as a subject and as a judge: two values, each checked.
TEST(RecordProbe, TwoValues) {
  EXPECT_EQ(subject([] { return 7; }), 7);
  EXPECT_EQ(subject([] { return std::string("seven"); }), "seven");
}

struct ProbeRun {
  int exit_code;
  std::string said;
};

// This program, running only the probe, as the subject (recording to `record`) or as the judge.
ProbeRun probe(const ScratchDir& dir, const std::string& role, const std::filesystem::path& record) {
  const CommandResult r = run_command(role + "='" + record.string() + "' /proc/" + std::to_string(::getpid()) +
                                          "/exe --gtest_filter=RecordProbe.TwoValues",
                                      dir);
  return {r.exit_code, r.out + r.err};
}

TEST(RecordChannel, AJudgeAcceptsOnlyItsOwnTestsUntamperedRecord) {
  ScratchDir dir;
  const auto record = dir / "record.bin";
  ASSERT_EQ(probe(dir, "RT_GRADING_RECORD", record).exit_code, 0);
  const std::string made = read_text(record);
  EXPECT_EQ(probe(dir, "RT_GRADING_REPLAY", record).exit_code, 0) << "the record as it was made";

  // A value changed: the judge's own assertion fails.
  std::string changed = made;
  const auto seven = changed.find("seven");
  ASSERT_NE(seven, std::string::npos);
  changed[seven] = 'S';
  write_text(record, changed);
  const ProbeRun wrong = probe(dir, "RT_GRADING_REPLAY", record);
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.said.find("Seven"), std::string::npos) << wrong.said;

  // The second record cut off: the judge ends at once, without a verdict.
  write_text(record, made.substr(0, seven));
  ProbeRun cut = probe(dir, "RT_GRADING_REPLAY", record);
  EXPECT_EQ(cut.exit_code, 86);
  EXPECT_NE(cut.said.find("grading: the record file ends inside a value"), std::string::npos) << cut.said;
  write_text(record, made.substr(0, made.size() / 2 - 12));
  EXPECT_EQ(probe(dir, "RT_GRADING_REPLAY", record).exit_code, 86);

  // Only the first record: the second value was never given.
  const std::uint32_t tag = *reinterpret_cast<const std::uint32_t*>(made.data());
  write_text(record, made.substr(0, 4 + tag + 8 + sizeof(int)));
  cut = probe(dir, "RT_GRADING_REPLAY", record);
  EXPECT_EQ(cut.exit_code, 86);
  EXPECT_NE(cut.said.find("ended before it gave the value at record_test.cpp:"), std::string::npos) << cut.said;

  // The records swapped: each names the place that asked for it.
  const std::string first = made.substr(0, 4 + tag + 8 + sizeof(int)), second = made.substr(first.size());
  write_text(record, second + first);
  const ProbeRun swapped = probe(dir, "RT_GRADING_REPLAY", record);
  EXPECT_EQ(swapped.exit_code, 86);
  EXPECT_NE(swapped.said.find("where the test asked for one at record_test.cpp:"), std::string::npos) << swapped.said;

  // A record more than the test asked for: the runs went different ways.
  write_text(record, made + second);
  const ProbeRun extra = probe(dir, "RT_GRADING_REPLAY", record);
  EXPECT_EQ(extra.exit_code, 86);
  EXPECT_NE(extra.said.find("more values than the test asked for"), std::string::npos) << extra.said;
}

}  // namespace
}  // namespace rt::testing
