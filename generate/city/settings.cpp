#include "generate/city/settings.h"

#include <cmath>

#include "generate/errors.h"

namespace exacity {
using nlohmann::json;

std::optional<std::string> overflowed_literal(const json& j) {
  if (!j.is_string()) return std::nullopt;
  const std::string& s = j.get_ref<const std::string&>();
  if (s.rfind(kOverflowMarker, 0) != 0) return std::nullopt;
  return s.substr(kOverflowMarker.size());
}

double read_number(const json& j, const std::string& file, const std::string& where, double min, double max) {
  auto fail = [&](const std::string& what) { throw UserError(file + ": " + where + ": " + what); };
  if (auto literal = overflowed_literal(j)) fail(*literal + " is not a finite number; write a finite number");
  if (!j.is_number()) fail("expected a number, found " + std::string(j.type_name()));
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail("the number is not finite; write a finite number");
  if (v < min || v > max)
    fail("value " + json(v).dump() + " is out of range; use a value from " + json(min).dump() + " to " + json(max).dump());
  return v;
}

void SettingsReader::expect_keys(const std::set<std::string>& keys) const {
  auto fail_here = [&](const std::string& what) { throw UserError(file_ + ": " + where_ + ": " + what); };
  if (!object_.is_object()) fail_here("expected an object, found " + std::string(object_.type_name()));
  for (auto& [k, v] : object_.items()) {
    if (keys.count(k)) continue;
    std::string valid;
    for (auto& key : keys) valid += (valid.empty() ? "" : ", ") + key;
    fail_here("unknown key \"" + k + "\"; remove it or use one of: " + valid);
  }
}

void SettingsReader::describe(const char* key, const char* kind, double min, double max, json value,
                              std::vector<std::string> choices, std::string what) const {
  if (!shapes_) return;
  for (const SettingShape& s : *shapes_)
    if (s.key == key) return;
  shapes_->push_back({key, kind, min, max, std::move(value), std::move(choices), std::move(what)});
}

void SettingsReader::number(const char* key, double& field, double min, double max) const {
  describe(key, "number", min, max, field);
  if (has(key)) field = read_number(object_[key], file_, where(key), min, max);
}

void SettingsReader::whole_number(const char* key, int& field, int min, int max, const char* what) const {
  describe(key, "whole", min, max, field, {}, what);
  if (!has(key)) return;
  if (!object_[key].is_number_integer())
    fail(key, std::string("expected a whole number of ") + what + ", " + std::to_string(min) + " to " + std::to_string(max));
  field = static_cast<int>(read_number(object_[key], file_, where(key), min, max));
}

void SettingsReader::range(const char* key, Range& field, double min, double max, const char* what) const {
  describe(key, "range", min, max, json::array({field.min, field.max}), {}, what);
  if (!has(key)) return;
  const json& v = object_[key];
  if (!v.is_array() || v.size() != 2) fail(key, std::string("give [smallest, largest] ") + what);
  field.min = read_number(v[0], file_, where(key), min, max);
  field.max = read_number(v[1], file_, where(key), field.min, max);
}

void SettingsReader::choice(const char* key, std::string& field, std::initializer_list<std::string_view> values,
                            const std::string& what) const {
  describe(key, "choice", 0, 0, field, std::vector<std::string>(values.begin(), values.end()), what);
  if (!has(key)) return;
  const json& v = object_[key];
  if (v.is_string())
    for (std::string_view value : values)
      if (v.get_ref<const std::string&>() == value) {
        field = value;
        return;
      }
  fail(key, what);
}

void SettingsReader::boolean(const char* key, bool& field) const {
  describe(key, "boolean", 0, 0, field);
  if (!has(key)) return;
  if (!object_[key].is_boolean()) fail(key, "expected true or false");
  field = object_[key].get<bool>();
}

void SettingsReader::distribution(const char* key, std::vector<double>& field, double min, double max,
                                  const std::string& what, const char* example) const {
  describe(key, "json", 0, 0, field, {}, what + " at equal steps of their distribution, smallest to largest");
  if (!has(key)) return;
  const json& a = object_[key];
  if (!a.is_array() || a.size() < 2 || a.size() > 101)
    fail(key, "give from 2 to 101 " + what + ", smallest to largest, such as " + example);
  field.clear();
  for (const json& v : a) field.push_back(read_number(v, file_, where(key), field.empty() ? min : field.back(), max));
}

void SettingsReader::fail(const char* key, const std::string& what) const {
  throw UserError(file_ + ": " + where(key) + ": " + what);
}

}  // namespace exacity
