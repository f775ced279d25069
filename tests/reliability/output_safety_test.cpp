// No run loses a file: an output never overwrites an input, a stop before the first sample leaves
// the old image alone, a name too long is refused before the render, a planted link is never
// followed, no output ever holds a non-finite value, and merge checks its batches in O(n log n)
// (label "reliability").
#include "common/program.h"
#include "common/batch_merge.h"
#include "common/error.h"
#include "common/file_io.h"
#include "common/image_io.h"
#include "common/interrupt.h"
#include "common/random.h"
#include "common/sample_batch.h"

#include "reliability/child_process.h"
#include "reliability/stage_programs.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cmath>
#include <thread>

namespace rt {
namespace {

using namespace std::chrono_literals;
using testing::error_message;
using testing::expect_one_line_error;
using testing::read_text;
using testing::run_command;
using testing::ScratchDir;
using testing::source_path;
using testing::write_text;
using testing::ChildProcess;

using testing::kPrograms;
using testing::kMeshPrograms;

// A scene every stage renders: one diffuse sphere under a point light.
constexpr const char* kSphere = R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 30},
  "materials": {"m": {"albedo": [0.5, 0.5, 0.5]}},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
  "lights": [{"type": "point", "position": [0, 3, -3], "intensity": [10, 10, 10]}]})";

// Found by trying: --out equal to --scene overwrote the scene with the render.
TEST(OutputsSpareInputs, TheSceneIsNeverItsOwnOutput) {
  ScratchDir dir;
  std::filesystem::create_directories(dir / "sub");
  write_text(dir / "scene.json", kSphere);
  for (const char* program : kPrograms)
    for (const std::string& out : {(dir / "scene.json").string(), (dir / "sub/../scene.json").string()}) {
      const auto r = run_command(std::string(program) + " --scene " + (dir / "scene.json").string() + " --out " + out, dir);
      expect_one_line_error(r, 2, "would overwrite the input " + (dir / "scene.json").string());
      EXPECT_EQ(read_text(dir / "scene.json"), kSphere) << program;
    }
}

TEST(OutputsSpareInputs, NeitherIsAMeshNorAnImageOfABatch) {
  ScratchDir dir;
  // A mesh whose name a render's output could take: the image itself, or a batch's sum image.
  const std::string obj = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";
  for (const char* mesh : {"mesh.pfm", "part.sum.pfm"}) {
    write_text(dir / mesh, obj);
    write_text(dir / "scene.json", std::string(R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 30},
      "materials": {"m": {}}, "shapes": [{"type": "mesh", "file": ")") + mesh + R"(", "material": "m"}]})");
    const std::string out = std::string(mesh) == "mesh.pfm" ? "mesh.pfm" : "part.json";
    for (const char* program : kMeshPrograms) {
      // Stage 6's default method and stage 7 write no batch at all (Stage6Cli.WhatAMethodCannotRenderIsOneLine).
      if (out == "part.json" && (std::string(program) == STAGE6_EXE || std::string(program) == STAGE7_EXE)) continue;
      const auto r = run_command(std::string(program) + " --scene " + (dir / "scene.json").string() + " --spp 1 --out " +
                                     (dir / out).string(),
                                 dir);
      expect_one_line_error(r, 2, "would overwrite the input " + (dir / mesh).string());
      EXPECT_EQ(read_text(dir / mesh), obj) << program;
    }
  }
}

// Found by trying: --out or --sample-map naming a scene's texture or environment map replaced it.
// Every image a scene reads is an input.
TEST(OutputsSpareInputs, NeitherATextureNorTheEnvironmentMap) {
  ScratchDir dir;
  write_image(dir / "grid.png", Image(4, 4, Color(0.5f)));
  write_image(dir / "sky.pfm", Image(8, 4, Color(0.25f)));
  write_text(dir / "scene.json", R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 30},
    "environment": {"file": "sky.pfm"}, "materials": {"m": {"albedo": {"file": "grid.png"}}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
  const std::string grid = read_text(dir / "grid.png"), sky = read_text(dir / "sky.pfm");
  const std::string scene = " --scene " + (dir / "scene.json").string() + " --width 8 --height 6 --spp 1 ";
  for (const char* program : kPrograms)
    for (const char* input : {"grid.png", "sky.pfm"}) {
      const auto r = run_command(program + scene + "--out " + (dir / input).string(), dir);
      expect_one_line_error(r, 2, "--out " + (dir / input).string() + " would overwrite the input");
    }
  for (const std::string& map : {(dir / "grid.png").string(), (dir / "sub/../grid.png").string()}) {
    std::filesystem::create_directories(dir / "sub");
    const auto r = run_command(STAGE5_EXE + scene + "--adaptive 0.1 --out " + (dir / "o.pfm").string() +
                                   " --sample-map " + map, dir);
    expect_one_line_error(r, 2, "--sample-map " + map + " would overwrite the input");
  }
  EXPECT_EQ(read_text(dir / "grid.png"), grid);
  EXPECT_EQ(read_text(dir / "sky.pfm"), sky);
}

// Found by trying: --sample-map naming --out's file lost the map, and a --sample-map in a missing
// folder was refused only after the whole render, with the image then not written either. Every
// output is checked before anything renders.
TEST(OutputsAreCheckedFirst, TwoOutputsAreNeverOneFileAndAMissingFolderStopsTheRunAtOnce) {
  ScratchDir dir;
  write_text(dir / "scene.json", kSphere);
  const std::string run = std::string(STAGE5_EXE) + " --scene " + (dir / "scene.json").string() + " --adaptive 0.1 ";
  const std::string out = (dir / "o.png").string();
  std::filesystem::create_directories(dir / "sub");
  for (const std::string& map : {out, (dir / "." / "o.png").string(), (dir / "sub/../o.png").string()}) {
    const auto r = run_command(run + "--out " + out + " --sample-map " + map, dir);
    expect_one_line_error(r, 2, "--sample-map " + map + " is the file --out writes too");
    EXPECT_FALSE(std::filesystem::exists(dir / "o.png"));
  }
  // A render of 6.5 * 10^10 samples: a check after it would not be reached within the test's time.
  const auto missing = run_command(run + "--width 4000 --height 4000 --spp 4096 --out " + out + " --sample-map " +
                                       (dir / "none/map.png").string(), dir);
  expect_one_line_error(missing, 1, "does not exist");
  EXPECT_FALSE(std::filesystem::exists(dir / "o.png"));
}

// Found by trying: merge --out naming one of its inputs destroyed it.
TEST(OutputsSpareInputs, MergeNeverWritesOverWhatItReads) {
  ScratchDir dir;
  write_text(dir / "scene.json", kSphere);
  const std::string render = std::string(STAGE1_EXE) + " --scene " + (dir / "scene.json").string() + " --width 8 --height 6 ";
  ASSERT_EQ(run_command(render + "--sample-range 0:2 --out " + (dir / "a.json").string(), dir).exit_code, 0);
  ASSERT_EQ(run_command(render + "--sample-range 2:4 --out " + (dir / "b.json").string(), dir).exit_code, 0);
  ASSERT_EQ(run_command(render + "--spp 4 --out " + (dir / "ref.pfm").string(), dir).exit_code, 0);
  const std::string a = read_text(dir / "a.json"), a_sum = read_text(dir / "a.sum.pfm"), ref = read_text(dir / "ref.pfm");
  const std::string merge = std::string(MERGE_EXE) + " --reference " + (dir / "ref.pfm").string() + " ";
  const std::string inputs = " " + (dir / "a.json").string() + " " + (dir / "b.json").string();
  for (const char* out : {"a.json", "a.sum.pfm", "b.count.pfm", "ref.pfm"}) {
    const auto r = run_command(merge + "--out " + (dir / out).string() + inputs, dir);
    expect_one_line_error(r, 2, "would overwrite the input");
  }
  EXPECT_EQ(read_text(dir / "a.json"), a);
  EXPECT_EQ(read_text(dir / "a.sum.pfm"), a_sum);
  EXPECT_EQ(read_text(dir / "ref.pfm"), ref);
  // Found by trying: a --reference path over 96 characters was cut short in merge's report.
  const std::string long_name = std::string(120, 'r') + ".pfm";
  std::filesystem::copy_file(dir / "ref.pfm", dir / long_name);
  const auto r = run_command(std::string(MERGE_EXE) + " --reference " + (dir / long_name).string() + " --out " +
                                 (dir / "m.pfm").string() + inputs,
                             dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("against " + (dir / long_name).string() + "; wrote"), std::string::npos) << r.out;
}

// Found by trying: Ctrl-C while the scene was loading replaced a good image with a black one.
TEST(StopBeforeTheFirstSample, LeavesAnExistingImageAsItWas) {
  ScratchDir dir;
  const auto out = dir / "image.pfm";
  write_image(out, Image(3, 2, Color(0.5f)));
  const std::string before = read_text(out);
  CommonOptions options;
  options.out = out.string();
  RenderSettings settings;
  settings.width = 3, settings.height = 2, settings.spp = 4;
  const SceneDescription description;
  request_interrupt(SIGINT);
  const SampleSums none(3, 2);
  try {
    write_render("stage1", options, "scene.json", description, settings, PixelMeaning::radiance, none, 0.1);
    ADD_FAILURE() << "no Interrupted";
  } catch (const Interrupted& stop) {
    EXPECT_EQ(stop.signal_number, SIGINT);
    EXPECT_EQ(stop.message, "interrupted by Ctrl-C before any sample finished: nothing written");
  }
  clear_interrupt();
  EXPECT_EQ(read_text(out), before);

  // End to end: stage 3 loads and builds 1.1 M triangles (a second or more) before its first
  // sample; SIGINT during that writes nothing. A SIGINT that comes before the program has set up
  // its handler (a slow start on a loaded machine) ends it the default way, which is not what this
  // checks: then it is sent again, later.
  std::optional<int> status;
  for (const auto delay : {150ms, 500ms, 1500ms}) {
    ChildProcess child({STAGE3_EXE, "--scene", source_path("assets/scenes/bunnies.json").string(), "--out", out.string()},
                       dir / "stdout.txt", dir / "stderr.txt");
    std::this_thread::sleep_for(delay);
    child.signal(SIGINT);
    status = child.wait_for(20000ms);
    ASSERT_TRUE(status);
    if (!(WIFSIGNALED(*status) && WTERMSIG(*status) == SIGINT)) break;
  }
  ASSERT_TRUE(WIFEXITED(*status)) << "the program never got as far as its Ctrl-C handler";
  EXPECT_EQ(WEXITSTATUS(*status), 128 + SIGINT);
  EXPECT_NE(read_text(dir / "stderr.txt").find("stage3: interrupted by Ctrl-C before any sample finished: nothing written"),
            std::string::npos)
      << read_text(dir / "stderr.txt");
  EXPECT_EQ(read_text(out), before);
}

// Found by trying: a legal output name of 250 bytes was refused only after the render, because the
// temporary name beside it ("NAME.tmp<pid>") was longer than NAME_MAX.
TEST(LongOutputNames, TheLongestLegalNameIsWrittenAndALongerOneRefusedFirst) {
  ScratchDir dir;
  write_text(dir / "scene.json", kSphere);
  const long name_max = ::pathconf(dir.path().c_str(), _PC_NAME_MAX);
  ASSERT_GT(name_max, 16);
  const std::string longest = std::string(size_t(name_max) - 4, 'n') + ".pfm";
  const std::string render = std::string(STAGE1_EXE) + " --scene " + (dir / "scene.json").string() + " --width 8 --height 6 ";
  auto r = run_command(render + "--out " + (dir / longest).string(), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_pfm(dir / longest).width(), 8);
  const std::string too_long = "n" + longest;
  r = run_command(render + "--spp 1000000 --out " + (dir / too_long).string(), dir);  // minutes, if it rendered
  expect_one_line_error(r, 1, "its name is " + std::to_string(name_max + 1) + " bytes long, and this file system allows " +
                                  std::to_string(name_max));
  // A batch writes NAME.sum.pfm and NAME.count.pfm beside NAME.json: their names count too.
  const std::string batch = std::string(size_t(name_max) - 6, 'b') + ".json";  // fits; its .count.pfm does not
  r = run_command(render + "--spp 1000000 --out " + (dir / batch).string(), dir);
  expect_one_line_error(r, 1, ".sum.pfm': its name is");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator()), 4)
      << "scene.json, the written image and the two outputs of stdout and stderr only";
}

// The temporary file used to be OUT.tmp<pid>, opened following links: a link planted under that
// name made the program overwrite whatever it pointed to.
TEST(TemporaryFiles, APlantedLinkIsNeverFollowed) {
  ScratchDir dir;
  write_text(dir / "victim.txt", "precious");
  const auto out = dir / "out.pfm";
  std::filesystem::create_symlink(dir / "victim.txt", dir / ("out.pfm.tmp" + std::to_string(::getpid())));
  write_image(out, Image(2, 2, Color(0.25f)));
  EXPECT_EQ(read_text(dir / "victim.txt"), "precious");
  EXPECT_EQ(read_pfm(out).at(1, 1), Color(0.25f));
  // An output that is itself a link is replaced by the new file; what it pointed to is kept.
  std::filesystem::create_symlink(dir / "victim.txt", dir / "linked.pfm");
  write_image(dir / "linked.pfm", Image(1, 1));
  EXPECT_EQ(read_text(dir / "victim.txt"), "precious");
  EXPECT_FALSE(std::filesystem::is_symlink(dir / "linked.pfm"));
  // Created as 0666 less the umask, like any file the user writes, and nothing left behind.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(std::filesystem::status(out).permissions(), std::filesystem::perms(0666 & ~mask));
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 4);  // victim, the planted link, out.pfm, linked.pfm
}

TEST(NonFiniteValues, ARenderWritesThemBlackAndSaysSo) {
  ScratchDir dir;
  CommonOptions options;
  options.out = (dir / "nan.pfm").string();
  RenderSettings settings;
  settings.width = 2, settings.height = 1, settings.spp = 1;
  SampleSums sums(2, 1);
  sums.set(0, 0, Color(std::nanf(""), 1.0f, 1.0f), 1);
  sums.set(1, 0, Color(0.5f), 1);
  ::testing::internal::CaptureStderr();
  write_render("stage4", options, "scene.json", SceneDescription{}, settings, PixelMeaning::radiance, sums, 0.1);
  const std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(said, "stage4: warning: 1 pixels had a radiance that is not finite and are written black\n");
  const Image image = read_pfm(dir / "nan.pfm");
  EXPECT_EQ(image.at(0, 0), Color(0.0f));
  EXPECT_EQ(image.at(1, 0), Color(0.5f));
}

// Found by trying: --exr-half wrote +inf above 65504, from the stage programs and from merge.
TEST(NonFiniteValues, AHalfExrClampsWhatItCannotHoldAndSaysSo) {
  ScratchDir dir;
  CommonOptions options;
  options.out = (dir / "bright.exr").string();
  options.encoding.exr_half = true;
  RenderSettings settings;
  settings.width = 2, settings.height = 1, settings.spp = 1;
  SampleSums sums(2, 1);
  sums.set(0, 0, Color(1e6f, 0.5f, 70000.0f), 1);
  sums.set(1, 0, Color(65504.0f), 1);
  ::testing::internal::CaptureStderr();
  write_render("stage4", options, "scene.json", SceneDescription{}, settings, PixelMeaning::radiance, sums, 0.1);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "stage4: warning: 2 values lie beyond 65504, the largest half float, and are written as 65504 (write "
            "32-bit floats without --exr-half to keep them)\n");
  const Image image = decode_exr(read_text(dir / "bright.exr"), "bright.exr");
  EXPECT_EQ(image.at(0, 0), Color(65504.0f, 0.5f, 65504.0f));
  EXPECT_EQ(image.at(1, 0), Color(65504.0f));
  // merge writes through the same function: its half EXR of a bright render is finite too.
  write_text(dir / "scene.json", R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 30},
    "materials": {"m": {"albedo": [0.5, 0.5, 0.5]}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
    "lights": [{"type": "point", "position": [0, 0, -3], "intensity": [1e9, 1e9, 1e9]}]})");
  const std::string render = std::string(STAGE1_EXE) + " --scene " + (dir / "scene.json").string() + " --width 8 --height 6 ";
  ASSERT_EQ(run_command(render + "--sample-range 0:1 --out " + (dir / "a.json").string(), dir).exit_code, 0);
  const auto merged = run_command(std::string(MERGE_EXE) + " --exr-half --out " + (dir / "m.exr").string() + " " +
                                      (dir / "a.json").string(), dir);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.err.find("merge: warning: "), std::string::npos) << merged.err;
  const Image merged_image = decode_exr(read_text(dir / "m.exr"), "m.exr");
  for (const Color& c : merged_image.pixels()) EXPECT_TRUE(is_finite(c) && max_component(c) <= 65504.0f);
}

// Sample batches whose pixel sums are each a float but whose total is not.
TEST(NonFiniteValues, MergeRefusesSumsThatOverflowFloat) {
  ScratchDir dir;
  std::vector<SampleBatch> batches;
  const char* const names[] = {"b0.json", "b1.json"};  // not "b" + to_string(k): GCC 12's false -Wstringop-overflow
  for (int k = 0; k < 2; ++k) {
    SampleBatch b;
    b.file = dir / names[k];
    b.identity = {"stage5", "scene.json", "0123", "", 2, 1, 7};
    b.window = {0, 0, 2, 1};
    b.pieces = {{{0, 0, 2, 1}, {k, k + 1}}};
    b.sums = SampleSums(2, 1);
    b.sums.set(0, 0, Color(0.5f), 1);
    b.sums.set(1, 0, Color(3.0e38f), 1);
    write_sample_batch(b);
    batches.push_back(read_sample_batch(b.file));
  }
  EXPECT_EQ(error_message([&] { merge_batches(batches, {}); }),
            "pixel (1, 0): the batches' sums add up to more than float's range (3.4e38): the merged render would hold "
            "infinities");
  batches.pop_back();
  EXPECT_EQ(error_message([&] { merge_batches(batches, {.spp = 1}); }), "");
}

// The overlap check compared every pair of pieces: 59 s for 10^5, and a 58 MB description of
// 10^6 pieces never finished. Here 10^6 pieces (a 1000 x 1000 image, one piece per pixel) would
// take hours that way and so hit ctest's time limit; the sweep takes a second.
TEST(BatchPieces, AMillionPiecesAreCheckedForOverlapInLinearTime) {
  std::vector<BatchPiece> pieces;
  for (int y = 0; y < 1000; ++y)
    for (int x = 0; x < 1000; ++x) pieces.push_back({{x, y, x + 1, y + 1}, {0, 16}});
  EXPECT_FALSE(first_overlap(pieces));
  pieces.push_back({{500, 400, 501, 401}, {15, 17}});  // shares sample 15 of one pixel
  const auto overlap = first_overlap(pieces);
  ASSERT_TRUE(overlap);
  EXPECT_EQ(overlap->first, pieces.size() - 1);
  EXPECT_EQ(overlap->second, size_t(400 * 1000 + 500));
  pieces.back().samples = {16, 17};  // touching, not sharing
  EXPECT_FALSE(first_overlap(pieces));
}

// Found by the merge fuzzer's input space: two pixels at opposite corners of a 2^20 x 2^20 image
// would have asked for a per-pixel table of 2^40 entries.
TEST(BatchPieces, FewPiecesFarApartNeedMemoryOnlyForTheirPixels) {
  const int far = (1 << 20) - 1;
  std::vector<BatchPiece> pieces = {{{0, 0, 1, 1}, {0, 4}}, {{far, far, far + 1, far + 1}, {0, 4}}};
  EXPECT_FALSE(first_overlap(pieces));
  pieces.push_back({{far - 1, far, far + 1, far + 1}, {3, 5}});
  const auto overlap = first_overlap(pieces);
  ASSERT_TRUE(overlap);
  EXPECT_EQ(overlap->first, 2u);
  EXPECT_EQ(overlap->second, 1u);
}

TEST(BatchPieces, TheSweepFindsExactlyTheOverlapsEveryPairWould) {
  Rng rng(11, 0, 0);
  auto number = [&](int n) { return std::min(n - 1, int(rng.uniform() * float(n))); };
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<BatchPiece> pieces;
    const int count = 1 + number(6);
    for (int i = 0; i < count; ++i) {
      const int x0 = number(6), y0 = number(6), s0 = number(6);
      pieces.push_back({{x0, y0, x0 + 1 + number(3), y0 + 1 + number(3)}, {s0, s0 + 1 + number(3)}});
    }
    bool any = false;
    for (size_t i = 0; i < pieces.size(); ++i)
      for (size_t j = 0; j < i; ++j) {
        const BatchPiece both = shared_part(pieces[i], pieces[j]);
        any = any || (!both.pixels.empty() && both.samples.count() > 0);
      }
    const auto found = first_overlap(pieces);
    ASSERT_EQ(bool(found), any) << "trial " << trial;
    if (found) {
      ASSERT_LT(found->second, found->first);
      const BatchPiece both = shared_part(pieces[found->first], pieces[found->second]);
      EXPECT_TRUE(!both.pixels.empty() && both.samples.count() > 0) << "trial " << trial;
    }
  }
}

}  // namespace
}  // namespace rt
