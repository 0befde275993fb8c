// Reading the sketch's settings (docs/design.md, The sketch): each step declares and reads
// its own settings of a zone type (generate/layout/road_settings.h,
// generate/parcels/parcel_settings.h, generate/placement/building_settings.h) through a
// SettingsReader, which checks each value as it is read and names the key in its error.
#pragma once

#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace exacity {

struct Range {
  double min = 0, max = 0;
  friend bool operator==(const Range&, const Range&) = default;
};

// nlohmann::json refuses numbers beyond a double's range (such as 1e999) outright. So that
// the error can name the feature, the sketch reader re-reads the text with each such
// literal replaced by a string with this marker; the literal, when `j` is such a string.
inline constexpr std::string_view kOverflowMarker = "exacity-overflow:";
std::optional<std::string> overflowed_literal(const nlohmann::json& j);

// A number the sketch wrote, finite and in [min, max]; else a UserError naming `file` and
// `where`.
double read_number(const nlohmann::json& j, const std::string& file, const std::string& where, double min, double max);

// A setting as its step reads it, for a form of the settings (exacity serve's GET
// /api/settings): its key; its kind ("number", "whole", "range", "choice", "boolean", or
// "json" for one the step reads itself); its bounds; the value the field held before it was
// read (read over the defaults: the default); a choice's values; the reader's own words on it.
struct SettingShape {
  std::string key, kind;
  double min = 0, max = 0;
  nlohmann::json value;
  std::vector<std::string> choices;
  std::string what;
};

// One JSON object of settings. Every getter leaves the field as it is when the key is absent.
class SettingsReader {
 public:
  SettingsReader(const nlohmann::json& object, std::string file, std::string where)
      : object_(object), file_(std::move(file)), where_(std::move(where)) {}
  // Each key read is also described into `shapes`, once, in the order read.
  SettingsReader(const nlohmann::json& object, std::vector<SettingShape>& shapes)
      : object_(object), shapes_(&shapes) {}

  // Refuses the object when it is not one, or when it has a key not in `keys`, listing them.
  void expect_keys(const std::set<std::string>& keys) const;

  bool has(const char* key) const {
    describe(key, "json", 0, 0, nullptr);
    return object_.contains(key);
  }
  const nlohmann::json& at(const char* key) const { return object_.at(key); }
  const std::string& file() const { return file_; }
  // How errors name a key: "exacity".zones.residential.block_area.
  std::string where(const char* key) const { return where_ + "." + key; }

  void number(const char* key, double& field, double min, double max) const;
  // [smallest, largest]; `what` says what the two numbers measure.
  void range(const char* key, Range& field, double min, double max, const char* what) const;
  // One of `values`; `what` is the error's text when it is none of them.
  void choice(const char* key, std::string& field, std::initializer_list<std::string_view> values,
              const std::string& what) const;
  void boolean(const char* key, bool& field) const;
  // Values at equal steps of their distribution, smallest to largest (2 to 101, from `min`
  // to `max`), as --like measures them (kind "json"); `what` names them with their unit,
  // "footprint areas in m²", and `example` is a list of them.
  void distribution(const char* key, std::vector<double>& field, double min, double max, const std::string& what,
                    const char* example) const;
  // A whole number in [min, max]; `what` names what it counts ("rules").
  void whole_number(const char* key, int& field, int min, int max, const char* what) const;

  // The row of `table` (rows with a `name` and a `what`) the key names, `fallback` when it
  // is absent; the error lists the table's rows.
  template <typename Row>
  const Row& row(const char* key, const std::vector<Row>& table, const Row& fallback) const {
    std::vector<std::string> names;
    for (const Row& r : table) names.emplace_back(r.name);
    describe(key, "choice", 0, 0, std::string(fallback.name), std::move(names));
    if (!has(key)) return fallback;
    const nlohmann::json& j = at(key);
    for (const Row& r : table)
      if (j.is_string() && r.name == j.get_ref<const std::string&>()) return r;
    std::string expected = "expected ";
    for (std::size_t i = 0; i < table.size(); ++i)
      expected += std::string(i == 0 ? "" : i + 1 == table.size() ? " or " : ", ") + "\"" + std::string(table[i].name) +
                  "\" (" + std::string(table[i].what) + ")";
    fail(key, expected);
  }

  [[noreturn]] void fail(const char* key, const std::string& what) const;

 private:
  void describe(const char* key, const char* kind, double min, double max, nlohmann::json value,
                std::vector<std::string> choices = {}, std::string what = {}) const;
  const nlohmann::json& object_;
  std::string file_, where_;
  std::vector<SettingShape>* shapes_ = nullptr;
};

}  // namespace exacity
