#include "generate/regenerate.h"

#include <filesystem>
#include <system_error>

namespace exacity {
namespace fs = std::filesystem;

namespace {

void append_file(std::string& key, const fs::path& file) {
  std::error_code error;
  const auto size = fs::file_size(file, error);
  const auto time = fs::last_write_time(file, error);
  key += "file " + file.string() + " " + std::to_string(error ? 0 : size) + " " +
         std::to_string(error ? 0 : time.time_since_epoch().count()) + " ";
}

}  // namespace

std::string shared_input(const Sketch& sketch) {
  std::string key = sketch.settings_text;
  for (const RoadFeature& road : sketch.roads) {
    key += " road " + std::to_string(static_cast<int>(road.road_class)) + " ";
    append_key(key, road.width);
    for (const geom::Polyline& line : road.lines) {
      key += "line ";
      for (geom::Vec2 p : line) append_key(key, p.x), append_key(key, p.y);
    }
  }
  if (sketch.terrain) append_file(key, sketch.terrain->heightmap);
  for (const ChannelSpec& channel : sketch.channels) append_file(key, channel.image);
  if (!sketch.models.empty()) append_file(key, sketch.models);
  return key;
}

void RegionCache::next_build(const Sketch& sketch) {
  const std::string shared =
      sketch.settings_text.empty() ? "unknown settings " + std::to_string(++unknown_) : shared_input(sketch);
  road_plans.next_build(shared);
  lot_plans.next_build(shared);
  placements.next_build(shared);
}

City regenerate(const City& previous, const Sketch& edited, StageClock& clock) {
  return build_city(edited, clock, previous.regions ? previous.regions : std::make_shared<RegionCache>());
}

}  // namespace exacity
