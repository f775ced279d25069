// Inputs at the edges of float range and of what the formats allow, each found by trying to break
// the programs: refused in one line that names the file and quotes the value, never a crash, a
// NaN image, a hang or a silent clamp (label "reliability").
#include "03-acceleration/bvh.h"
#include "04-radiometry/lighting_scene.h"
#include "common/options.h"
#include "common/error.h"
#include "common/memory_limit.h"
#include "common/obj_loader.h"
#include "common/scene.h"

#include "reliability/child_process.h"
#include "reliability/stage_programs.h"
#include "support/test_support.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <limits>

namespace rt {
namespace {

using namespace std::chrono_literals;
using testing::error_message;
using testing::expect_one_line_error;
using testing::run_command;
using testing::ScratchDir;
using testing::source_path;
using testing::write_text;

using testing::kPrograms;
using testing::kMeshPrograms;
using testing::kEmitterPrograms;
constexpr const char* kCamera = R"("camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 30})";

std::string scene_with(const std::string& materials, const std::string& shapes, const std::string& camera = kCamera) {
  return "{" + camera + R"(, "materials": {)" + materials + R"(}, "shapes": [)" + shapes + "]}";
}

// `program` on `scene` (written to the scratch folder) into a tiny image.
testing::CommandResult render(const char* program, const ScratchDir& dir, const std::string& scene,
                              const std::string& flags = "") {
  write_text(dir / "scene.json", scene);
  return run_command(std::string(program) + " --scene " + (dir / "scene.json").string() + " --width 8 --height 6 --spp 2 " +
                         flags + " --out " + (dir / "out.pfm").string(),
                     dir);
}

// Found by trying: a sphere {center [3e38, 0, 0], radius 3e38} sent the SAH builder into int(NaN)
// and a SIGSEGV in stages 3-5; an emitter of radius 1e19 overflowed its area into NaN pixels.
TEST(FarGeometry, ShapesBeyondTheCoordinateLimitAreRefusedInOneLine) {
  ScratchDir dir;
  const std::string m = R"("m": {})";
  for (const char* program : kPrograms) {
    auto r = render(program, dir, scene_with(m, R"({"type": "sphere", "center": [3e38, 0, 0], "radius": 3e38, "material": "m"})"));
    expect_one_line_error(r, 1, "scene.json: /shapes/0/center/0: coordinate 3e+38 lies beyond +-1e18");
    // Each number within the limit, the shape's box not: centre 9e17 plus radius 2e17.
    r = render(program, dir, scene_with(m, R"({"type": "sphere", "center": [0, 9e17, 0], "radius": 2e17, "material": "m"})"));
    expect_one_line_error(r, 1, "/shapes/0: the shape reaches beyond +-1e18");
    EXPECT_FALSE(std::filesystem::exists(dir / "out.pfm")) << program;
  }
  write_text(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  for (const char* program : kMeshPrograms) {
    const auto r = render(program, dir,
                          scene_with(m, R"({"type": "mesh", "file": "tri.obj", "material": "m", "transform": {"scale": 3e38}})"));
    expect_one_line_error(r, 1, "/shapes/0: the placed mesh reaches beyond +-1e18");
  }
  for (const char* program : kEmitterPrograms) {
    const auto r = render(program, dir,
                          scene_with(R"("e": {"emission": [1, 1, 1]})",
                                     R"({"type": "sphere", "center": [0, 0, 0], "radius": 1e19, "material": "e"})"));
    expect_one_line_error(r, 1, "/shapes/0/radius: radius must be at most 1e18, got 1e+19");
  }
}

TEST(FarGeometry, TheLimitItselfIsAcceptedAndTheNextFloatIsNot) {
  const std::string m = R"("m": {})";
  // 1e18 as a float is 999999984306749440; the next float up is 1000000053026226176.
  EXPECT_NO_THROW(parse_scene(scene_with(m, R"({"type": "plane", "point": [0, 0, 999999984306749440], "normal": [0, 0, 1], "material": "m"})"), "s.json"));
  EXPECT_NE(error_message([&] {
              parse_scene(scene_with(m, R"({"type": "plane", "point": [0, 0, 1000000053026226176], "normal": [0, 0, 1], "material": "m"})"), "s.json");
            }).find("/shapes/0/point/2: coordinate 1000000053026226176 lies beyond +-1e18"),
            std::string::npos);
  EXPECT_NO_THROW(parse_scene(scene_with(m, R"({"type": "sphere", "center": [0, 0, 5e17], "radius": 4.9e17, "material": "m"})"), "s.json"));
}

TEST(FarGeometry, ACameraFarAwayIsToldSoNotThatItsUpIsParallel) {
  const std::string message = error_message([] {
    parse_scene(scene_with("", "", R"("camera": {"position": [1e38, 0, -5], "look_at": [0, 0, 0], "vfov": 30})"), "s.json");
  });
  EXPECT_NE(message.find("s.json: /camera/position/0: coordinate 1e+38 lies beyond +-1e18"), std::string::npos) << message;
  // A huge up vector is only a direction: normalized in double, it is not parallel to anything.
  EXPECT_NO_THROW(parse_scene(scene_with("", "", R"("camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 3e38, 0], "vfov": 30})"), "s.json"));
  EXPECT_NO_THROW(parse_scene(scene_with("", "", R"("camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 1e-40, 0], "vfov": 30})"), "s.json"));
}

// The builder itself must not crash whatever the boxes: int(NaN) there was the SIGSEGV.
TEST(FarGeometry, TheBvhBuildersSurviveBoxesThatOverflowOrHoldNaN) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<Aabb> boxes;
  for (int i = 0; i < 200; ++i) {
    Aabb box;
    box.expand(Vec3(float(i), 0.0f, 0.0f));
    box.expand(Vec3(float(i) + 1.0f, 1.0f, 1.0f));
    boxes.push_back(box);
  }
  boxes[3].hi.x = inf;                       // extent inf: every bin index 0 * inf or inf / inf
  boxes[7].lo = Vec3(-3e38f), boxes[7].hi = Vec3(3e38f);  // centroid finite, extent overflows
  boxes[11].lo.y = nan;
  boxes[12].hi = Vec3(nan);
  for (const SplitMethod split : {SplitMethod::median, SplitMethod::middle, SplitMethod::sah}) {
    const Bvh bvh = build_bvh(boxes, BvhBuildOptions{.split = split});
    std::vector<std::uint32_t> order(bvh.order.begin(), bvh.order.end());
    std::sort(order.begin(), order.end());
    for (std::uint32_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i) << split_method_name(split);
    EXPECT_EQ(order.size(), boxes.size());
  }
}

TEST(EmitterPower, APowerOrASumOfPowersBeyondFloatIsRefusedAtLoad) {
  ScratchDir dir;
  for (const char* program : kEmitterPrograms) {
    auto r = render(program, dir,
                    scene_with(R"("e": {"emission": [3e38, 3e38, 3e38]})",
                               R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "e"})"));
    expect_one_line_error(r, 1, "scene.json: /shapes/0: the emitted power (pi x radiance x area) overflows float");
    EXPECT_FALSE(std::filesystem::exists(dir / "out.pfm"));
  }
  // Each disk's power pi * pi * 2e37 = 2.0e38 is a float; their sum, 3.9e38, is not.
  const std::string disk = R"({"type": "disk", "center": [0, 0, 0], "normal": [0, 0, -1], "radius": 1, "material": "e"})";
  const std::string materials = R"("e": {"emission": [2e37, 2e37, 2e37]})";
  EXPECT_EQ(error_message([&] { const LightingScene one(parse_scene(scene_with(materials, disk), "one.json")); }), "");
  EXPECT_NE(error_message([&] { const LightingScene two(parse_scene(scene_with(materials, disk + ", " + disk), "two.json")); })
                .find("two.json: /shapes/1: the emitted power"),
            std::string::npos);
}

TEST(JsonText, ANulByteAndWhatFollowsItAreRefused) {
  const std::string scene = scene_with(R"("m": {})", "");
  EXPECT_NO_THROW(parse_scene(scene, "s.json"));
  EXPECT_EQ(error_message([&] { parse_scene(scene + std::string(1, '\0') + "garbage", "s.json"); }),
            "s.json: a NUL byte at offset " + std::to_string(scene.size()) + ": not a JSON text file");
  EXPECT_NE(error_message([&] { parse_scene(std::string(1, '\0'), "s.json"); }).find("a NUL byte at offset 0"), std::string::npos);
}

TEST(Seeds, EverySeedUpTo2To64Minus1IsTakenAndNothingBeyondIsClamped) {
  auto seed_of = [](const std::string& value) {
    return parse_scene(R"({"render": {"seed": )" + value + "}, " + kCamera + R"(, "materials": {}, "shapes": []})", "s.json")
        .render.seed;
  };
  EXPECT_EQ(seed_of("9223372036854775808"), std::uint64_t(1) << 63);  // was refused as -9223372036854775808
  EXPECT_EQ(seed_of("18446744073709551615"), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(seed_of("0"), 0u);
  EXPECT_NE(error_message([&] { seed_of("18446744073709551616"); }).find("/render/seed: expected an integer, got number 1.8446744073709552e+19"),
            std::string::npos);
  EXPECT_NE(error_message([&] { seed_of("-1"); }).find("/render/seed: must be in [0, 18446744073709551615], got -1"),
            std::string::npos);

  ScratchDir dir;
  const std::string base = std::string(STAGE1_EXE) + " --scene " + source_path("assets/scenes/spheres.json").string() +
                           " --width 4 --height 4 --spp 1 --out " + (dir / "x.pfm").string();
  EXPECT_EQ(run_command(base + " --seed 18446744073709551615", dir).exit_code, 0);
  EXPECT_EQ(run_command(base + " --seed 000018446744073709551615", dir).exit_code, 0);
  std::filesystem::remove(dir / "x.pfm");
  for (const char* seed : {"18446744073709551616", "99999999999999999999999", "-1", "1e3", "0x10", "", " 7"}) {
    expect_one_line_error(run_command(base + " --seed '" + seed + "'", dir), 2, "--seed");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.pfm")) << seed;
  }
}

// CLI11 reads a leading 0 as octal: "--spp 010" rendered 8 samples.
TEST(CommandLine, IntegersAreDecimalWhateverTheirLeadingZeros) {
  ScratchDir dir;
  const auto r = run_command(std::string(STAGE1_EXE) + " --scene " + source_path("assets/scenes/spheres.json").string() +
                                 " --width 04 --height 3 --spp 010 --out " + (dir / "x.pfm").string(),
                             dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(4x3, 10 spp)"), std::string::npos) << r.out;
  for (const auto& [flag, value] : {std::pair("--spp", "0x10"), std::pair("--width", "0b11"), std::pair("--spp", "1_0"),
                                    std::pair("--threads", "+2"), std::pair("--spp", "1048577")})
    expect_one_line_error(run_command(std::string(STAGE1_EXE) + " --scene " + source_path("assets/scenes/spheres.json").string() +
                                          " " + flag + " " + value + " --out " + (dir / "y.pfm").string(),
                                      dir),
                          2, std::string(flag) + ": " + value + ": ");
  EXPECT_FALSE(std::filesystem::exists(dir / "y.pfm"));
}

TEST(CommandLine, NanAndInfinityAreNotNumbersAFlagTakes) {
  ScratchDir dir;
  const std::string base = std::string(STAGE2_EXE) + " --scene " + source_path("assets/scenes/whitted.json").string() +
                           " --width 4 --height 4 --spp 1 --offset fixed --out " + (dir / "x.pfm").string();
  for (const char* epsilon : {"nan", "NaN", "inf", "-inf", "-0.001", "1e39", "0.5x"}) {
    expect_one_line_error(run_command(base + " --epsilon " + epsilon, dir), 2, "--epsilon");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.pfm")) << epsilon;
  }
  EXPECT_EQ(run_command(base + " --epsilon 0", dir).exit_code, 0);
  EXPECT_EQ(run_command(base + " --epsilon 1e-4", dir).exit_code, 0);
}

TEST(ObjIndices, EveryIndexIsCheckedAsWrittenAndQuotedSo) {
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  // tinyobjloader keeps indices in an int: 4294967299 wrapped to vertex 3, 2147483648 to -2147483644.
  EXPECT_EQ(error_message([&] { parse_obj(triangle + "f 1 2 4294967299\n", "m.obj"); }),
            "m.obj:4: vertex index 4294967299 is out of range (the file has 3 vertices)");
  EXPECT_EQ(error_message([&] { parse_obj(triangle + "f 1 2 2147483648\n", "m.obj"); }),
            "m.obj:4: vertex index 2147483648 is out of range (the file has 3 vertices)");
  EXPECT_EQ(error_message([&] { parse_obj(triangle + "f 1 2 99999999999999999999999\n", "m.obj"); }),
            "m.obj:4: vertex index 99999999999999999999999 is out of range (the file has 3 vertices)");
  EXPECT_EQ(error_message([&] { parse_obj(triangle + "f 1 2 -4\n", "m.obj"); }),
            "m.obj:4: vertex index -4 is out of range (3 vertices come before it)");
  // A normal index counting back too far was silently dropped (the triangle shaded flat).
  EXPECT_EQ(error_message([&] { parse_obj(triangle + "vn 0 0 1\nf 1//1 2//-2 3//1\n", "m.obj"); }),
            "m.obj:5: normal index -2 is out of range (1 normals come before it)");
  EXPECT_EQ(error_message([&] { parse_obj(triangle + "vt 0 0\nf 1/2 2/1 3/1\n", "m.obj"); }),
            "m.obj:5: texture index 2 is out of range (the file has 1 texture coordinates)");
  // The boundaries themselves load: the last vertex, counting forward and back.
  EXPECT_EQ(parse_obj(triangle + "f 1 2 3\n", "m.obj").triangles.size(), 1u);
  EXPECT_EQ(parse_obj(triangle + "f -3 -2 -1\n", "m.obj").triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(parse_obj(triangle + "vn 0 0 1\nf 1//-1 2//1 3//1\n", "m.obj").triangle_normals[0],
            (std::array<std::int32_t, 3>{0, 0, 0}));
  // OBJ lets a positive index point forward to a vertex defined later in the file.
  EXPECT_EQ(parse_obj("f 1 2 3\n" + triangle, "m.obj").triangles.size(), 1u);
}

TEST(ObjNumbers, TooSmallForFloatIsZeroTooLargeIsRefused) {
  // 1e-50 was called "not finite": it is a tiny number, 0 in float, as every OBJ reader takes it.
  const TriangleMesh mesh = parse_obj("v 0 0 1e-50\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj");
  EXPECT_EQ(mesh.positions[0].z, 0.0f);
  EXPECT_EQ(error_message([] { parse_obj("v 0 0 3.5e38\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj"); }),
            "m.obj:1: vertex needs three finite coordinates, got '3.5e38'");
  EXPECT_NO_THROW(parse_obj("v 0 0 3.4e38\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj"));
}

// Found by trying: a NUL byte in an OBJ vertex cut the message there (what() is a C string).
// Every message is made printable when its error is made, the NUL escaped with the rest of it.
TEST(Messages, ANulByteQuotedFromAFileIsEscapedNotTheEndOfTheMessage) {
  const char text[] = "v 0 0 0\nv 1 0\0x 0\nv 0 1 0\nf 1 2 3\n";
  const std::string obj(text, sizeof text - 1);
  EXPECT_EQ(error_message([&] { parse_obj(obj, "m.obj"); }),
            "m.obj:2: vertex needs three finite coordinates, got '0\\x00x'");
  EXPECT_STREQ(UsageError(std::string("a\0b\nc", 5)).what(), "a\\x00b\\nc");
}

TEST(Messages, AScenesSizeIsQuotedAsGivenWhenFloatLosesIt) {
  EXPECT_NE(error_message([] {
              parse_scene(scene_with(R"("m": {})", R"({"type": "sphere", "center": [0, 0, 0], "radius": 1e-50, "material": "m"})"), "s.json");
            }).find("/shapes/0/radius: radius must be positive, got 1e-50 (0 in float)"),
            std::string::npos);
  EXPECT_NE(error_message([] {
              parse_scene(scene_with(R"("m": {})", R"({"type": "sphere", "center": [0, 0, 0], "radius": -2.5, "material": "m"})"), "s.json");
            }).find("/shapes/0/radius: radius must be positive, got -2.5"),
            std::string::npos);
}

// A newline inside a JSON string (a key, a file name) was echoed raw: a two-line error.
TEST(Messages, ControlCharactersAreEscapedSoEveryErrorIsOneLine) {
  ScratchDir dir;
  const auto r = render(STAGE2_EXE, dir,
                        scene_with(R"("m": {})", R"({"type": "mesh", "file": "no\nsuch\tmesh.obj", "material": "m"})"));
  expect_one_line_error(r, 1, "no\\nsuch\\tmesh.obj: cannot open mesh file");
  const auto r2 = render(STAGE1_EXE, dir, scene_with(R"("m": {})", R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "gold\u0007\n"})"));
  expect_one_line_error(r2, 1, "unknown material 'gold\\x07\\n'");
  const auto r3 = render(STAGE1_EXE, dir, scene_with(R"("m\nx": {"albedo": [2, 0, 0]})", ""));
  expect_one_line_error(r3, 1, "/materials/m\\nx/albedo/0");
  EXPECT_EQ(printable("a\nb\r\tc\x01\x7f" "d\\e"), "a\\nb\\r\\tc\\x01\\x7fd\\e");
}

TEST(HostileFiles, KernelInterfacesFifosAndFoldersAreRefusedWithoutBlocking) {
  ScratchDir dir;
  // /proc files claim to be regular files of size 0; /proc/kmsg blocked the read for ever.
  for (const char* kernel_file : {"/proc/self/status", "/proc/version", "/sys/kernel/mm/transparent_hugepage/enabled"}) {
    if (!std::filesystem::exists(kernel_file)) continue;
    EXPECT_EQ(error_message([&] { load_obj(kernel_file); }),
              std::string(kernel_file) + ": cannot read mesh file: a kernel interface under /proc or /sys, not a file");
  }
  const std::string fifo = (dir / "scene.fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  testing::ChildProcess child({STAGE1_EXE, "--scene", fifo, "--out", (dir / "x.png").string()}, dir / "stdout.txt",
                              dir / "stderr.txt");
  const std::optional<int> status = child.wait_for(5000ms);
  ASSERT_TRUE(status) << "reading a FIFO with no writer blocked";
  EXPECT_EQ(WEXITSTATUS(*status), 1);
  EXPECT_NE(testing::read_text(dir / "stderr.txt").find("scene.fifo: cannot read scene file: not a regular file"),
            std::string::npos);
}

TEST(Memory, ASceneIsRefusedBeforeBuildingWithTheFigures) {
  const MemoryLimit machine{std::uint64_t(24) << 30, MemoryLimit::Source::machine};
  // 10^5 placed bunnies of 69,451 triangles: the 13 MB scene that asked for 800 GB.
  EXPECT_EQ(error_message([&] { check_scene_fits("bunnies.json", 6945100000ull, {0.0, "the image"}, machine); }),
            "bunnies.json: the render needs about 1.6 TiB of memory (6945100000 triangles at 256 bytes each with the "
            "acceleration structure, and the image), and this machine has 24.0 GiB");
  EXPECT_NO_THROW(check_scene_fits("one.json", 69451, {0.0, "the image"}, machine));
  // The boundary: exactly the limit fits, a byte more does not.
  const MemoryLimit tight{1000 * kBytesPerTriangle + 24, MemoryLimit::Source::address_space};
  EXPECT_NO_THROW(check_scene_fits("s.json", 1000, {24.0, "the image"}, tight));
  EXPECT_NE(error_message([&] { check_scene_fits("s.json", 1000, {25.0, "the image"}, tight); }).find("(ulimit -v)"),
            std::string::npos);
  EXPECT_EQ(MemoryLimit({std::uint64_t(3) << 30, MemoryLimit::Source::cgroup}).describe(),
            "its cgroup allows 3.0 GiB (memory.max)");
  EXPECT_EQ(MemoryLimit({std::uint64_t(5) << 20, MemoryLimit::Source::data_segment}).describe(),
            "this process may use 5.0 MiB (ulimit -d)");

  ScratchDir dir;
  std::string shapes;
  for (int i = 0; i < 100000; ++i)
    shapes += std::string(i ? ", " : "") + R"({"type": "mesh", "file": ")" + source_path("assets/meshes/stanford-bunny.obj").string() +
              R"(", "material": "m", "transform": {"translate": [)" + std::to_string(i) + ", 0, 0]}}";
  write_text(dir / "bunnies.json", scene_with(R"("m": {})", shapes));
  const auto r = run_command(std::string(STAGE3_EXE) + " --scene " + (dir / "bunnies.json").string() + " --out " +
                                 (dir / "x.png").string(),
                             dir);
  expect_one_line_error(r, 1, "bunnies.json: the render needs about 1.6 TiB of memory (6945100000 triangles");
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(Memory, TheLimitIsTheTightestOfMachineUlimitAndCgroup) {
  ScratchDir dir;
  // A v2 hierarchy: the job's group allows 2 GiB, its parent 1 GiB, the grandparent has no limit.
  std::filesystem::create_directories(dir / "cg/batch/job");
  write_text(dir / "cg/batch/job/memory.max", "2147483648\n");
  write_text(dir / "cg/batch/memory.max", "1073741824\n");
  write_text(dir / "self-cgroup", "0::/batch/job\n");
  EXPECT_EQ(cgroup_memory_limit((dir / "self-cgroup").string(), (dir / "cg").string()), std::uint64_t(1) << 30);
  write_text(dir / "cg/batch/memory.max", "max\n");
  EXPECT_EQ(cgroup_memory_limit((dir / "self-cgroup").string(), (dir / "cg").string()), std::uint64_t(2) << 30);
  // v1: the memory controller's own line among the others.
  std::filesystem::create_directories(dir / "cg/memory/docker/abc");
  write_text(dir / "cg/memory/docker/abc/memory.limit_in_bytes", "536870912\n");
  write_text(dir / "self-cgroup", "12:cpu,cpuacct:/docker/abc\n4:memory:/docker/abc\n");
  EXPECT_EQ(cgroup_memory_limit((dir / "self-cgroup").string(), (dir / "cg").string()), std::uint64_t(512) << 20);
  write_text(dir / "self-cgroup", "garbage\n");
  EXPECT_EQ(cgroup_memory_limit((dir / "self-cgroup").string(), (dir / "cg").string()),
            std::numeric_limits<std::uint64_t>::max());
  EXPECT_LE(memory_limit().bytes, physical_memory_bytes());
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;  // its shadow memory needs terabytes of address space
#else
constexpr bool kAddressSanitizer = false;
#endif

TEST(Memory, AnAddressSpaceLimitIsHonouredWithTheFigures) {
  if (kAddressSanitizer) GTEST_SKIP() << "ulimit -v and AddressSanitizer cannot be combined";
  ScratchDir dir;
  // 1.1 M triangles at 256 bytes are 272 MiB, more than 200 MB of address space.
  const std::string limited = "ulimit -v 200000; ";
  auto r = run_command(limited + STAGE3_EXE + " --scene " + source_path("assets/scenes/bunnies.json").string() + " --out " +
                           (dir / "x.png").string(),
                       dir);
  expect_one_line_error(r, 1, "bunnies.json: the render needs about");
  EXPECT_NE(r.err.find("(1111216 triangles at 256 bytes each"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("this process may use 195.3 MiB (ulimit -v)"), std::string::npos) << r.err;
  r = run_command(limited + STAGE1_EXE + " --scene " + source_path("assets/scenes/spheres.json").string() +
                      " --width 8000 --height 8000 --out " + (dir / "x.png").string(),
                  dir);
  expect_one_line_error(r, 1, "x.png: a 8000x8000 image needs 4.8 GiB of memory");
  EXPECT_NE(r.err.find("(ulimit -v)"), std::string::npos) << r.err;
  // Found by trying: stage 6 counted every method at the image's bytes a pixel, and light tracing,
  // BDPT and SPPM failed after seconds of work with no figure. Here the image alone fits (110 MiB),
  // light tracing's splats do not (198 MiB), nor do SPPM's 1.1 * 10^6 photons a pass (201 MiB).
  const std::string cornell = STAGE6_EXE + std::string(" --scene ") + source_path("assets/scenes/cornell-box.json").string();
  r = run_command(limited + cornell + " --method lt --width 1200 --height 1200 --out " + (dir / "x.png").string(), dir);
  expect_one_line_error(r, 1, "the image with lt's splats, 144 bytes a pixel), and this process may use 195.3 MiB");
  r = run_command(limited + cornell + " --method pt --width 1200 --height 1200 --spp 1 --out " + (dir / "pt.png").string(),
                  dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;  // the path tracer needs the image alone
  r = run_command(limited + cornell + " --method sppm --width 64 --height 64 --photons 1100000 --out " +
                      (dir / "y.png").string(), dir);
  expect_one_line_error(r, 1, "and 1100000 photons a pass at 192 bytes each), and this process may use 195.3 MiB");
  // Found by trying: a valid 8192^2 PNG under ulimit -v 1G was "broken image (outofmem)". Its size
  // is checked against the memory first (the header alone is enough: no pixel is decoded).
  std::string png = "\x89PNG\r\n\x1a\n" + std::string("\0\0\0\x0dIHDR\0\0\x20\0\0\0\x20\0\x08\x02\0\0\0", 21);
  testing::write_text(dir / "big.png", png + std::string(64, '\0'));
  testing::write_text(dir / "textured.json", R"({"camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "vfov": 30},
    "materials": {"m": {"albedo": {"file": "big.png"}}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
  r = run_command(limited + STAGE4_EXE + " --scene " + (dir / "textured.json").string() + " --out " +
                      (dir / "z.png").string(), dir);
  expect_one_line_error(r, 1, "big.png: a 8192x8192 texture needs 1.5 GiB of memory to decode, and this process may use");
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "y.png"));
}

}  // namespace
}  // namespace rt
