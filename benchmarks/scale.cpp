#include "benchmarks/scale.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "benchmarks/child_process.h"
#include "benchmarks/figures.h"

namespace exacity::bench {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

constexpr double kGap = 60;  // metres between copies: a street's width and its verges

void for_each_position(ordered_json& coordinates, const auto& f) {
  if (coordinates.is_array() && !coordinates.empty() && coordinates[0].is_number()) return f(coordinates);
  for (ordered_json& c : coordinates) for_each_position(c, f);
}

// The last line a child wrote to its log, without the program's prefix: why it failed, when
// it says so (a refused sketch's one line).
std::string last_line(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  const std::string prefix = "exacity: error: ";
  return last.starts_with(prefix) ? last.substr(prefix.size()) : last;
}

// One size's runs: the medians of each figure.
struct SizeResult {
  int size = 0;
  double buildings = 0, wall_s = 0, cpu_s = 0, peak_mib = 0;
  std::vector<double> walls;  // every run's, for the spread
  ordered_json stage_s = ordered_json::object(), stage_peak_mib = ordered_json::object();
};

SizeResult measure(const ScaleOptions& o, int size) {
  const fs::path sketch = o.out / ("sketch-" + std::to_string(size) + ".geojson");
  std::ofstream(sketch) << tiled_sketch(o.sketch, size);
  const fs::path city = o.out / ("city-" + std::to_string(size));
  SizeResult r;
  r.size = size;
  std::vector<double> buildings, cpu, peak;
  std::map<std::string, std::vector<double>> stage_s, stage_peak;
  std::vector<std::string> stages;  // in the order they ran
  for (int run = 0; run < o.runs; ++run) {
    fs::remove_all(city);
    const fs::path log = o.out / ("city-" + std::to_string(size) + ".log");
    const Run ran = run_child({o.program.string(), "generate", sketch.string(), "-o", city.string(), "--threads",
                               std::to_string(o.threads), "--quiet"},
                              log, std::numeric_limits<double>::infinity());
    if (ran.status != Run::Exited || ran.code != 0)
      throw std::runtime_error("the city of " + sketch.string() + " failed (" + last_line(log) + "); see " +
                               log.string());
    std::ifstream in(city / "report.json");
    const ordered_json report = ordered_json::parse(in);
    const ordered_json& counts = report.at("counts");
    buildings.push_back(counts.contains("buildings_by_kind") ? counts["buildings_by_kind"].value("building", 0)
                                                              : counts.value("buildings", 0));
    r.walls.push_back(ran.seconds), cpu.push_back(ran.cpu_seconds), peak.push_back(ran.peak_mib);
    for (const auto& [stage, s] : report.at("timings_s").items()) {
      if (!stage_s.count(stage)) stages.push_back(stage);
      stage_s[stage].push_back(s.get<double>());
    }
    if (report.contains("peak_memory_mib"))
      for (const auto& [stage, m] : report["peak_memory_mib"].items()) stage_peak[stage].push_back(m.get<double>());
  }
  r.buildings = median(buildings), r.wall_s = median(r.walls), r.cpu_s = median(cpu), r.peak_mib = median(peak);
  for (const std::string& stage : stages) {
    r.stage_s[stage] = median(stage_s[stage]);
    if (stage_peak.count(stage)) r.stage_peak_mib[stage] = median(stage_peak[stage]);
  }
  return r;
}

// A figure at this size over the smallest size's scaled by the buildings: 1 is linear growth.
double over_linear(double value, double first_value, double buildings, double first_buildings) {
  return first_value > 0 && buildings > 0 && first_buildings > 0 ? value / first_value / (buildings / first_buildings)
                                                                  : 0;
}

std::string markdown(const std::vector<SizeResult>& results, const ScaleOptions& o) {
  std::ostringstream s;
  s << "| size | buildings | wall s (spread) | CPU s | peak MiB | kB/building | wall / linear | CPU / linear | peak / "
       "linear |\n|---|---|---|---|---|---|---|---|---|\n";
  const SizeResult& first = results.front();
  for (const SizeResult& r : results) {
    const auto [lo, hi] = std::minmax_element(r.walls.begin(), r.walls.end());
    s << "| " << r.size << " | " << fixed(r.buildings, 0) << " | " << fixed(r.wall_s, 1) << " (" << fixed(*lo, 1)
      << "-" << fixed(*hi, 1) << ") | " << fixed(r.cpu_s, 1) << " | " << fixed(r.peak_mib, 0) << " | "
      << fixed(r.buildings > 0 ? r.peak_mib * 1048.576 / r.buildings : 0, 1) << " | "
      << fixed(over_linear(r.wall_s, first.wall_s, r.buildings, first.buildings), 2) << " | "
      << fixed(over_linear(r.cpu_s, first.cpu_s, r.buildings, first.buildings), 2) << " | "
      << fixed(over_linear(r.peak_mib, first.peak_mib, r.buildings, first.buildings), 2) << " |\n";
  }
  s << "\nBy stage: seconds, and the process's peak MiB when the stage ended\n\n| stage |";
  for (const SizeResult& r : results) s << " size " << r.size << " |";
  s << "\n|---|";
  for (std::size_t i = 0; i < results.size(); ++i) s << "---|";
  s << "\n";
  for (const auto& [stage, _] : first.stage_s.items()) {
    s << "| " << stage << " |";
    for (const SizeResult& r : results)
      s << " " << fixed(r.stage_s.value(stage, 0.0), 2) << " s, " << fixed(r.stage_peak_mib.value(stage, 0.0), 0)
        << " MiB |";
    s << "\n";
  }
  s << "\n" << o.runs << " run(s) a size, medians; `--threads " << o.threads << "` (0: one per core).\n";
  return s.str();
}

// Wall seconds and peak MiB against buildings, both axes from zero, with the linear
// extrapolations from the smallest size dashed.
std::string svg_plot(const std::vector<SizeResult>& results) {
  const double w = 640, h = 360, left = 60, bottom = 40, top = 20, right = 60;
  double max_b = 0, max_s = 0, max_m = 0;
  const SizeResult& first = results.front();
  for (const SizeResult& r : results) {
    max_b = std::max(max_b, r.buildings);
    max_s = std::max({max_s, r.wall_s, first.wall_s * r.buildings / std::max(1.0, first.buildings)});
    max_m = std::max({max_m, r.peak_mib, first.peak_mib * r.buildings / std::max(1.0, first.buildings)});
  }
  auto x = [&](double b) { return left + (w - left - right) * b / std::max(1.0, max_b); };
  auto y = [&](double v, double max) { return h - bottom - (h - bottom - top) * v / std::max(1e-9, max); };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<line x1=\"" << left << "\" y1=\"" << h - bottom << "\" x2=\"" << w - right << "\" y2=\"" << h - bottom
    << "\" stroke=\"black\"/>\n<text x=\"" << w / 2 << "\" y=\"" << h - 8 << "\" text-anchor=\"middle\">buildings (max "
    << fixed(max_b, 0) << ")</text>\n<text x=\"8\" y=\"14\" fill=\"#1f77b4\">wall s (max " << fixed(max_s, 0)
    << ")</text>\n<text x=\"" << w - 8 << "\" y=\"14\" text-anchor=\"end\" fill=\"#d62728\">peak MiB (max "
    << fixed(max_m, 0) << ")</text>\n";
  auto line = [&](const char* colour, bool dashed, auto&& value, double max) {
    s << "<polyline fill=\"none\" stroke=\"" << colour << "\"" << (dashed ? " stroke-dasharray=\"4 4\"" : "")
      << " points=\"" << x(0) << "," << y(0, max);
    for (const SizeResult& r : results) s << " " << x(r.buildings) << "," << y(value(r), max);
    s << "\"/>\n";
  };
  const double per_building = 1.0 / std::max(1.0, first.buildings);
  line("#1f77b4", false, [](const SizeResult& r) { return r.wall_s; }, max_s);
  line("#1f77b4", true, [&](const SizeResult& r) { return first.wall_s * r.buildings * per_building; }, max_s);
  line("#d62728", false, [](const SizeResult& r) { return r.peak_mib; }, max_m);
  line("#d62728", true, [&](const SizeResult& r) { return first.peak_mib * r.buildings * per_building; }, max_m);
  s << "</svg>\n";
  return s.str();
}

}  // namespace

namespace {

// The copies a side of a tiling of `size` copies has.
int side_of(int size) {
  const int k = static_cast<int>(std::lround(std::sqrt(size)));
  if (size < 1 || k * k != size)
    throw std::runtime_error("--sizes: " + std::to_string(size) + " is not a square number (1, 4, 9, 16, ...)");
  return k;
}

}  // namespace

std::string tiled_sketch(const fs::path& sketch, int size) {
  const int k = side_of(size);
  std::ifstream in(sketch);
  if (!in) throw std::runtime_error(sketch.string() + ": cannot read");
  ordered_json doc = ordered_json::parse(in, nullptr, false);
  if (doc.is_discarded() || !doc.contains("features") || !doc["features"].is_array())
    throw std::runtime_error(sketch.string() + ": not a GeoJSON FeatureCollection");
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (ordered_json& f : doc["features"])
    for_each_position(f["geometry"]["coordinates"], [&](const ordered_json& p) {
      x0 = std::min(x0, p[0].get<double>()), x1 = std::max(x1, p[0].get<double>());
      y0 = std::min(y0, p[1].get<double>()), y1 = std::max(y1, p[1].get<double>());
    });
  ordered_json features = ordered_json::array();
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (ordered_json f : doc["features"]) {
        const double dx = i * (x1 - x0 + kGap), dy = j * (y1 - y0 + kGap);
        for_each_position(f["geometry"]["coordinates"], [&](ordered_json& p) {
          p[0] = p[0].get<double>() + dx;
          p[1] = p[1].get<double>() + dy;
        });
        if (k > 1 && f["properties"].contains("name") && f["properties"]["name"].is_string())
          f["properties"]["name"] = f["properties"]["name"].get<std::string>() + " (" + std::to_string(i) + "," +
                                    std::to_string(j) + ")";
        features.push_back(std::move(f));
      }
  doc["features"] = std::move(features);
  return doc.dump();
}

void run_scale(const ScaleOptions& o, std::ostream& log) {
  for (int size : o.sizes) side_of(size);
  fs::create_directories(o.out);
  std::vector<SizeResult> results;
  for (int size : o.sizes) {
    log << "size " << size << ": " << o.runs << " run(s)" << std::endl;
    results.push_back(measure(o, size));
  }
  ordered_json json = ordered_json::array();
  for (const SizeResult& r : results)
    json.push_back({{"size", r.size}, {"buildings", r.buildings}, {"wall_s", r.wall_s}, {"wall_s_runs", r.walls},
                    {"cpu_s", r.cpu_s}, {"peak_mib", r.peak_mib}, {"stage_s", r.stage_s},
                    {"stage_peak_mib", r.stage_peak_mib}});
  std::ofstream(o.out / "scale.json") << ordered_json{{"sketch", o.sketch.string()}, {"threads", o.threads},
                                                      {"runs", o.runs}, {"sizes", json}}
                                             .dump(2)
                                      << "\n";
  const std::string table = markdown(results, o);
  std::ofstream(o.out / "scale.md") << table;
  std::ofstream(o.out / "scale.svg") << svg_plot(results);
  log << table;
}

}  // namespace exacity::bench
