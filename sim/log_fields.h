#pragma once
// Checked access to the fields of a step log line (`polysim log`, `polysim view`).

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace polysim::sim {

// Checked access to a step line's fields: each error names where the field was looked
// for ("line 3: event 0: pair 1") and the field, instead of reading past what is there.
class LogFields {
 public:
  LogFields(const nlohmann::ordered_json& object, std::string where) : object_(object), where_(std::move(where)) {
    if (!object_.is_object()) throw std::runtime_error(where_ + ": not a JSON object");
  }
  const std::string& where() const { return where_; }
  bool has(const char* key) const { return object_.contains(key); }
  const nlohmann::ordered_json& any(const char* key) const {
    if (!object_.contains(key)) throw std::runtime_error(where_ + ": no \"" + key + "\"");
    return object_[key];
  }
  double number(const char* key) const { return typed(key, &nlohmann::ordered_json::is_number, "a number").get<double>(); }
  long integer(const char* key) const { return typed(key, &nlohmann::ordered_json::is_number_integer, "a whole number").get<long>(); }
  std::string text(const char* key) const { return typed(key, &nlohmann::ordered_json::is_string, "a string").get<std::string>(); }
  const nlohmann::ordered_json& array(const char* key) const { return typed(key, &nlohmann::ordered_json::is_array, "an array"); }
  /// An array of exactly `count` numbers.
  std::vector<double> numbers(const char* key, size_t count) const {
    const nlohmann::ordered_json& list = array(key);
    std::vector<double> out;
    for (const nlohmann::ordered_json& x : list) {
      if (!x.is_number()) break;
      out.push_back(x.get<double>());
    }
    if (out.size() != count || list.size() != count)
      throw std::runtime_error(where_ + ": \"" + key + "\" is not " + std::to_string(count) + " numbers");
    return out;
  }

 private:
  const nlohmann::ordered_json& typed(const char* key, bool (nlohmann::ordered_json::*is)() const noexcept, const char* what) const {
    const nlohmann::ordered_json& v = any(key);
    if (!(v.*is)()) throw std::runtime_error(where_ + ": \"" + key + "\" is not " + what);
    return v;
  }
  const nlohmann::ordered_json& object_;
  std::string where_;
};

}  // namespace polysim::sim
