#include "common/cli.h"

#include "common/stage_program.h"

#include "common/error.h"
#include "common/file_io.h"
#include "common/image_io.h"
#include "common/interrupt.h"
#include "common/sample_batch.h"

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace rt {

RenderSettings CommonOptions::settings_for(const SceneDescription& description) const {
  RenderSettings s = description.render;
  if (spp) s.spp = *spp;
  if (width) s.width = *width;
  if (height) s.height = *height;
  if (seed) s.seed = *seed;
  if (max_depth) s.max_depth = *max_depth;
  if (filter) s.filter = pixel_filter_from_name(*filter).value();  // --filter's check admits only known names
  if (sample_range) {
    const SampleRangeFlag range = parse_sample_range(*sample_range);
    s.first_sample = range.first;
    s.spp = range.count;
  }
  if (crop) s.crop = parse_crop(*crop, s.width, s.height);
  std::vector<std::string> inputs = files_read_by(description);
  inputs.push_back(scene);
  require_outputs_spare_inputs(outputs_of(out, more_outputs), inputs);
  const MemoryLimit limit = memory_limit();
  check_image_fits(out, s.window().width(), s.window().height(), limit);
  check_scene_fits(scene, triangle_count(description), {double(s.window().area()) * double(kBytesPerPixel), "the image"},
                   limit);
  return s;
}

std::vector<std::string> output_files(const std::string& out) {
  if (!is_batch_path(out)) return {out};
  return {out, batch_sum_path(out).string(), batch_count_path(out).string()};
}

std::vector<NamedOutput> outputs_of(const std::string& out, const std::vector<NamedOutput>& more) {
  std::vector<NamedOutput> outputs;
  for (const std::string& file : output_files(out)) outputs.push_back({"--out", file});
  outputs.insert(outputs.end(), more.begin(), more.end());
  return outputs;
}

void check_outputs(const std::vector<NamedOutput>& outputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    check_output_writable(outputs[i].file);
    for (size_t j = 0; j < i; ++j)
      if (same_file(outputs[i].file, outputs[j].file))
        throw UsageError(outputs[i].flag + " " + outputs[i].file + " is the file " + outputs[j].flag +
                         " writes too: one would be lost (give each output its own name)");
  }
}

void require_outputs_spare_inputs(const std::vector<NamedOutput>& outputs, const std::vector<std::string>& inputs) {
  for (const NamedOutput& output : outputs)
    for (const std::string& input : inputs)
      if (same_file(output.file, input))
        throw UsageError(output.flag + " " + output.file + " would overwrite the input " + input +
                         " (give another output name)");
}

namespace {

// A non-negative decimal integer up to `max`, the whole of `text`.
std::optional<int> parse_count(const std::string& text, int max) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return {};
  const int value = std::stoi(text);
  if (value > max) return {};
  return value;
}

// "a:b" as two numbers up to `max`.
std::optional<std::pair<int, int>> parse_span(const std::string& text, int max) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos) return {};
  const auto a = parse_count(text.substr(0, colon), max), b = parse_count(text.substr(colon + 1), max);
  if (!a || !b) return {};
  return std::pair(*a, *b);
}

// Why `text` is not a sample range a:b, or "" when it is one.
std::string sample_range_problem(const std::string& text) {
  const auto span = parse_span(text, kMaxSpp);
  if (!span) return "expected a:b, two whole numbers up to " + std::to_string(kMaxSpp);
  if (span->first >= span->second) return "the range a:b holds samples a to b - 1, so a must be less than b";
  return "";
}

// Why `text` is not a crop window x0:x1,y0:y1 inside a width x height image, or "".
std::string crop_problem(const std::string& text, int width, int height) {
  const size_t comma = text.find(',');
  if (comma == std::string::npos) return "expected x0:x1,y0:y1, four whole numbers";
  const auto x = parse_span(text.substr(0, comma), kMaxImageSide), y = parse_span(text.substr(comma + 1), kMaxImageSide);
  if (!x || !y) return "expected x0:x1,y0:y1, four whole numbers";
  if (x->first >= x->second || y->first >= y->second) return "the window [x0, x1) x [y0, y1) is empty";
  if (x->second > width || y->second > height)
    return "the window reaches beyond the " + std::to_string(width) + "x" + std::to_string(height) + " image";
  return "";
}

// A CLI11 check of a flag's text: `problem(text)` says what is wrong, or "".
CLI::Validator text_check(std::function<std::string(const std::string&)> problem, const char* form) {
  return CLI::Validator(
      [problem](std::string& text) {
        const std::string why = problem(text);
        return why.empty() ? why : text + ": " + why;
      },
      form);
}

}  // namespace

SampleRangeFlag parse_sample_range(const std::string& text) {
  if (const std::string why = sample_range_problem(text); !why.empty())
    throw UsageError("--sample-range " + text + ": " + why);
  const auto span = parse_span(text, kMaxSpp);
  return {span->first, span->second - span->first};
}

PixelRect parse_crop(const std::string& text, int width, int height) {
  if (const std::string why = crop_problem(text, width, height); !why.empty())
    throw UsageError("--crop " + text + ": " + why);
  const size_t comma = text.find(',');
  const auto x = parse_span(text.substr(0, comma), kMaxImageSide), y = parse_span(text.substr(comma + 1), kMaxImageSide);
  return {x->first, y->first, x->second, y->second};
}

namespace {

// Each of the stage's own flags with its default as text (CLI11 turns a value into the same text
// whether it was typed or is the default, e.g. an enum's number), taken before parsing; the
// defaults are then cleared again so that --help shows what it always showed.
std::vector<std::pair<CLI::Option*, std::string>> stage_flag_defaults(CLI::App& app,
                                                                      const std::set<std::string>& common) {
  std::vector<std::pair<CLI::Option*, std::string>> flags;
  for (CLI::Option* option : app.get_options()) {
    if (common.count(option->get_name())) continue;
    const std::string shown = option->get_default_str();
    option->capture_default_str();
    flags.emplace_back(option, option->get_items_expected_max() == 0 ? "false" : option->get_default_str());
    option->default_str(shown);
  }
  return flags;
}

std::string describe_flags(const std::vector<std::pair<CLI::Option*, std::string>>& flags) {
  std::string text;
  for (const auto& [option, default_value] : flags) {
    std::string value = default_value;
    if (option->count() > 0) {
      value.clear();
      for (const std::string& r : option->results()) value += (value.empty() ? "" : ",") + r;
    }
    text += (text.empty() ? "" : " ") + option->get_name() + "=" + value;
  }
  return text;
}

}  // namespace

CLI::Validator decimal(std::uint64_t lo, std::uint64_t hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [lo, hi, range](std::string& text) {
        std::uint64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        if (!digits) return text + ": not a whole number in decimal digits";
        if (error == std::errc::result_out_of_range || end != text.data() + text.size() || value < lo || value > hi)
          return text + ": must be in " + range;
        text = std::to_string(value);
        return std::string();
      },
      "INT in " + range);
}

CLI::Validator finite_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) {
        double value = 0.0;
        // Decimal notation only: std::stod also reads "0x10" (16), "inf" and "nan".
        if (text.empty() || text.find_first_not_of("0123456789+-.eE") != std::string::npos)
          return text + ": not a decimal number";
        try {
          size_t used = 0;
          value = std::stod(text, &used);
          if (used != text.size()) return text + ": not a number";
        } catch (const std::exception&) {
          return text + ": not a number";
        }
        if (!std::isfinite(value) || value < lo || value > hi)
          return text + ": must be a finite number in [" + CLI::detail::to_string(lo) + ", " +
                 CLI::detail::to_string(hi) + "]";
        return std::string();
      },
      "FLOAT in [" + CLI::detail::to_string(lo) + " - " + CLI::detail::to_string(hi) + "]");
}

void add_image_encoding_flags(CLI::App& app, ImageEncoding& encoding) {
  DisplayTransform& display = encoding.display;
  app.add_option_function<double>(
         "--exposure", [&display](double stops) { display.exposure_stops = float(stops); },
         "PNG only: exposure in stops, each doubling the radiance before the tone curve (default 0)")
      ->check(finite_range(-64.0, 64.0));
  std::map<std::string, ToneCurve> tones;
  for (const auto& [tone, name] : kToneCurveNames) tones[name] = tone;
  app.add_option("--tone", display.tone, "PNG only: tone curve clamp (default), reinhard or aces")
      ->transform(CLI::CheckedTransformer(tones));
  app.add_option_function<double>(
         "--white", [&display](double white) { display.white = float(white); },
         "PNG only: the luminance Reinhard's curve maps to 1 (default 4)")
      ->check(finite_range(1e-3, 1e6));
  app.add_option_function<double>(
         "--gamma",
         [&display](double gamma) {
           display.transfer = TransferCurve::gamma;
           display.gamma = float(gamma);
         },
         "PNG only: encode with the power 1/gamma instead of the sRGB curve")
      ->check(finite_range(0.2, 5.0));
  app.add_flag("--exr-half", encoding.exr_half, "EXR only: 16-bit half floats instead of 32-bit floats");
}

namespace {

CLI::Validator rule_check(FlagRule rule) {
  switch (rule.kind) {
    case FlagRule::Kind::decimal: return decimal(std::uint64_t(rule.lo), std::uint64_t(rule.hi));
    case FlagRule::Kind::finite: return finite_range(rule.lo, rule.hi);
    case FlagRule::Kind::any: break;
  }
  return CLI::Validator();
}

template <class T>
void add_checked(CLI::App& app, const std::string& name, T& value, const std::string& help, FlagRule rule) {
  CLI::Option* option = app.add_option(name, value, help);
  if (rule.kind != FlagRule::Kind::any) option->transform(rule_check(rule));
}

}  // namespace

void StageFlags::add(const std::string& name, int& value, const std::string& help, FlagRule rule) {
  add_checked(app_, name, value, help, rule);
}
void StageFlags::add(const std::string& name, float& value, const std::string& help, FlagRule rule) {
  add_checked(app_, name, value, help, rule);
}
void StageFlags::add(const std::string& name, std::optional<float>& value, const std::string& help, FlagRule rule) {
  add_checked(app_, name, value, help, rule);
}
void StageFlags::add(const std::string& name, std::string& value, const std::string& help) {
  app_.add_option(name, value, help)
      ->check(CLI::Validator([](const std::string& t) { return t.empty() ? "must not be empty" : ""; }, "TEXT"));
}

void StageFlags::add_output(const std::string& name, std::string& value, const std::string& help) {
  add(name, value, help);
  outputs_.push_back({name, &value});
}

std::vector<NamedOutput> StageFlags::outputs() const {
  std::vector<NamedOutput> given;
  for (const auto& [name, value] : outputs_)
    if (!value->empty()) given.push_back({name, *value});
  return given;
}

void StageFlags::add_word(const std::string& name, std::string& value, const std::vector<std::string>& words,
                          const std::string& help) {
  app_.add_option(name, value, help)->check(CLI::IsMember(words));
}

void StageFlags::add_choice_number(const std::string& name, int& number,
                                   const std::vector<std::pair<std::string, int>>& words, const std::string& help) {
  app_.add_option(name, number, help)
      ->transform(CLI::CheckedTransformer(std::map<std::string, int>(words.begin(), words.end())));
}

void StageFlags::add_switch(const std::string& name, bool& value, const std::string& help, const std::string& needs) {
  CLI::Option* option = app_.add_flag(name, value, help);
  if (!needs.empty()) option->needs(app_.get_option(needs));
}

void StageFlags::add_max_depth(CommonOptions& options, const std::string& limits) {
  app_.add_option("--max-depth", options.max_depth, "Depth limit: " + limits + " (default: the scene's max_depth)")
      ->transform(decimal(0, 1000));
}

int run_stage_program(int argc, char** argv, const std::string& program, const std::string& title,
                      CommonOptions& options, const std::function<void(StageFlags&)>& add_stage_flags,
                      const std::function<void()>& run) {
  CLI::App app(title, program);
  app.add_option("--scene", options.scene, "Scene file (JSON, see docs/scene-format.md)")
      ->required();
  app.add_option("--out", options.out,
                 "Output; the ending picks the format: .png, .pfm or .exr (the image), or .json (a sample batch "
                 "for merge: the undivided sums and counts, see docs/scale-out.md)")
      ->required();
  CLI::Option* spp = app.add_option("--spp", options.spp, "Samples per pixel (default: the scene's)")
                         ->transform(decimal(1, kMaxSpp));
  app.add_option("--width", options.width, "Image width in pixels (default: the scene's)")
      ->transform(decimal(1, kMaxImageSide));
  app.add_option("--height", options.height, "Image height in pixels (default: the scene's)")
      ->transform(decimal(1, kMaxImageSide));
  app.add_option("--threads", options.threads, "Worker threads, 0 = all cores")
      ->transform(decimal(0, 1024));
  // Checked as text: CLI11 would wrap "-1" around to 2^64 - 1 and clamp 2^64 to 2^64 - 1.
  app.add_option("--seed", options.seed, "Random seed (default: the scene's)")
      ->transform(decimal(0, std::numeric_limits<std::uint64_t>::max()));
  // Their form is checked here, the crop's fit to the image once the scene's size is known.
  app.add_option("--sample-range", options.sample_range,
                 "Render samples a to b - 1 of each pixel (a:b), e.g. one batch of a render split "
                 "across machines")
      ->check(text_check(sample_range_problem, "a:b"))
      ->excludes(spp);
  app.add_option("--crop", options.crop, "Render only the pixels [x0, x1) x [y0, y1) (x0:x1,y0:y1), e.g. one tile")
      ->check(text_check([](const std::string& t) { return crop_problem(t, kMaxImageSide, kMaxImageSide); },
                         "x0:x1,y0:y1"));
  std::vector<std::string> filter_names;
  for (const auto& entry : kPixelFilterNames) filter_names.push_back(entry.second);
  app.add_option("--filter", options.filter,
                 "Pixel reconstruction filter: box, tent, gaussian, mitchell or blackman-harris (default: the "
                 "scene's, or box)")
      ->check(CLI::IsMember(filter_names));
  add_image_encoding_flags(app, options.encoding);
  const std::set<std::string> common_flags = {
      "--help", "--scene", "--out", "--spp", "--width", "--height", "--threads", "--seed", "--sample-range",
      "--crop", "--max-depth", "--filter", "--exposure", "--tone", "--white", "--gamma", "--exr-half"};
  StageFlags flags(app);
  add_stage_flags(flags);
  const std::vector<std::pair<CLI::Option*, std::string>> stage_flags = stage_flag_defaults(app, common_flags);

  if (const std::optional<int> exit_code = parse_command_line(app, argc, argv, program)) return *exit_code;
  flags.write_back();
  options.image_flags = describe_flags(stage_flags);
  options.more_outputs = flags.outputs();

  InterruptHandler interrupt_handler;
  return run_reporting_errors(
      program,
      [&] {
        if (!is_batch_path(options.out)) image_format_for(options.out);
        // Every output is checked before anything renders: none may fail, or be lost, at the end.
        const std::vector<NamedOutput> outputs = outputs_of(options.out, options.more_outputs);
        check_outputs(outputs);
        require_outputs_spare_inputs(outputs, {options.scene});
        run();
      },
      options.scene);
}

std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv, const std::string& program) {
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: error: %s (see --help)\n", program.c_str(), printable(e.what()).c_str());
    return kExitBadUsage;
  }
}

int run_reporting_errors(const std::string& program, const std::function<void()>& body, const std::string& subject) {
  auto report = [&](const char* kind, const std::string& what) {
    std::fprintf(stderr, "%s: %s%s\n", program.c_str(), kind, printable(what).c_str());
  };
  try {
    body();
    return kExitOk;
  } catch (const Interrupted& stop) {
    if (!stop.message.empty()) report("", stop.message);
    return 128 + stop.signal_number;
  } catch (const UsageError& e) {
    report("error: ", e.what());
    return kExitBadUsage;
  } catch (const InputError& e) {
    report("error: ", e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    report("error: ", (subject.empty() ? "" : subject + ": ") + "out of memory, and " + memory_limit().describe());
    return kExitBadInput;
  } catch (const std::exception& e) {
    report("error: ", e.what());
    return kExitBadInput;
  }
}

}  // namespace rt
