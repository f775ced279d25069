// The line between what a graded test computes with the submission's code and what it judges.
//
//   const auto t = subject([&] { return intersect_plane(ray, floor, Interval::positive()); });
//   ASSERT_TRUE(t);
//   EXPECT_NEAR(*t, 2.0f, 1e-6f);
//
// Everything that runs a student's code goes inside subject(), which returns plain data (a form in
// tests/support/record.h); every assertion stays outside. Run by hand or by ctest, subject() just
// calls the lambda. Under the grader each graded test runs twice (docs/instructors.md, "The
// verdict"): first the test program built with the submission, where subject() runs the lambda and
// records its value (RT_GRADING_RECORD names the file); then the same test program built with every
// task the starter's placeholder, the judge, where subject() never runs the lambda but reads the
// recorded value back (RT_GRADING_REPLAY). The judge decides the verdict and writes the report, and
// no code of the submission ever runs in it: the submission chooses only the values its code gives
// the test. A record missing, out of order or malformed ends the judge without a report, which
// fails the test.
//
// So a graded test's course must depend only on the values subject() gives and on the test's own
// code, which both runs share: no assertion inside the lambda (the judge would never evaluate it),
// no student call outside it (the judge would call the placeholder), no random number drawn inside
// it that the test draws again outside, no file the lambda wrote read outside it.
#pragma once

#include "support/record.h"

#include <atomic>
#include <source_location>
#include <string>
#include <type_traits>

namespace rt::testing {

enum class GradingRole { kLocal, kSubject, kJudge };

// Which run this is, from the environment (read once).
GradingRole grading_role();
// Subject: appends the value recorded at `where`. Judge: the value recorded at `where`, or the
// test ends (no report) when the next record is from elsewhere or there is none.
void record_value(const std::source_location& where, const std::string& bytes);
std::string replay_value(const std::source_location& where);
// The test ends (no report) with why `where`'s record is malformed.
[[noreturn]] void malformed_value(const std::source_location& where, const char* why);
// False when the judge did not read every record the subject run wrote: the two runs went different
// ways (the test program's main then ends with an error).
bool judge_used_every_record();

// How many subject() calls are running their lambdas (on any thread). One called from inside
// another's lambda (a helper that takes its values through subject(), called within a larger
// computation that is taken whole) just runs its lambda: the outer call records the whole.
inline std::atomic<int> subjects_running{0};

template <class Compute>
auto subject(Compute&& compute, std::source_location where = std::source_location::current()) {
  using Value = std::remove_cvref_t<std::invoke_result_t<Compute&>>;
  const GradingRole role = grading_role();
  if (role == GradingRole::kLocal || subjects_running.load() > 0) return Value(compute());
  std::string bytes;
  if (role == GradingRole::kSubject) {
    RecordWriter out;
    ++subjects_running;
    try {
      write_record(out, Value(compute()));
    } catch (...) {
      --subjects_running;
      throw;
    }
    --subjects_running;
    bytes = std::move(out.out());
    record_value(where, bytes);
  } else {
    bytes = replay_value(where);
  }
  // Both runs go on with the value as read back from its record, so that they take the same course.
  Value value{};
  try {
    RecordReader in(bytes);
    read_record(in, value);
    if (in.left() != 0) throw MalformedRecord{"bytes are left over"};
  } catch (const MalformedRecord& e) {
    malformed_value(where, e.what);
  }
  return value;
}

// A call taken through subject() whose arguments are evaluated by the test itself, in both runs:
//   RT_GRADED(brdf.sample)(wo, rng.uniform2(), rng.uniform())
// draws its random numbers outside the lambda, so the judge draws them too.
template <class Call>
struct Graded {
  Call call;
  std::source_location where;
  template <class... Arguments>
  auto operator()(Arguments&&... arguments) const {
    return subject([&] { return call(std::forward<Arguments>(arguments)...); }, where);
  }
};
template <class Call>
Graded<Call> graded(Call call, std::source_location where = std::source_location::current()) {
  return {std::move(call), where};
}

}  // namespace rt::testing

#define RT_GRADED(function)                                                                         \
  ::rt::testing::graded([&](auto&&... arguments) -> decltype(auto) {                               \
    return function(std::forward<decltype(arguments)>(arguments)...);                              \
  })
