// Structure-aware: the bytes choose a valid sketch near degeneracy (vertices shared, moved
// by a few ulps, put on another zone's edge or a highway; frames far from the origin and
// rotated; parameter values at their bounds), and the whole pipeline runs on it with
// `exacity validate` as the oracle: every run ends in a valid city or one UserError.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fuzz/fuzz_target.h"
#include "generate/pipeline.h"
#include "generate/sketch/sketch.h"

namespace {

using nlohmann::json;

struct Frame {
  double x0 = 0, y0 = 0, angle = 0;
  json at(double x, double y) const {
    const double c = std::cos(angle), s = std::sin(angle);
    return json::array({x0 + c * x - s * y, y0 + s * x + c * y});
  }
};

double nudge(FuzzedDataProvider& in, double v) {
  for (int k = in.ConsumeIntegralInRange(-3, 3); k != 0; k += k > 0 ? -1 : 1)
    v = std::nextafter(v, k > 0 ? INFINITY : -INFINITY);
  return v;
}

using Vertices = std::vector<std::pair<double, double>>;  // in the frame

const char* const kZones[] = {"residential", "commercial", "industrial", "park", "water"};

Frame pick_frame(FuzzedDataProvider& in) {
  Frame f;
  const double origins[] = {0, 1e5, 3.5e6, 1e9, -7e9};
  f.x0 = in.PickValueInArray(origins), f.y0 = in.PickValueInArray(origins);
  const double angles[] = {0, M_PI / 4, M_PI / 6, 1e-9};
  f.angle = in.PickValueInArray(angles);
  return f;
}

// A new vertex, or, once there are two, often one near degeneracy with those seen.
std::pair<double, double> pick_vertex(FuzzedDataProvider& in, const Vertices& seen) {
  const int how = in.ConsumeIntegralInRange(0, 3);
  if (how > 0 && seen.size() >= 2) {
    auto a = seen[in.ConsumeIntegralInRange<std::size_t>(0, seen.size() - 1)];
    auto b = seen[in.ConsumeIntegralInRange<std::size_t>(0, seen.size() - 1)];
    if (how == 1) return {nudge(in, a.first), nudge(in, a.second)};  // shared, or a few ulps off
    const double t = in.ConsumeFloatingPointInRange(0.0, 1.0);       // on (or next to) an edge
    return {nudge(in, a.first + t * (b.first - a.first)), nudge(in, a.second + t * (b.second - a.second))};
  }
  return {in.ConsumeFloatingPointInRange(-300.0, 300.0), in.ConsumeFloatingPointInRange(-300.0, 300.0)};
}

json zone_features(FuzzedDataProvider& in, const Frame& f, Vertices& seen) {
  json features = json::array();
  const int zone_count = in.ConsumeIntegralInRange(1, 4);
  for (int z = 0; z < zone_count; ++z) {
    json ring = json::array();
    const int n = in.ConsumeIntegralInRange(3, 8);
    for (int i = 0; i < n; ++i) {
      auto p = pick_vertex(in, seen);
      seen.push_back(p);
      ring.push_back(f.at(p.first, p.second));
    }
    ring.push_back(ring[0]);
    features.push_back({{"type", "Feature"},
                        {"properties", {{"zone", in.PickValueInArray(kZones)}}},
                        {"geometry", {{"type", "Polygon"}, {"coordinates", json::array({ring})}}}});
  }
  return features;
}

void add_road_features(FuzzedDataProvider& in, const Frame& f, Vertices& seen, json& features) {
  const char* roads[] = {"highway", "main", "local"};
  for (int r = in.ConsumeIntegralInRange(0, 2); r > 0; --r) {
    json line = json::array();
    for (int i = in.ConsumeIntegralInRange(2, 4); i > 0; --i) {
      auto p = pick_vertex(in, seen);
      seen.push_back(p);
      line.push_back(f.at(p.first, p.second));
    }
    const double widths[] = {0.5, 3, 12, 40};
    features.push_back({{"type", "Feature"},
                        {"properties", {{"road", in.PickValueInArray(roads)}, {"width", in.PickValueInArray(widths)}}},
                        {"geometry", {{"type", "LineString"}, {"coordinates", line}}}});
  }
}

// Parameters at their bounds, kept where a run stays short.
json zone_parameters(FuzzedDataProvider& in) {
  json params = json::object();
  if (in.ConsumeBool()) params["block_area"] = in.PickValueInArray({2000.0, 30000.0, 1e9});
  if (in.ConsumeBool()) params["branches"] = in.ConsumeIntegralInRange(1, 16);
  if (in.ConsumeBool()) params["setback"] = in.PickValueInArray({0.0, 1e3});
  if (in.ConsumeBool()) params["jitter"] = in.PickValueInArray({0.0, 180.0});
  if (in.ConsumeBool()) params["origin_deviation"] = in.PickValueInArray({0.0, 80.0});
  if (in.ConsumeBool()) params["lots"] = in.ConsumeBool() ? "split" : "allocation";
  if (in.ConsumeBool()) params["min_block_width"] = in.PickValueInArray({0.0, 1e4});
  if (in.ConsumeBool()) params["building_gap"] = in.PickValueInArray({0.0, 1e3});
  if (in.ConsumeBool()) params["lot_width"] = json::array({2, in.PickValueInArray({2.0, 1e4})});
  return params;
}

// Every step draws from `in` in turn, so the order of the steps is the byte layout.
std::string sketch_from(FuzzedDataProvider& in) {
  const Frame f = pick_frame(in);
  Vertices seen;
  json features = zone_features(in, f, seen);
  add_road_features(in, f, seen, features);
  const json params = zone_parameters(in);
  json settings = {{"seed", in.ConsumeIntegral<std::uint16_t>()}};
  if (!params.empty()) settings["zones"] = {{in.PickValueInArray(kZones), params}};
  return json{{"type", "FeatureCollection"}, {"exacity", settings}, {"features", features}}.dump();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const std::string text = sketch_from(in);
  const auto dir = exacity::fuzz::scratch();
  exacity::fuzz::write(dir / "fuzz.geojson", text);  // the run copies it into its output
  exacity::fuzz::expect_user_errors_only([&] {
    exacity::Sketch sketch = exacity::parse_sketch(text, dir / "fuzz.geojson");
    std::filesystem::create_directories(dir / "out");
    exacity::GenerateResult result = exacity::generate_city(sketch, dir / "out", nullptr);
    if (!result.valid) {
      std::fprintf(stderr, "invalid city from:\n%s\n", text.c_str());
      std::abort();
    }
  });
  return 0;
}
