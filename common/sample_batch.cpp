#include "common/sample_batch.h"

#include "common/error.h"
#include "common/file_io.h"
#include "common/hash.h"
#include "common/image_io.h"
#include "common/scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace fs = std::filesystem;
using nlohmann::json;

namespace rt {
namespace {

constexpr const char* kFormat = "rt sample batch 1";
// A description is a page of JSON (a merged batch lists one piece per tile).
constexpr std::uintmax_t kMaxDescriptionBytes = std::uintmax_t(64) << 20;
// Counts are stored as floats, exact integers up to 2^24.
constexpr float kMaxStoredCount = float(1 << 24);

fs::path with_suffix(const fs::path& json_path, const char* suffix) {
  fs::path p = json_path;
  p.replace_extension();
  p += suffix;
  return p;
}

json rect_to_json(const PixelRect& r) { return {{"x", {r.x0, r.x1}}, {"y", {r.y0, r.y1}}}; }

std::string fingerprint(const std::vector<char>& bytes) { return Fnv1a64().add(bytes.data(), bytes.size()).hex(); }

// Reading: every problem becomes InputError "FILE: problem".
class DescriptionReader {
 public:
  explicit DescriptionReader(const fs::path& file) : file_(file.string()) {}

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_ + ": " + problem); }

  const json& field(const json& object, const char* key) const {
    if (!object.is_object() || !object.contains(key)) fail(std::string("missing \"") + key + "\"");
    return object.at(key);
  }
  std::string text(const json& object, const char* key) const {
    const json& v = field(object, key);
    if (!v.is_string()) fail(std::string("\"") + key + "\" is not a string");
    return v.get<std::string>();
  }
  std::int64_t integer(const json& object, const char* key, std::int64_t lo, std::int64_t hi) const {
    const json& v = field(object, key);
    if (!v.is_number_integer()) fail(std::string("\"") + key + "\" is not an integer");
    const std::int64_t n = v.get<std::int64_t>();
    if (n < lo || n > hi)
      fail(std::string("\"") + key + "\" is " + std::to_string(n) + ", outside [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    return n;
  }
  // [a, b) with 0 <= a < b <= hi; `label` names it in messages ("window.x").
  std::pair<int, int> pair(const json& object, const char* key, int hi, const std::string& label) const {
    const json& v = field(object, key);
    if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() || !v[1].is_number_integer())
      fail("\"" + label + "\" is not a pair of integers");
    const std::int64_t a = v[0].get<std::int64_t>(), b = v[1].get<std::int64_t>();
    if (a < 0 || b > hi || a >= b)
      fail("\"" + label + "\" is " + std::to_string(a) + ":" + std::to_string(b) +
           ", not a non-empty range within 0:" + std::to_string(hi));
    return {int(a), int(b)};
  }
  PixelRect rect(const json& object, const char* key, int width, int height) const {
    const json& r = field(object, key);
    const auto [x0, x1] = pair(r, "x", width, std::string(key) + ".x");
    const auto [y0, y1] = pair(r, "y", height, std::string(key) + ".y");
    return {x0, y0, x1, y1};
  }

 private:
  std::string file_;
};

}  // namespace

std::string scene_fingerprint(const fs::path& scene_file, const SceneDescription& scene) {
  Fnv1a64 hash;
  hash.add(read_input_file(scene_file, "scene file", kMaxSceneFileBytes));
  auto add_all = [&](const auto& values) { hash.add(values.data(), values.size() * sizeof(values[0])); };
  for (const Shape& shape : scene.shapes)
    if (const Mesh* mesh = std::get_if<Mesh>(&shape.geometry)) {
      add_all(mesh->mesh->positions);
      add_all(mesh->mesh->normals);
      add_all(mesh->mesh->triangles);
      add_all(mesh->mesh->triangle_normals);
      add_all(mesh->mesh->uvs);
      add_all(mesh->mesh->triangle_uvs);
    }
  // The images the scene file names: a texture or an environment changed on disk changes the render.
  for (const Material& material : scene.materials)
    for (const auto* texture : {material.albedo_texture.get(), material.specular_texture.get()})
      if (texture) add_all(texture->texels->pixels());
  if (scene.environment && scene.environment->image) add_all(scene.environment->image->pixels());
  return hash.hex();
}

fs::path batch_sum_path(const fs::path& json_path) { return with_suffix(json_path, ".sum.pfm"); }
fs::path batch_count_path(const fs::path& json_path) { return with_suffix(json_path, ".count.pfm"); }
fs::path written_location(const fs::path& json_path) {
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(fs::absolute(json_path, ec), ec);
  return ec ? json_path : real;
}
bool is_batch_path(const fs::path& path) { return path.extension() == ".json"; }

std::string format_rect(const PixelRect& r) {
  return std::to_string(r.x0) + ":" + std::to_string(r.x1) + "," + std::to_string(r.y0) + ":" + std::to_string(r.y1);
}
std::string format_range(const SampleRange& r) { return std::to_string(r.begin) + ":" + std::to_string(r.end); }

BatchPiece shared_part(const BatchPiece& a, const BatchPiece& b) {
  return {a.pixels.intersection(b.pixels),
          {std::max(a.samples.begin, b.samples.begin), std::min(a.samples.end, b.samples.end)}};
}

std::uint64_t covered_pixels(const std::vector<BatchPiece>& pieces) {
  std::uint64_t total = 0;
  for (const BatchPiece& p : pieces) total += p.pixels.area();
  return total;
}

namespace {

// Per pixel, the largest sample end of the pieces swept so far, and the piece that reaches it.
struct Reach {
  int end = 0;
  std::uint32_t holder = 0;
};

// The sweep of first_overlap over `cells` (a vector over the pieces' bounding box, or a hash map
// when the pieces are few and far apart), which `cell(x, y)` indexes.
template <class CellOf>
std::optional<std::pair<size_t, size_t>> sweep(const std::vector<BatchPiece>& pieces, CellOf&& cell) {
  std::vector<size_t> order(pieces.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return pieces[a].samples.begin < pieces[b].samples.begin; });
  for (const size_t i : order) {
    const BatchPiece& piece = pieces[i];
    if (piece.samples.count() <= 0) continue;
    for (int y = piece.pixels.y0; y < piece.pixels.y1; ++y)
      for (int x = piece.pixels.x0; x < piece.pixels.x1; ++x) {
        Reach& r = cell(x, y);
        if (piece.samples.begin < r.end) return std::pair(std::max<size_t>(i, r.holder), std::min<size_t>(i, r.holder));
        r = {piece.samples.end, std::uint32_t(i)};
      }
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::pair<size_t, size_t>> first_overlap(const std::vector<BatchPiece>& pieces) {
  // A sweep over the samples: taken in order of their first sample, a piece overlaps an earlier one
  // exactly when, at some pixel of it, its first sample comes before the largest end of the ranges
  // already there (every earlier range there begins no later than it does). One Reach per pixel
  // makes this O(n log n) plus the pixels the pieces cover, where comparing every pair was O(n^2):
  // 59 s for 10^5 pieces.
  if (pieces.empty()) return std::nullopt;
  PixelRect box = pieces[0].pixels;
  for (const BatchPiece& p : pieces)
    box = {std::min(box.x0, p.pixels.x0), std::min(box.y0, p.pixels.y0), std::max(box.x1, p.pixels.x1),
           std::max(box.y1, p.pixels.y1)};
  const std::uint64_t covered = covered_pixels(pieces);
  if (box.area() <= 4 * covered + 4096) {
    std::vector<Reach> cells(box.area());
    return sweep(pieces, [&](int x, int y) -> Reach& {
      return cells[size_t(y - box.y0) * size_t(box.width()) + size_t(x - box.x0)];
    });
  }
  // Pieces scattered over a large box: memory for the pixels they cover only.
  std::unordered_map<std::uint64_t, Reach> cells;
  cells.reserve(size_t(std::min<std::uint64_t>(covered, 1u << 24)));
  return sweep(pieces, [&](int x, int y) -> Reach& { return cells[std::uint64_t(y) << 32 | std::uint32_t(x)]; });
}

std::vector<std::uint32_t> expected_counts(const PixelRect& window, const std::vector<BatchPiece>& pieces) {
  std::vector<std::uint32_t> counts(window.area(), 0);
  for (const BatchPiece& piece : pieces) {
    const PixelRect r = piece.pixels.intersection(window);
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x)
        counts[size_t(y - window.y0) * size_t(window.width()) + size_t(x - window.x0)] +=
            std::uint32_t(piece.samples.count());
  }
  return counts;
}

void write_sample_batch(const SampleBatch& batch) {
  const SampleSums& sums = batch.sums;
  std::vector<float> counts(sums.counts().begin(), sums.counts().end());
  const std::vector<char> sum_bytes = encode_pfm(sums.sums());
  const std::vector<char> count_bytes = encode_pfm_grey(sums.width(), sums.height(), counts);

  // One field per line, in reading order, and one line per piece (a merged batch has many).
  const RenderIdentity& id = batch.identity;
  const std::vector<std::pair<const char*, json>> fields = {
      {"format", kFormat},
      {"program", id.program},
      {"scene", id.scene},
      {"scene_fnv1a64", id.scene_hash},
      {"options", id.options},
      {"width", id.width},
      {"height", id.height},
      {"seed", id.seed},
      {"window", rect_to_json(batch.window)},
      {"interrupted", batch.interrupted},
      {"sum", batch_sum_path(batch.file).filename().string()},
      {"sum_fnv1a64", fingerprint(sum_bytes)},
      {"count", batch_count_path(batch.file).filename().string()},
      {"count_fnv1a64", fingerprint(count_bytes)},
  };
  std::string text = "{\n";
  for (const auto& [key, value] : fields) text += "  \"" + std::string(key) + "\": " + value.dump() + ",\n";
  text += "  \"pieces\": [\n";
  for (size_t i = 0; i < batch.pieces.size(); ++i) {
    const BatchPiece& p = batch.pieces[i];
    const json piece = {{"pixels", rect_to_json(p.pixels)}, {"samples", {p.samples.begin, p.samples.end}}};
    text += "    " + piece.dump() + (i + 1 < batch.pieces.size() ? ",\n" : "\n");
  }
  text += "  ]\n}\n";
  write_file_atomically(batch_sum_path(batch.file), sum_bytes);
  write_file_atomically(batch_count_path(batch.file), count_bytes);
  write_file_atomically(batch.file, std::vector<char>(text.begin(), text.end()));
}

SampleBatch read_sample_batch(const fs::path& json_path) {
  const DescriptionReader in(json_path);
  json d;
  try {
    const std::string text = read_input_file(json_path, "sample batch", kMaxDescriptionBytes);
    // nlohmann's parser takes a NUL byte for the end of the input and would accept whatever follows.
    if (const size_t nul = text.find('\0'); nul != std::string::npos)
      in.fail("a NUL byte at offset " + std::to_string(nul) + ": not a sample batch description");
    d = json::parse(text);
  } catch (const json::exception& e) {  // a syntax error, or a number beyond double (out_of_range)
    in.fail(std::string("not a sample batch description (malformed JSON: ") + e.what() + ")");
  }
  if (!d.is_object() || !d.contains("format") || d["format"] != kFormat)
    in.fail(std::string("not a sample batch description (no \"format\": \"") + kFormat + "\")");

  SampleBatch batch;
  batch.file = json_path;
  RenderIdentity& id = batch.identity;
  id.program = in.text(d, "program");
  id.scene = in.text(d, "scene");
  id.scene_hash = in.text(d, "scene_fnv1a64");
  id.options = in.text(d, "options");
  id.width = int(in.integer(d, "width", 1, kMaxImageSide));
  id.height = int(in.integer(d, "height", 1, kMaxImageSide));
  const json& seed = in.field(d, "seed");
  if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<std::int64_t>() >= 0))
    in.fail("\"seed\" is not a non-negative integer");
  id.seed = seed.get<std::uint64_t>();
  batch.window = in.rect(d, "window", id.width, id.height);

  const json& pieces = in.field(d, "pieces");
  if (!pieces.is_array() || pieces.empty()) in.fail("\"pieces\" is not a non-empty list");
  for (const json& p : pieces) {
    const PixelRect pixels = in.rect(p, "pixels", id.width, id.height);
    const auto [begin, end] = in.pair(p, "samples", kMaxSpp, "samples");
    if (!batch.window.contains(pixels))
      in.fail("a piece's pixels " + format_rect(pixels) + " lie outside the window " + format_rect(batch.window));
    batch.pieces.push_back({pixels, {begin, end}});
  }
  if (covered_pixels(batch.pieces) > kMaxCoveredPixels)
    in.fail("its " + std::to_string(batch.pieces.size()) + " pieces cover " + std::to_string(covered_pixels(batch.pieces)) +
            " pixels in all, more than the " + std::to_string(kMaxCoveredPixels) + " a batch may");
  if (const auto overlap = first_overlap(batch.pieces))
    in.fail("two pieces both hold samples of pixels " +
            format_rect(shared_part(batch.pieces[overlap->first], batch.pieces[overlap->second]).pixels));
  const json& interrupted = in.field(d, "interrupted");
  if (!interrupted.is_boolean()) in.fail("\"interrupted\" is not true or false");
  batch.interrupted = interrupted.get<bool>();

  // The images: beside the description, of the window's size, the very files it was written with.
  const fs::path folder = written_location(json_path).parent_path();
  auto load = [&](const char* name_key, const char* hash_key) {
    const fs::path image_path = folder / in.text(d, name_key);
    const std::string bytes = read_input_file(image_path, "sample batch image", kMaxPfmFileBytes);
    if (Fnv1a64().add(bytes).hex() != in.text(d, hash_key))
      in.fail(image_path.filename().string() + " is not the image this description was written with "
                                               "(replaced or damaged since)");
    Image image = decode_pfm(bytes, image_path.string());
    if (image.width() != batch.window.width() || image.height() != batch.window.height())
      in.fail(image_path.filename().string() + " is " + std::to_string(image.width()) + "x" +
              std::to_string(image.height()) + ", but the window is " + std::to_string(batch.window.width()) + "x" +
              std::to_string(batch.window.height()));
    return image;
  };
  const Image sum = load("sum", "sum_fnv1a64");
  const Image count = load("count", "count_fnv1a64");

  batch.sums = SampleSums(batch.window.width(), batch.window.height());
  const std::vector<std::uint32_t> expected = expected_counts(batch.window, batch.pieces);
  for (int y = 0; y < sum.height(); ++y)
    for (int x = 0; x < sum.width(); ++x) {
      const Color s = sum.at(x, y);
      const float n = count.at(x, y).r;
      const std::string where = "pixel (" + std::to_string(batch.window.x0 + x) + ", " +
                                std::to_string(batch.window.y0 + y) + ")";
      if (!std::isfinite(s.r) || !std::isfinite(s.g) || !std::isfinite(s.b)) in.fail(where + " has a sum that is not finite");
      if (!(n >= 0.0f && n <= kMaxStoredCount && n == std::floor(n)))
        in.fail(where + " has a sample count that is not a whole number of samples");
      const std::uint32_t have = std::uint32_t(n), want = expected[size_t(y) * size_t(sum.width()) + size_t(x)];
      if (have > want || (have < want && !batch.interrupted))
        in.fail(where + " holds " + std::to_string(have) + " samples, but the pieces give it " + std::to_string(want));
      batch.sums.set(x, y, s, have);
    }
  return batch;
}

}  // namespace rt
