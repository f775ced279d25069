// Reliability (label "reliability"): hostile input, absurd sizes, Ctrl-C and SIGTERM mid-render, a
// killed run, and every input the fuzzers were seeded with or found, each refused in one line or
// loaded, never crashing.
#include "01-ray-casting/render.h"
#include "common/options.h"
#include "common/error.h"
#include "common/image_io.h"
#include "common/interrupt.h"
#include "common/obj_loader.h"
#include "common/sample_batch.h"
#include "common/scene.h"

#include "fuzz/batch_inputs.h"
#include "fuzz/image_input.h"
#include "reliability/child_process.h"
#include "reliability/stage_programs.h"
#include "support/glowing_room.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <map>
#include <thread>

namespace rt {
namespace {

using namespace std::chrono_literals;
using testing::ChildProcess;
using testing::ScratchDir;
using testing::source_path;

using testing::kPrograms;

// Loads, or is refused with InputError: one line that names the source.
template <class Load>
void expect_loads_or_one_line(const std::filesystem::path& file, const std::string& source, Load&& load) {
  try {
    load(testing::read_text(file), source);
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << file << ": " << message;
    EXPECT_FALSE(message.empty()) << file;
  } catch (const std::exception& e) {
    ADD_FAILURE() << file << ": not an InputError: " << e.what();
  }
}

TEST(FuzzInputs, EverySeedAndFindingLoadsOrIsRefusedInOneLine) {
  // The fuzzers' seed corpus and every input they ever found a bug with (tests/fuzz/), replayed
  // here in the normal build and under the sanitizer preset.
  ScratchDir batch_folder;
  fuzzing::write_batch_images(batch_folder.path());
  std::map<std::string, int> files;
  for (const char* folder : {"tests/fuzz/corpus", "tests/fuzz/regressions"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(source_path(folder))) {
      if (!entry.is_regular_file() || entry.path().filename() == ".keep") continue;
      const std::string kind = entry.path().parent_path().filename().string();
      if (kind == "scene")
        expect_loads_or_one_line(entry.path(), "fuzz.json", [](const std::string& t, const std::string& s) { parse_scene(t, s); });
      else if (kind == "obj")
        expect_loads_or_one_line(entry.path(), "fuzz.obj", [](const std::string& t, const std::string& s) { parse_obj(t, s); });
      else if (kind == "batch")
        expect_loads_or_one_line(entry.path(), "input.json", [&](const std::string& t, const std::string& s) {
          fuzzing::read_batch_text(batch_folder.path(), t, s);
        });
      else if (kind == "image")
        expect_loads_or_one_line(entry.path(), "", [](const std::string& t, const std::string&) { fuzzing::decode_image_input(t); });
      else if (kind == "merge") {
        EXPECT_NO_THROW(fuzzing::merge_batch_texts(batch_folder.path(), testing::read_text(entry.path()))) << entry.path();
      }
      ++files[kind];
    }
  }
  for (const char* kind : {"scene", "obj", "batch", "merge", "image"}) EXPECT_GE(files[kind], 3) << kind;
  // The batch seeds are valid: they carry the fingerprints of the images the fuzzers write.
  EXPECT_EQ(fuzzing::read_batch_text(batch_folder.path(), testing::read_text(source_path("tests/fuzz/corpus/batch/whole.json")),
                                     "whole.json")
                .sums.total_count(),
            16u);
}

TEST(HostileFiles, DevicesAndFoldersAreRefusedNotReadForever) {
  // Found by the scene fuzzer: a mesh file "/dev/zero" was read until memory ran out.
  ScratchDir dir;
  for (const std::string& path : {std::string("/dev/zero"), dir.path().string()}) {
    try {
      load_obj(path);
      ADD_FAILURE() << path << " loaded";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ": cannot read mesh file: not a regular file"), std::string::npos) << e.what();
    }
    EXPECT_THROW(load_scene(path), InputError);
  }
  testing::write_text(dir / "scene.json", testing::read_text(source_path("tests/fuzz/regressions/scene/mesh-file-is-dev-zero.json")));
  testing::expect_one_line_error(testing::run_command(std::string(STAGE2_EXE) + " --scene " + (dir / "scene.json").string() +
                                                          " --out " + (dir / "x.png").string(), dir),
                                 1, "/dev/zero: cannot read mesh file: not a regular file");
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// Each kind of broken input, through a program: exit 1, one line naming the file and the problem,
// no output file. (The loaders' own suites check every message; this is the end-to-end promise.)
TEST(HostileFiles, BrokenScenesAndMeshesAreOneLineAndWriteNothing) {
  ScratchDir dir;
  const std::string camera = R"("camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 30})";
  testing::write_text(dir / "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
  testing::write_text(dir / "index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  testing::write_text(dir / "empty.obj", "");
  const std::pair<std::string, std::string> cases[] = {
      {"{" + camera + R"(, "materials": {"m": {}}, "shapes": [{"type": "sphere", "center": "up", "radius": 1, "material": "m"}]})",
       "/shapes/0/center"},
      {"{" + camera + R"(, "materials": {"m": {}}, "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "m"}]})",
       "/shapes/0/radius"},
      {"{" + camera + R"(, "materials": {"m": {}}, "shapes": [], "colour": [1, 0, 0]})", "unknown key 'colour'"},
      {"{" + camera + R"(, "materials": {"m": {"albedo": [0.5, 1e39, 0.5]}}, "shapes": []})", "beyond float's range"},
      {"{" + camera + R"(, "materials": {}, "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "gold"}]})",
       "unknown material 'gold'"},
      {"{" + camera + R"(, "materials": {"m": {}}, "shapes": [{"type": "mesh", "file": "none.obj", "material": "m"}]})",
       "none.obj: cannot open mesh file"},
      {"{" + camera + R"(, "materials": {"m": {}}, "shapes": [{"type": "mesh", "file": "nan.obj", "material": "m"}]})",
       "nan.obj:2: vertex needs three finite coordinates"},
      {"{" + camera + R"(, "materials": {"m": {}}, "shapes": [{"type": "mesh", "file": "index.obj", "material": "m"}]})",
       "index.obj:4: vertex index 7 is out of range"},
      {"{" + camera + R"(, "materials": {"m": {}}, "shapes": [{"type": "mesh", "file": "empty.obj", "material": "m"}]})",
       "empty.obj: the mesh has no faces"},
      {"{" + camera + ", ", "scene.json"}};
  for (const auto& [scene, fragment] : cases) {
    testing::write_text(dir / "scene.json", scene);
    for (const char* program : {STAGE2_EXE, STAGE5_EXE}) {
      const auto r = testing::run_command(std::string(program) + " --scene " + (dir / "scene.json").string() + " --out " +
                                              (dir / "x.png").string(), dir);
      testing::expect_one_line_error(r, 1, fragment);
      EXPECT_NE(r.err.find("scene.json"), std::string::npos) << r.err;
      EXPECT_FALSE(std::filesystem::exists(dir / "x.png")) << program << ": " << fragment;
    }
  }
}

TEST(ImageSize, RefusedBeforeAnythingIsAllocatedWithTheFigure) {
  const MemoryLimit eight_gib{std::uint64_t(8) << 30, MemoryLimit::Source::machine};
  EXPECT_NO_THROW(check_image_fits("a.png", 8192, 13107, eight_gib));  // 8 GiB less 128 KiB: fits
  EXPECT_THROW(check_image_fits("a.png", 8192, 13108, eight_gib), InputError);  // 8 GiB and 512 KiB: does not
  try {
    check_image_fits("a.png", 40000, 50000, eight_gib);
    ADD_FAILURE() << "a 40000x50000 image fits in 8 GiB";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "a.png: a 40000x50000 image needs 149.0 GiB of memory (its sample sums, the image and "
                           "the encoded file), and this machine has 8.0 GiB");
  }
  EXPECT_THROW(check_image_fits("a.png", 1 << 20, 1 << 20, MemoryLimit{~std::uint64_t(0), MemoryLimit::Source::machine}),
               InputError);  // 2^40 pixels
}

TEST(ImageSize, EveryProgramRefusesAnImageLargerThanTheMachine) {
  ScratchDir dir;
  for (const char* program : kPrograms) {
    const auto r = testing::run_command(std::string(program) + " --scene " + source_path("assets/scenes/spheres.json").string() +
                                            " --width 1048576 --height 1048576 --out " + (dir / "big.png").string(), dir);
    testing::expect_one_line_error(r, 1, "big.png: a 1048576x1048576 image has more than 2^31 - 1 pixels");
    const auto r2 = testing::run_command(std::string(program) + " --scene " + source_path("assets/scenes/spheres.json").string() +
                                             " --width 40000 --height 50000 --out " + (dir / "big.png").string(), dir);
    if (physical_memory_bytes() < std::uint64_t(40000) * 50000 * kBytesPerPixel) {
      testing::expect_one_line_error(r2, 1, "image needs 149.0 GiB of memory");
      EXPECT_NE(r2.err.find("this machine has"), std::string::npos) << r2.err;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "big.png")) << program;
  }
}

TEST(CommandLine, ImpossibleNumbersAreOneLineUsageErrors) {
  ScratchDir dir;
  const std::string scene = " --scene " + source_path("assets/scenes/spheres.json").string() + " --out " + (dir / "x.png").string();
  for (const char* program : kPrograms)
    for (const char* flags : {"--spp 0", "--spp -4", "--width 0", "--height -1", "--threads -2", "--spp 99999999999",
                              "--width 1e9", "--seed -1", "--spp four"}) {
      const auto r = testing::run_command(std::string(program) + scene + " " + flags, dir);
      testing::expect_one_line_error(r, 2, "");
      EXPECT_FALSE(std::filesystem::exists(dir / "x.png")) << program << " " << flags;
    }
}

// Found by trying: "--exposure 0x10" was read as 16 (std::stod reads hexadecimal), and an empty
// --strategy or --sample-map was taken as if the flag were absent. Every float flag shares the one
// validator; every text flag refuses an empty value.
TEST(CommandLine, HexadecimalFloatsAndEmptyTextAreOneLineUsageErrors) {
  ScratchDir dir;
  const std::string scene = " --scene " + source_path("assets/scenes/spheres.json").string() + " --out " +
                            (dir / "x.png").string() + " --width 8 --height 8 --spp 1 ";
  const std::pair<const char*, const char*> cases[] = {
      {STAGE1_EXE, "--exposure 0x10"}, {STAGE1_EXE, "--white 0x1p3"},  {STAGE1_EXE, "--gamma 0X2"},
      {STAGE1_EXE, "--exposure inf"},  {STAGE1_EXE, "--exposure nan"}, {STAGE2_EXE, "--epsilon 0x1p-10"},
      {STAGE5_EXE, "--adaptive 0x0.1p0"}, {STAGE6_EXE, "--method sppm --radius 0x1"},
      {STAGE6_EXE, "--method sppm --alpha 0x.8p0"}, {STAGE6_EXE, "--strategy ''"},
      {STAGE5_EXE, "--adaptive 0.1 --sample-map ''"}};
  for (const auto& [program, flags] : cases) {
    const auto r = testing::run_command(std::string(program) + scene + flags, dir);
    testing::expect_one_line_error(r, 2, std::string(flags).find("''") != std::string::npos ? "must not be empty"
                                                                                           : "not a decimal number");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png")) << program << " " << flags;
  }
  // Decimal notation in all its forms is still a number.
  for (const char* exposure : {"1", "-1.5", "+.5", "2e-1", "1E1"})
    EXPECT_EQ(testing::run_command(std::string(STAGE1_EXE) + scene + "--exposure " + exposure, dir).exit_code, 0)
        << exposure;
}

// A render in this process that a "signal" stops after `after` samples: every pixel it reached is
// the mean of the samples it finished, so with a constant radiance exactly that constant.
TEST(Interrupt, PartialImageIsNormalizedPerPixel) {
  const Camera camera(CameraSpec{}, 40, 30);
  RenderSettings settings;
  settings.width = 40, settings.height = 30, settings.spp = 64;
  std::atomic<int> samples{0};
  auto radiance = [&](const Ray&, Sampler&) {
    if (++samples == 20000) request_interrupt(SIGINT);
    return Color(0.25f);
  };
  ProgressBar progress(40 * 30 * 64, "samples", false);
  const Image image = render_image(camera, settings, 2, radiance, &progress);
  clear_interrupt();
  int reached = 0, black = 0;
  for (const Color& c : image.pixels()) {
    if (c == Color(0.25f)) ++reached;
    else if (c == Color(0.0f)) ++black;
    else ADD_FAILURE() << "pixel " << c.r << " is neither the mean of its samples nor black";
  }
  EXPECT_GT(reached, 0);
  EXPECT_GT(black, 0);
  EXPECT_LT(progress.done(), 40u * 30u * 64u);  // the progress counts what was done, not what was asked
  EXPECT_GE(progress.done(), 20000u);
}


// stage5 on the glowing room at 2^20 samples per pixel: hours, unless stopped.
struct LongRender {
  ScratchDir& dir;
  std::filesystem::path out;
  ChildProcess child;
  LongRender(ScratchDir& d, const std::string& output)
      : dir(d), out(d / output),
        child({STAGE5_EXE, "--scene", write_scene(d), "--width", "64", "--height", "64", "--spp", "1048576",
               "--threads", "2", "--out", out.string()}, d / "stdout.txt", d / "stderr.txt") {}
  static std::string write_scene(ScratchDir& d) {
    testing::write_text(d / "room.json", testing::kGlowingRoom);
    return (d / "room.json").string();
  }
};

std::vector<std::string> temporaries(const ScratchDir& dir) {
  std::vector<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    if (entry.path().filename().string().find(".tmp") != std::string::npos) found.push_back(entry.path().string());
  return found;
}

void expect_stops_and_writes(int signal_number) {
  ScratchDir dir;
  LongRender run(dir, "partial.pfm");
  ASSERT_TRUE(run.child.started());
  std::this_thread::sleep_for(700ms);  // well into the render (which would take hours)
  run.child.signal(signal_number);
  const std::optional<int> status = run.child.wait_for(1000ms);
  ASSERT_TRUE(status) << "still running a second after the signal";
  ASSERT_TRUE(WIFEXITED(*status));
  EXPECT_EQ(WEXITSTATUS(*status), 128 + signal_number);
  const std::string said = testing::read_text(dir / "stdout.txt");
  EXPECT_NE(said.find("stage5: interrupted by"), std::string::npos) << said;
  EXPECT_NE(said.find("samples"), std::string::npos) << said;
  const Image image = read_pfm(run.out);
  int lit = 0;
  for (const Color& c : image.pixels()) lit += c.r > 0.0f ? 1 : 0;
  EXPECT_GT(lit, 0) << "no pixel of the samples finished was written";
  EXPECT_TRUE(temporaries(dir).empty());
}

TEST(Interrupt, CtrlCStopsWithinASecondAndWritesTheSamplesSoFar) { expect_stops_and_writes(SIGINT); }
TEST(Interrupt, SigtermStopsWithinASecondAndWritesTheSamplesSoFar) { expect_stops_and_writes(SIGTERM); }
// A closed terminal sends SIGHUP: the render is stopped and kept, not lost.
TEST(Interrupt, SighupStopsLikeSigterm) { expect_stops_and_writes(SIGHUP); }

// Found by trying: Ctrl-C in stage 6's SPPM waited for the photon pass under way to end (13-46 s
// with 2 * 10^7 photons). The stop is checked per chunk of photons and between a pass's steps: a
// pass cut short is dropped, and a stop in the first pass writes nothing, as for every method.
// Here a pass takes some 2.5 s (3 * 10^6 photons): 0.7 s in, the run must end within 2 s.
// An SPPM render of the Cornell box at 16 x 16 with `photons` a pass, Ctrl-C `after` its start:
// its exit status, or none if it still ran 2 s after the signal. The image goes to dir/sppm.pfm.
std::optional<int> sppm_stopped_after(const ScratchDir& dir, const char* photons, std::chrono::milliseconds after) {
  ChildProcess child({STAGE6_EXE, "--scene", source_path("assets/scenes/cornell-box.json").string(), "--method", "sppm",
                      "--width", "16", "--height", "16", "--spp", "100000", "--photons", photons, "--threads", "2",
                      "--out", (dir / "sppm.pfm").string()},
                     dir / "stdout.txt", dir / "stderr.txt");
  EXPECT_TRUE(child.started());
  std::this_thread::sleep_for(after);
  child.signal(SIGINT);
  return child.wait_for(2000ms);
}

TEST(Interrupt, SppmStopsInsideAPhotonPass) {
  ScratchDir dir;
  const std::optional<int> status = sppm_stopped_after(dir, "3000000", 700ms);
  ASSERT_TRUE(status) << "still running 2 s after Ctrl-C";
  ASSERT_TRUE(WIFEXITED(*status));
  EXPECT_EQ(WEXITSTATUS(*status), 128 + SIGINT);
  EXPECT_FALSE(std::filesystem::exists(dir / "sppm.pfm")) << "no pass had ended";
}

// The passes that ended before the stop are the image: finite, and lit.
TEST(Interrupt, SppmKeepsThePassesThatEnded) {
  ScratchDir dir;
  const std::optional<int> status = sppm_stopped_after(dir, "20000", 1500ms);
  ASSERT_TRUE(status && WIFEXITED(*status));
  EXPECT_EQ(WEXITSTATUS(*status), 128 + SIGINT);
  const Image image = read_pfm(dir / "sppm.pfm");
  double sum = 0.0;
  for (const Color& c : image.pixels()) {
    ASSERT_TRUE(is_finite(c));
    sum += double(c.r + c.g + c.b);
  }
  EXPECT_GT(sum, 0.0);
}

// The render takes its samples in passes over the whole image, so a stopped one is a usable,
// uniformly sampled image (each pixel at most one pass apart), not a few finished pixels: before,
// every pixel took all 2^20 of its samples before the next began, and a stop after 0.7 s left one
// pixel lit.
TEST(Interrupt, AStoppedRenderHasNearlyTheSameSamplesInEveryPixel) {
  ScratchDir dir;
  LongRender run(dir, "partial.json");
  ASSERT_TRUE(run.child.started());
  std::this_thread::sleep_for(1500ms);  // a pass over the image takes some 0.1 s, 0.5 s under the sanitizers
  run.child.signal(SIGTERM);
  ASSERT_TRUE(run.child.wait_for(2000ms));
  const SampleBatch batch = read_sample_batch(run.out);
  ASSERT_TRUE(batch.interrupted);
  const auto [least, most] = std::minmax_element(batch.sums.counts().begin(), batch.sums.counts().end());
  const std::uint32_t pass = std::uint32_t(samples_per_pass(64 * 64, 1 << 20));
  EXPECT_GE(*least, pass) << "every pixel has finished its first pass";
  EXPECT_LE(*most - *least, pass) << "no pixel is more than one pass ahead of another";
}

TEST(Interrupt, SecondCtrlCQuitsAtOnceLeavingNoFileBehind) {
  ScratchDir dir;
  LongRender run(dir, "never.pfm");
  ASSERT_TRUE(run.child.started());
  std::this_thread::sleep_for(700ms);
  run.child.signal(SIGINT);
  run.child.signal(SIGINT);
  const std::optional<int> status = run.child.wait_for(1000ms);
  ASSERT_TRUE(status);
  ASSERT_TRUE(WIFEXITED(*status));
  EXPECT_EQ(WEXITSTATUS(*status), 128 + SIGINT);
  // Either the first stop finished writing before the second arrived, or nothing was written:
  // never a half-written image, never a temporary file.
  if (std::filesystem::exists(run.out)) {
    EXPECT_NO_THROW(read_pfm(run.out));
  }
  EXPECT_TRUE(temporaries(dir).empty());
}

TEST(AtomicOutput, AKilledRunNeverLeavesATruncatedImage) {
  // SIGKILL cannot be caught: whatever the moment, the output is the old image or the new whole
  // one, because the new one is written to a temporary file and renamed over it.
  ScratchDir dir;
  const auto out = dir / "image.pfm";
  write_image(out, Image(320, 200, Color(0.5f)));
  for (int attempt = 0; attempt < 6; ++attempt) {
    ChildProcess child({STAGE1_EXE, "--scene", source_path("assets/scenes/spheres.json").string(), "--spp", "1",
                        "--out", out.string()}, dir / "stdout.txt", dir / "stderr.txt");
    std::this_thread::sleep_for(std::chrono::milliseconds(15 * attempt));
    child.signal(SIGKILL);
    ASSERT_TRUE(child.wait_for(2000ms));
    const Image image = read_pfm(out);
    EXPECT_TRUE((image.width() == 320 && image.height() == 200) || (image.width() == 640 && image.height() == 400))
        << "attempt " << attempt;
  }
}

}  // namespace
}  // namespace rt
