// CityJSONSeq against the CityJSON document of the same city: the same objects, each with
// its vertex indices resolved to positions, and the same shared members.
#pragma once

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cityjson_seq {

using nlohmann::json;

// Vertex indices, however deeply nested, as the positions they index.
inline json positions(const json& boundaries, const json& vertices) {
  if (boundaries.is_number()) return vertices.at(boundaries.get<std::size_t>());
  json out = json::array();
  for (const json& b : boundaries) out.push_back(positions(b, vertices));
  return out;
}

inline void indices(const json& boundaries, std::set<std::size_t>& out) {
  if (boundaries.is_number()) out.insert(boundaries.get<std::size_t>());
  else for (const json& b : boundaries) indices(b, out);
}

// An object with each geometry's boundaries as positions.
inline json resolved(json object, const json& vertices) {
  for (json& g : object["geometry"]) g["boundaries"] = positions(g["boundaries"], vertices);
  return object;
}

inline void expect_same_city_objects(const std::filesystem::path& document_file,
                                     const std::filesystem::path& sequence_file) {
  const json document = json::parse(std::ifstream(document_file));
  std::map<std::string, json> expected;
  for (const auto& [key, object] : document["CityObjects"].items()) expected[key] = resolved(object, document["vertices"]);

  std::ifstream sequence(sequence_file);
  std::string line;
  ASSERT_TRUE(std::getline(sequence, line)) << sequence_file;
  const json header = json::parse(line);
  EXPECT_EQ(header["type"], "CityJSON");
  EXPECT_EQ(header["CityObjects"], json::object());
  EXPECT_EQ(header["vertices"], json::array());
  for (const char* member : {"version", "transform", "geometry-templates", "appearance", "metadata"})
    EXPECT_EQ(header.value(member, json()), document.value(member, json())) << member;

  std::map<std::string, json> got;
  int features = 0, children = 0;
  while (std::getline(sequence, line)) {
    const json feature = json::parse(line);
    ++features;
    EXPECT_EQ(feature["type"], "CityJSONFeature");
    EXPECT_TRUE(feature["CityObjects"].contains(feature["id"].get<std::string>())) << line.substr(0, 200);
    // A feature's vertices are its own: each one used, none of another's.
    std::set<std::size_t> used;
    for (const auto& [key, object] : feature["CityObjects"].items()) {
      EXPECT_EQ(got.count(key), 0u) << key << " in two features";
      children += object.contains("parents");
      for (const json& g : object["geometry"]) indices(g["boundaries"], used);
      got[key] = resolved(object, feature["vertices"]);
    }
    EXPECT_EQ(used.size(), feature["vertices"].size()) << feature["id"];
  }
  EXPECT_EQ(features + children, static_cast<int>(got.size()));
  EXPECT_EQ(got.size(), expected.size());
  for (const auto& [key, object] : expected) {
    auto it = got.find(key);
    if (it == got.end()) {
      ADD_FAILURE() << key << " is not in " << sequence_file;
      continue;
    }
    EXPECT_EQ(it->second, object) << key;
  }
}

}  // namespace cityjson_seq
