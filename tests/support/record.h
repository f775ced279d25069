// The plain-data form of the values a graded test takes from the submission (tests/support/subject.h):
// written by the process that ran the submission's code, read back by the judge, a process with
// none of it (docs/instructors.md, "The verdict"). Reading must be safe on any bytes at all: every
// length is checked against what is left before anything is allocated, a bool must be 0 or 1, and
// nothing read is ever a pointer (an index such as Hit::material is only compared, and the judge's
// containers check their bounds). So only the types below have a form; a struct gets one by
// listing its fields in a `record_fields` function found by argument lookup, and a type holding a
// pointer must not (return the fields a test checks instead).
#pragma once

#include "common/aabb.h"
#include "common/hit.h"
#include "common/image.h"
#include "common/math.h"
#include "common/ray.h"
#include "common/sample_sums.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace rt::testing {

// Thrown by RecordReader on bytes that are not a value of the type asked for (subject.h).
struct MalformedRecord {
  const char* what;
};

class RecordWriter {
 public:
  void bytes(const void* data, std::size_t size) { out_.append(static_cast<const char*>(data), size); }
  std::string& out() { return out_; }

 private:
  std::string out_;
};

class RecordReader {
 public:
  explicit RecordReader(std::string_view in) : in_(in) {}
  void bytes(void* data, std::size_t size) {
    if (size > in_.size()) throw MalformedRecord{"it ends early"};
    std::memcpy(data, in_.data(), size);
    in_.remove_prefix(size);
  }
  std::size_t left() const { return in_.size(); }

 private:
  std::string_view in_;
};

template <class T, class Enable = void>
struct Record;  // no form: a type must be given one below or by record_fields

template <class T>
void write_record(RecordWriter& out, const T& value) {
  Record<T>::write(out, value);
}
template <class T>
void read_record(RecordReader& in, T& value) {
  Record<T>::read(in, value);
}

// Numbers, bit for bit (a NaN stays the NaN it was).
template <class T>
struct Record<T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>>> {
  static void write(RecordWriter& out, T v) { out.bytes(&v, sizeof v); }
  static void read(RecordReader& in, T& v) { in.bytes(&v, sizeof v); }
};

template <>
struct Record<bool> {
  static void write(RecordWriter& out, bool v) {
    const std::uint8_t byte = v ? 1 : 0;
    out.bytes(&byte, 1);
  }
  static void read(RecordReader& in, bool& v) {
    std::uint8_t byte = 0;
    in.bytes(&byte, 1);
    if (byte > 1) throw MalformedRecord{"a bool that is neither 0 nor 1"};
    v = byte == 1;
  }
};

template <class T>
struct Record<T, std::enable_if_t<std::is_enum_v<T>>> {
  using Underlying = std::underlying_type_t<T>;
  static void write(RecordWriter& out, T v) { write_record(out, static_cast<Underlying>(v)); }
  static void read(RecordReader& in, T& v) {
    Underlying u{};
    read_record(in, u);
    v = static_cast<T>(u);
  }
};

template <glm::length_t L, class T, glm::qualifier Q>
struct Record<glm::vec<L, T, Q>> {
  static void write(RecordWriter& out, const glm::vec<L, T, Q>& v) {
    for (glm::length_t i = 0; i < L; ++i) write_record(out, v[i]);
  }
  static void read(RecordReader& in, glm::vec<L, T, Q>& v) {
    for (glm::length_t i = 0; i < L; ++i) read_record(in, v[i]);
  }
};

// A count, checked against the bytes left (every element takes one byte or more) before anything
// is allocated: a forged count of 2^60 is refused, not attempted.
inline std::size_t read_count(RecordReader& in) {
  std::uint64_t n = 0;
  read_record(in, n);
  if (n > in.left()) throw MalformedRecord{"a count larger than the bytes that follow"};
  return std::size_t(n);
}

template <class T>
struct Record<std::vector<T>> {
  static void write(RecordWriter& out, const std::vector<T>& v) {
    write_record(out, std::uint64_t(v.size()));
    for (const T& e : v) write_record(out, e);
  }
  static void read(RecordReader& in, std::vector<T>& v) {
    v.assign(read_count(in), T{});
    for (T& e : v) read_record(in, e);
  }
};

// std::vector<bool> packs its elements: each is read as a bool of its own.
template <>
struct Record<std::vector<bool>> {
  static void write(RecordWriter& out, const std::vector<bool>& v) {
    write_record(out, std::uint64_t(v.size()));
    for (const bool e : v) write_record(out, e);
  }
  static void read(RecordReader& in, std::vector<bool>& v) {
    v.assign(read_count(in), false);
    for (size_t i = 0; i < v.size(); ++i) {
      bool e = false;
      read_record(in, e);
      v[i] = e;
    }
  }
};

template <>
struct Record<std::string> {
  static void write(RecordWriter& out, const std::string& s) {
    write_record(out, std::uint64_t(s.size()));
    out.bytes(s.data(), s.size());
  }
  static void read(RecordReader& in, std::string& s) {
    s.assign(read_count(in), '\0');
    in.bytes(s.data(), s.size());
  }
};

template <class T, std::size_t N>
struct Record<std::array<T, N>> {
  static void write(RecordWriter& out, const std::array<T, N>& a) {
    for (const T& e : a) write_record(out, e);
  }
  static void read(RecordReader& in, std::array<T, N>& a) {
    for (T& e : a) read_record(in, e);
  }
};

template <class T>
struct Record<std::optional<T>> {
  static void write(RecordWriter& out, const std::optional<T>& o) {
    write_record(out, o.has_value());
    if (o) write_record(out, *o);
  }
  static void read(RecordReader& in, std::optional<T>& o) {
    bool present = false;
    read_record(in, present);
    o.reset();
    if (present) read_record(in, o.emplace());
  }
};

template <class A, class B>
struct Record<std::pair<A, B>> {
  static void write(RecordWriter& out, const std::pair<A, B>& p) {
    write_record(out, p.first);
    write_record(out, p.second);
  }
  static void read(RecordReader& in, std::pair<A, B>& p) {
    read_record(in, p.first);
    read_record(in, p.second);
  }
};

template <class... T>
struct Record<std::tuple<T...>> {
  static void write(RecordWriter& out, const std::tuple<T...>& t) {
    std::apply([&](const auto&... e) { (write_record(out, e), ...); }, t);
  }
  static void read(RecordReader& in, std::tuple<T...>& t) {
    std::apply([&](auto&... e) { (read_record(in, e), ...); }, t);
  }
};

// A struct whose `record_fields(T&)` (found by argument lookup) ties the fields that make it up.
template <class T>
struct Record<T, std::void_t<decltype(record_fields(std::declval<T&>()))>> {
  static void write(RecordWriter& out, const T& v) {
    std::apply([&](auto&... e) { (write_record(out, e), ...); }, record_fields(const_cast<T&>(v)));
  }
  static void read(RecordReader& in, T& v) {
    std::apply([&](auto&... e) { (read_record(in, e), ...); }, record_fields(v));
  }
};

// An image: its size, then its pixels, which must be as many as the size says.
template <>
struct Record<Image> {
  static void write(RecordWriter& out, const Image& image) {
    write_record(out, image.width());
    write_record(out, image.height());
    write_record(out, image.pixels());
  }
  static void read(RecordReader& in, Image& image) {
    int width = 0, height = 0;
    read_record(in, width);
    read_record(in, height);
    std::vector<Color> pixels;
    read_record(in, pixels);
    if (width < 0 || height < 0 || pixels.size() != std::size_t(width) * std::size_t(height))
      throw MalformedRecord{"an image whose size does not match its pixels"};
    image = Image(width, height);
    image.pixels() = std::move(pixels);
  }
};

// Per-pixel sums and counts: one count per pixel of the sums.
template <>
struct Record<SampleSums> {
  static void write(RecordWriter& out, const SampleSums& s) {
    write_record(out, s.sums());
    write_record(out, s.counts());
  }
  static void read(RecordReader& in, SampleSums& s) {
    Image sums;
    std::vector<std::uint32_t> counts;
    read_record(in, sums);
    read_record(in, counts);
    if (counts.size() != sums.pixel_count()) throw MalformedRecord{"sample sums whose counts do not match its pixels"};
    s = SampleSums(sums.width(), sums.height());
    s.sums() = std::move(sums);
    s.counts() = std::move(counts);
  }
};

}  // namespace rt::testing

namespace rt {

inline auto record_fields(Ray& ray) { return std::tie(ray.origin, ray.direction); }
inline auto record_fields(Aabb& box) { return std::tie(box.lo, box.hi); }
inline auto record_fields(Hit& h) {
  return std::tie(h.t, h.point, h.normal, h.shading_normal, h.point_error, h.uv, h.front_face, h.material, h.primitive,
                  h.triangle);
}

}  // namespace rt
