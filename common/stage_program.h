// The shell of every stage program: the common command line (common/options.h), the stage's own
// flags, then the render. The flags are registered through StageFlags, a small interface that
// keeps CLI11 out of the stage programs: CLI11 costs seconds of compile time in every file that
// includes it (docs/build.md), and a stage program is compiled again whenever a task header
// changes. StageFlags and run_stage_program are defined in common/cli.cpp, which sees CLI11.
#pragma once

#include "common/options.h"

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace CLI {
class App;
}

namespace rt {

// How a number flag's text is checked (common/cli.cpp gives each rule as a CLI11 check).
struct FlagRule {
  enum class Kind { any, decimal, finite } kind = Kind::any;
  double lo = 0.0, hi = 0.0;
};
// Decimal digits only, an integer in [lo, hi].
inline FlagRule decimal_in(std::uint64_t lo, std::uint64_t hi) {
  return {FlagRule::Kind::decimal, double(lo), double(hi)};
}
// A finite number in [lo, hi].
inline FlagRule finite_in(double lo, double hi) { return {FlagRule::Kind::finite, lo, hi}; }

// The flags a stage adds to the common ones, each bound to the variable it sets.
class StageFlags {
 public:
  explicit StageFlags(CLI::App& app) : app_(app) {}

  void add(const std::string& name, int& value, const std::string& help, FlagRule rule = {});
  void add(const std::string& name, float& value, const std::string& help, FlagRule rule = {});
  void add(const std::string& name, std::optional<float>& value, const std::string& help, FlagRule rule = {});
  // Text; an empty value is refused.
  void add(const std::string& name, std::string& value, const std::string& help);
  // A file the program writes besides --out: checked with --out's before anything renders
  // (writable, not another output, not a file the scene reads).
  void add_output(const std::string& name, std::string& value, const std::string& help);
  // The outputs given on the command line, after parsing.
  std::vector<NamedOutput> outputs() const;
  // A word from `words`.
  void add_word(const std::string& name, std::string& value, const std::vector<std::string>& words,
                const std::string& help);
  // A word from `words`, each naming a value of the enum.
  template <class Enum>
  requires std::is_enum_v<Enum>
  void add_choice(const std::string& name, Enum& value, const std::vector<std::pair<std::string, Enum>>& words,
                  const std::string& help) {
    int& number = numbers_.emplace_back(static_cast<int>(value));
    write_backs_.push_back([&value, &number] { value = static_cast<Enum>(number); });
    add_choice_number(name, number, as_numbers(words), help);
  }
  // The same, left empty unless given (for a flag some modes refuse).
  template <class Enum>
  void add_choice(const std::string& name, std::optional<Enum>& value,
                  const std::vector<std::pair<std::string, Enum>>& words, const std::string& help) {
    constexpr int kNotGiven = -1;
    int& number = numbers_.emplace_back(kNotGiven);
    write_backs_.push_back([&value, &number] {
      if (number != kNotGiven) value = static_cast<Enum>(number);
    });
    add_choice_number(name, number, as_numbers(words), help);
  }
  // A switch without a value; `needs`: a switch it may only come with.
  void add_switch(const std::string& name, bool& value, const std::string& help, const std::string& needs = "");
  // --max-depth, for the stage programs that follow rays recursively (stage 2 on); `limits` says
  // what it limits there, for --help. A method whose paths end by Russian roulette alone has no
  // depth to limit and refuses the flag (stages 5 and 6).
  void add_max_depth(CommonOptions& options, const std::string& limits);

  // After parsing: the enums take the numbers their words were read as.
  void write_back() const {
    for (const std::function<void()>& write : write_backs_) write();
  }

 private:
  void add_choice_number(const std::string& name, int& number, const std::vector<std::pair<std::string, int>>& words,
                         const std::string& help);
  // The enum's words with its values as numbers, which the parser stores.
  template <class Enum>
  static std::vector<std::pair<std::string, int>> as_numbers(const std::vector<std::pair<std::string, Enum>>& words) {
    std::vector<std::pair<std::string, int>> numbers;
    for (const auto& [word, choice] : words) numbers.emplace_back(word, static_cast<int>(choice));
    return numbers;
  }

  CLI::App& app_;
  std::deque<int> numbers_;  // a deque: the numbers stay where the parser was told they are
  std::vector<std::function<void()>> write_backs_;
  std::vector<std::pair<std::string, const std::string*>> outputs_;
};

// Parses the command line into `options` (plus whatever `add_stage_flags` registered), then calls
// `run`. Maps --help to exit 0, usage errors to 2 and InputError to 1, each with one line on stderr
// that starts with the program name. The output path is checked before `run` is called, so no
// render is wasted on an unwritable path.
int run_stage_program(int argc, char** argv, const std::string& program, const std::string& title,
                      CommonOptions& options, const std::function<void(StageFlags&)>& add_stage_flags,
                      const std::function<void()>& run);

}  // namespace rt
