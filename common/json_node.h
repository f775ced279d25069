// A JSON value of a scene file together with where it is (its file and its RFC 6901 pointer), so
// that every check the scene loader (common/scene_loader.cpp) makes can name both: a student's first
// scene will have a typo in it, and "cornell.json: /shapes/3/radius: must be positive, got -1"
// finds it.
#pragma once

#include "common/error.h"
#include "common/scene.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <utility>

namespace rt {

using Json = nlohmann::json;

class JsonNode {
 public:
  JsonNode(const Json& value, std::string path, const std::string& source)
      : value_(value), path_(std::move(path)), source_(source) {}

  // Keys and strings are quoted as given, control characters escaped: the message is one line.
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(printable(source_ + ": " + (path_.empty() ? "/" : path_) + ": " + problem));
  }

  const Json& value() const { return value_; }
  bool has(const char* key) const { return value_.contains(key); }

  JsonNode operator[](const char* key) const {
    if (!value_.contains(key)) fail(std::string("missing field '") + key + "'");
    return JsonNode(value_.at(key), path_ + "/" + key, source_);
  }
  JsonNode at(size_t i) const {
    return JsonNode(value_.at(i), path_ + "/" + std::to_string(i), source_);
  }

  // Objects may only hold the keys the format defines: a misspelt key is an error, not a
  // silently ignored default.
  void expect_object() const {
    if (!value_.is_object()) fail("expected an object, got " + type_name());
  }
  void expect_object(std::initializer_list<const char*> allowed) const {
    expect_object();
    const std::set<std::string> known(allowed.begin(), allowed.end());
    for (const auto& item : value_.items())
      if (!known.contains(item.key())) fail("unknown key '" + item.key() + "'");
  }

  size_t expect_array() const {
    if (!value_.is_array()) fail("expected an array, got " + type_name());
    return value_.size();
  }

  std::string as_string() const {
    if (!value_.is_string()) fail("expected a string, got " + type_name());
    return value_.get<std::string>();
  }

  float as_float() const {
    if (!value_.is_number()) fail("expected a number, got " + type_name());
    const double v = value_.get<double>();
    if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
      fail("the number " + given() + " is beyond float's range (+-3.4e38)");
    return float(v);
  }

  float as_float(float lo, float hi, const char* what) const {
    const float v = as_float();
    if (!(v >= lo && v <= hi)) fail(std::string(what) + " must be in [" + fmt(lo) + ", " + fmt(hi) + "], got " + given());
    return v;
  }

  // A size: positive in float and at most kMaxCoordinate (scene.h says why).
  float as_size(const char* what) const {
    const float v = as_float();
    if (!(v > 0.0f))
      fail(std::string(what) + " must be positive, got " + given() +
           (value_.get<double>() > 0.0 ? " (0 in float)" : ""));
    if (v > kMaxCoordinate) fail(std::string(what) + " must be at most 1e18, got " + given());
    return v;
  }

  // Any integer in [lo, hi]. JSON keeps a non-negative integer unsigned and a negative one signed;
  // each is compared as it is (std::cmp_*: no wrap-around), and quoted as given.
  template <class Int>
  Int as_integer(Int lo, Int hi) const {
    if (!value_.is_number_integer())
      fail("expected an integer, got " + type_name() + (value_.is_number() ? " " + given() : ""));
    const auto in = [&](auto v) { return std::cmp_greater_equal(v, lo) && std::cmp_less_equal(v, hi); };
    const bool unsigned_value = value_.is_number_unsigned();
    if (!(unsigned_value ? in(value_.get<std::uint64_t>()) : in(value_.get<std::int64_t>())))
      fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + given());
    return unsigned_value ? Int(value_.get<std::uint64_t>()) : Int(value_.get<std::int64_t>());
  }
  long long as_int(long long lo, long long hi) const { return as_integer<long long>(lo, hi); }

  bool as_bool() const {
    if (!value_.is_boolean()) fail("expected true or false, got " + type_name());
    return value_.get<bool>();
  }

  Vec3 as_vec3() const {
    if (!value_.is_array() || value_.size() != 3) fail("expected an array of 3 numbers");
    return Vec3(at(0).as_float(), at(1).as_float(), at(2).as_float());
  }

  // A point of the scene: each coordinate within +-kMaxCoordinate (scene.h says why).
  Vec3 as_position() const {
    const Vec3 p = as_vec3();
    for (int i = 0; i < 3; ++i)
      if (!(std::abs(p[i]) <= kMaxCoordinate))
        at(size_t(i)).fail("coordinate " + at(size_t(i)).given() + " lies beyond +-1e18, where squared distances overflow float");
    return p;
  }

  // A direction of any length but zero, normalized in double, where neither a tiny one nor a huge
  // one (1e38) under- or overflows its squared length.
  Vec3 as_unit_vector() const {
    const glm::dvec3 d(as_vec3());
    if (!(glm::length(d) > 0.0)) fail("direction must not be zero");
    return Vec3(glm::normalize(d));
  }

  Color as_color(float hi, const char* what) const {
    const Vec3 c = as_vec3();
    for (int i = 0; i < 3; ++i)
      if (!(c[i] >= 0.0f && c[i] <= hi))
        at(size_t(i)).fail(std::string(what) + " must be in [0, " + fmt(hi) + "], got " + at(size_t(i)).given());
    return c;
  }

  // The value as the file spells it (for a number, the shortest text that reads back the same).
  std::string given() const { return value_.dump(); }

 private:
  std::string type_name() const { return value_.type_name(); }
  static std::string fmt(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  const Json& value_;
  std::string path_;
  const std::string& source_;
};

}  // namespace rt
