#pragma once
// How a scene file's fields are read (sim/scene.cpp): every problem is collected, each as
// "FILE: WHERE: WHAT", so that a bad scene gets one error listing all of them.

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sim/scene.h"

namespace polysim::sim::scene_fields {

using nlohmann::json;

// Collects every problem with a scene, each as "FILE: WHERE: WHAT".
class Problems {
 public:
  explicit Problems(std::string file) : file_(std::move(file)) {}
  void add(const std::string& where, const std::string& what) {
    lines_.push_back(file_ + ": " + (where.empty() ? "" : where + ": ") + what);
  }
  bool empty() const { return lines_.empty(); }
  [[noreturn]] void raise() const {
    std::string all;
    for (const std::string& l : lines_) all += (all.empty() ? "" : "\n") + l;
    throw SceneError(all);
  }

 private:
  std::string file_;
  std::vector<std::string> lines_;
};

inline std::string describe(const json& value) {
  switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    default: return "a number";
  }
}

// Reads fields of one JSON object, reporting problems under `where`.
class Fields {
 public:
  Fields(const json& object, std::string where, Problems& problems)
      : object_(object), where_(std::move(where)), problems_(problems) {}

  void allowOnly(const std::set<std::string>& known) {
    for (const auto& [key, value] : object_.items())
      if (!known.count(key)) problems_.add(where_, "unknown field \"" + key + "\"");
  }
  bool has(const std::string& key) const { return object_.contains(key); }
  const json& raw(const std::string& key) const { return object_.at(key); }

  std::optional<double> number(const std::string& key, bool required = false) {
    if (!has(key)) return missing(key, required), std::nullopt;
    const json& v = object_.at(key);
    if (!v.is_number()) return wrong(key, "a number", v), std::nullopt;
    const double x = v.get<double>();
    if (!std::isfinite(x)) return problems_.add(where_, key + " is not a finite number"), std::nullopt;
    return x;
  }
  std::optional<double> positive(const std::string& key, bool required = false) {
    std::optional<double> x = number(key, required);
    if (x && *x <= 0) problems_.add(where_, key + " must be positive (got " + num(*x) + ")"), x.reset();
    return x;
  }
  std::optional<std::string> string(const std::string& key, bool required = false) {
    if (!has(key)) return missing(key, required), std::nullopt;
    if (!object_.at(key).is_string()) return wrong(key, "a string", object_.at(key)), std::nullopt;
    return object_.at(key).get<std::string>();
  }
  std::optional<bool> boolean(const std::string& key) {
    if (!has(key)) return std::nullopt;
    if (!object_.at(key).is_boolean()) return wrong(key, "true or false", object_.at(key)), std::nullopt;
    return object_.at(key).get<bool>();
  }
  template <int N>
  std::optional<Eigen::Matrix<double, N, 1>> vector(const std::string& key, bool required = false) {
    if (!has(key)) return missing(key, required), std::nullopt;
    const json& v = object_.at(key);
    if (!v.is_array() || v.size() != N) return wrong(key, "an array of " + std::to_string(N) + " numbers", v), std::nullopt;
    Eigen::Matrix<double, N, 1> out;
    for (int i = 0; i < N; ++i) {
      if (!v[i].is_number()) return wrong(key + "[" + std::to_string(i) + "]", "a number", v[i]), std::nullopt;
      out[i] = v[i].get<double>();
      if (!std::isfinite(out[i]))
        return problems_.add(where_, key + "[" + std::to_string(i) + "] is not a finite number"), std::nullopt;
    }
    return out;
  }
  std::optional<int> integer(const std::string& key, bool required = false) {
    if (!has(key)) return missing(key, required), std::nullopt;
    const json& v = object_.at(key);
    if (!v.is_number_integer()) return wrong(key, "an integer", v), std::nullopt;
    const long long wide = v.get<long long>();  // 2^32 + 1 must not wrap to 1
    if (wide < std::numeric_limits<int>::min() || wide > std::numeric_limits<int>::max())
      return problem(key + " " + std::to_string(wide) + " is out of range (beyond " +
                     std::to_string(std::numeric_limits<int>::max()) + ")"),
             std::nullopt;
    return static_cast<int>(wide);
  }
  void problem(const std::string& what) { problems_.add(where_, what); }
  const std::string& where() const { return where_; }

  static std::string num(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
  }

 private:
  void missing(const std::string& key, bool required) {
    if (required) problems_.add(where_, "missing field \"" + key + "\"");
  }
  void wrong(const std::string& key, const std::string& expected, const json& got) {
    problems_.add(where_, key + " must be " + expected + " (got " + describe(got) + ")");
  }

  const json& object_;
  std::string where_;
  Problems& problems_;
};

}  // namespace polysim::sim::scene_fields
