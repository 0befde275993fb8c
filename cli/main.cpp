// The exacity command: options, progress, error reporting and exit codes (0 ok, 2 bad
// input, 3 failed internal check). The work itself lives in generate/.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <unistd.h>

#include "benchmarks/families.h"
#include "benchmarks/robustness.h"
#include "benchmarks/scale.h"
#include "cli/progress.h"
#include "cli/serve_command.h"
#include "generate/city/format_number.h"
#include "generate/city_report.h"
#include "generate/errors.h"
#include "generate/input_file.h"
#include "generate/export/output_folder.h"
#include "generate/export/gis_export.h"
#include "generate/pipeline.h"
#include "generate/plan/plan.h"
#include "generate/regenerate.h"
#include "generate/sketch/like_place.h"
#include "generate/sketch/sketch.h"
#include "generate/export/statistics.h"
#include "generate/export/validate.h"
#include "geom/planar_map.h"
#include "render/camera_path.h"
#include "render/camera_spec.h"
#include "render/render.h"
#include "render/render_path.h"
#include "render/white_balance.h"

namespace fs = std::filesystem;
using namespace exacity;

namespace {

// When this process started, on the steady clock: --time is the whole command's, and
// loading the program's libraries before main took 0.3 to 0.8 s of wall time here (269
// of them). From /proc/self/stat's start time (clock ticks since boot) against the boot
// clock; where that cannot be read, main's start is the nearest.
std::chrono::steady_clock::time_point process_started() {
  const auto now = std::chrono::steady_clock::now();
  std::ifstream stat("/proc/self/stat");
  std::string line;
  timespec boot{};
  if (!std::getline(stat, line) || clock_gettime(CLOCK_BOOTTIME, &boot) != 0) return now;
  // Field 22, counted after the command's name, which is in parentheses and may hold spaces.
  const auto name_end = line.rfind(')');
  if (name_end == std::string::npos) return now;
  std::istringstream fields(line.substr(name_end + 2));
  std::string field;
  for (int i = 3; i < 22 && fields >> field;) ++i;
  unsigned long long ticks = 0;
  const long per_second = sysconf(_SC_CLK_TCK);
  if (!(fields >> ticks) || per_second <= 0) return now;
  const double age = boot.tv_sec + boot.tv_nsec * 1e-9 - static_cast<double>(ticks) / per_second;
  if (!(age >= 0 && age < 60)) return now;  // a clock this far off is not the process's start
  return now - std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(age));
}

// The render options a user gives; the camera spec is parsed once the city is known.
struct RenderOptions {
  std::string camera;
  float fov = 45;
  std::string size = "960x540";
  int spp = 16;
  float haze = 0;
  bool mark_mapped = false;
  bool overview = false, minimap = false, orthographic = false;
  std::string denoise = "on";
  std::string landscape_trees = "on";  // the woods' and hedgerows' trees beyond the city
  float exposure_ev = 0, white_balance_k = render::kNeutralKelvin;
  double time_s = 0;
  std::string time_of_day;  // HH:MM
  bool night = false;       // --night: 22:00
  std::string date;         // MM-DD or YYYY-MM-DD: the day the hour's sun is reckoned on
  float aperture = 0, focus_distance = 0, focus_tilt = 0;  // depth of field (render/camera.h)
  fs::path path;       // a camera path file: frames, not a still
  std::string frames;  // A:B, of the path's frames
  std::string shard;   // I/N: the I-th of N shares of those frames (a job array's task)
};

// Where a camera spec came from, for messages: --camera, or the sketch's "exacity".camera.
std::string camera_origin(const RenderOptions& o, const std::string& camera_source) {
  return !o.camera.empty() ? std::string("--camera") : camera_source + " \"exacity\".camera";
}

constexpr const char* kCameraExamples =
    "; e.g. orbit:target=0,0,0,azimuth=225,elevation=35,distance=900, look:from=0,-500,200,to=0,0,0, "
    "pedestrian:road=3,along=40, pedestrian:at=120,80,heading=90 or flyer:at=0,0,height=60,heading=45,pitch=-20";

// The camera the user gave (option first, then the sketch's), parsed; nullopt for none.
std::optional<render::CameraSpec> given_camera(const std::string& sketch_camera, const RenderOptions& o,
                                               const std::string& camera_source) {
  const std::string spec = !o.camera.empty() ? o.camera : sketch_camera;
  if (spec.empty()) return std::nullopt;
  try {
    return render::parse_camera_spec(spec, o.fov);
  } catch (const std::invalid_argument& e) {
    throw UserError(camera_origin(o, camera_source) + " \"" + spec + "\": " + e.what() + kCameraExamples);
  }
}

// --time-of-day (or --night) as hours; below 0 for neither. Checked before any work.
float time_of_day(const RenderOptions& o) {
  if (o.night) return 22;
  if (o.time_of_day.empty()) return -1;
  int h = -1, m = -1;
  char colon = 0;
  std::istringstream in(o.time_of_day);
  if (!(in >> h >> colon >> m) || colon != ':' || h < 0 || h > 23 || m < 0 || m > 59 || !in.eof())
    throw UserError("--time-of-day " + o.time_of_day + ": expected HH:MM from 00:00 to 23:59, such as 06:30 or 21:00");
  return static_cast<float>(h) + static_cast<float>(m) / 60;
}

// --date as the day of the year; 0 for none (an equinox). Checked before any work.
int day_of_year(const RenderOptions& o) {
  if (o.date.empty()) return 0;
  const std::string fix = "--date " + o.date + ": expected MM-DD or YYYY-MM-DD, such as 06-21 or 2024-12-21";
  int year = 2001, month = 0, day = 0;  // a common year when none is given
  char dash = 0, dash2 = 0;
  std::istringstream in(o.date);
  const bool with_year = o.date.size() > 5;
  if (with_year && !(in >> year >> dash2 && dash2 == '-' && year >= 1 && year <= 9999)) throw UserError(fix);
  if (!(in >> month >> dash >> day) || dash != '-' || month < 1 || month > 12 || !in.eof()) throw UserError(fix);
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (day < 1 || day > kDays[month - 1] + (leap && month == 2 ? 1 : 0)) throw UserError(fix + " (no such day)");
  if (time_of_day(o) < 0) throw UserError("--date " + o.date + ": a date sets the hour's sun; give --time-of-day HH:MM or --night with it");
  return render::day_of_year(month, day, leap);
}

// --size as width and height; checked before any work.
std::pair<int, int> image_size(const RenderOptions& o) {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream size(o.size);
  if (!(size >> w >> x >> h) || x != 'x' || w < 8 || h < 8 || w > 16384 || h > 16384 || !size.eof())
    throw UserError("--size " + o.size + ": expected WIDTHxHEIGHT such as 1920x1080 (8 to 16384 each)");
  return {w, h};
}

render::RenderRequest request_for(const City& city, const RenderOptions& o, const std::string& camera_source) {
  render::RenderRequest r;
  std::tie(r.width, r.height) = image_size(o);
  r.spp = o.spp;
  if (auto given = given_camera(city.camera, o, camera_source)) {
    try {
      r.camera = render::place_camera(*given, city);
    } catch (const std::invalid_argument& e) {
      throw UserError(camera_origin(o, camera_source) + " \"" + given->text + "\": " + e.what());
    }
  } else {
    r.camera = render::default_camera(city);
    r.camera.fov_y = o.fov;
  }
  r.overview = o.overview, r.minimap = o.minimap, r.orthographic_overview = o.orthographic;
  r.haze_visibility = o.haze;
  r.mark_mapped = o.mark_mapped;
  r.denoise = o.denoise == "on";
  r.landscape_trees = o.landscape_trees == "on";
  r.exposure_ev = o.exposure_ev, r.white_balance_k = o.white_balance_k;
  r.time_budget_s = o.time_s;
  r.time_of_day = time_of_day(o);
  r.day_of_year = day_of_year(o);
  r.camera.depth_of_field = {o.aperture, o.focus_distance, o.focus_tilt};
  return r;
}

nlohmann::ordered_json render_with_progress(const City& city, render::RenderRequest r, ProgressReport& progress) {
  return render::render_city(city, r, [&](const std::string& stage, double f) { progress.fraction("render " + stage, f); });
}

int generate(const std::vector<fs::path>& sketch_paths, const std::vector<fs::path>& footprints, const fs::path& models,
             const fs::path& like_given, const fs::path& out, bool quiet, const RenderOptions* rendering,
             const ExportOptions& exports, const fs::path& plan = {}) {
  const auto started = process_started();  // --time is the whole command's
  // exacity merge: the plan's sketch, and a cache holding every item its tasks computed.
  Sketch sketch;
  Plan read;
  fs::path like = like_given;
  if (plan.empty()) sketch = load_sketch(sketch_paths, true, models, footprints);
  else read = read_plan(plan, sketch), like = read.like;
  // The zone parameters measured from a real place's buildings, before any work.
  if (like.empty()) like = sketch.like;
  nlohmann::ordered_json like_report;
  if (!like.empty()) like_report = like_place(sketch, like);
  std::shared_ptr<RegionCache> merged;
  if (!plan.empty()) merged = merged_cache(plan, read, sketch);
  if (rendering) {  // a bad camera or size stops us before any work
    given_camera(sketch.camera, *rendering, sketch.path.string());
    image_size(*rendering);
  }
  OutputFolder folder(out);
  GenerateResult result;
  {
    ProgressReport progress(quiet);
    StageClock clock([&](int i, int n, const std::string& stage) { progress.stage(i, n, stage); },
                     kCityStages + kWriteStages + (rendering ? 1 : 0));
    City city = build_city(sketch, clock, merged);
    // Without a render nothing reads the city after its files: the 3D export need not hold all of it.
    result = rendering ? write_city(sketch, city, folder.staging(), clock, exports)
                       : write_city(sketch, std::move(city), folder.staging(), clock, exports);
    if (!like_report.is_null()) {
      result.report["like"] = like_report;
      write_report(result.report, folder.staging());
    }
    if (merged) {  // report.json as generate writes it: what the tasks computed is said here
      // Lots merged into a neighbour after a first placement (build_on_lots) are placed
      // here: which lots a placer leaves unbuilt is known only once every lot is placed.
      const auto& reused = result.report["reused"];
      auto of = [&](const char* kind) {
        return std::to_string(reused[kind]["reused"].get<int>()) + " of " + std::to_string(reused[kind]["of"].get<int>());
      };
      if (!quiet)
        std::printf("exacity: from the plan's tasks: region plans %s, block plans %s, lot placements %s\n",
                    of("region_plans").c_str(), of("block_plans").c_str(), of("lot_placements").c_str());
      result.report.erase("reused");
      write_report(result.report, folder.staging());
    }
    if (rendering) {
      // The default still, the overview and the minimap, into OUT/render.
      const fs::path dir = folder.staging() / "render";
      fs::create_directories(dir);
      render::RenderRequest r = request_for(city, *rendering, sketch.path.string());
      r.started = started;
      r.overview = r.minimap = true;
      r.still = dir / "still.png", r.overview_file = dir / "overview.png", r.minimap_file = dir / "minimap.png";
      result.report["render"] = clock.run("render", [&] { return render_with_progress(city, r, progress); });
      result.report["timings_s"] = clock.seconds;
      result.report["peak_memory_mib"] = clock.peak_mib;
      std::ofstream(folder.staging() / "report.json", std::ios::binary) << result.report.dump(2) << "\n";
    }
  }
  folder.commit();
  const auto& counts = result.report["counts"];
  // Buildings alone; the library's other models (trees, ...) by kind after them.
  std::string other_models;
  for (const auto& [kind, n] : counts["buildings_by_kind"].items())
    if (kind != "building") other_models += ", " + kind + " models " + std::to_string(n.get<int>());
  std::printf("exacity: wrote %s (roads %d, blocks %d, lots %d, buildings %d%s); open %s\n", out.string().c_str(),
              counts["roads"].get<int>(), counts["blocks"].get<int>(), counts["lots"].get<int>(),
              counts["buildings_by_kind"].value("building", 0), other_models.c_str(), (out / "map.svg").string().c_str());
  if (!like_report.is_null())
    for (const std::string& line : like_notes(like_report)) std::printf("exacity: like %s\n", line.c_str());
  if (!like_report.is_null())
    for (const auto& [zone, z] : result.report["footprints_by_zone"].items()) {
      auto figures = [](const nlohmann::ordered_json& f) {
        if (f["footprints"].get<int>() == 0) return std::string("none");
        return std::to_string(f["footprints"].get<int>()) + ", median " + format_number(f["median_m2"].get<double>()) +
               " m2, p90 " + format_number(f["p90_m2"].get<double>()) + " m2, coverage " +
               format_number(f["coverage_of_lots"].get<double>()) + " of their lots";
      };
      std::printf("exacity: %s footprints: mapped %s; generated %s\n", zone.c_str(), figures(z["mapped"]).c_str(),
                  figures(z["generated"]).c_str());
    }
  // Each file's own counts (several files read together each have theirs).
  for (const Sketch::OsmCounts& file : sketch.osm_counts) {
    if (file.left_out.empty()) continue;
    int total = 0;
    std::string tags;
    for (const auto& [why, count] : file.left_out) total += count;
    std::vector<std::pair<std::string, int>> most(file.left_out.begin(), file.left_out.end());
    std::stable_sort(most.begin(), most.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    for (std::size_t i = 0; i < most.size() && i < 4; ++i)
      tags += (i ? ", " : "") + most[i].first + " " + std::to_string(most[i].second);
    // A footprint file (--buildings) leaves out only buildings.
    const bool buildings = std::all_of(most.begin(), most.end(), [](const auto& m) { return m.first.rfind("building", 0) == 0; });
    std::fprintf(stderr,
                 buildings ? "exacity: note: %s: left out %d buildings (%s%s); report.json's \"mapped_buildings\" counts them\n"
                           : "exacity: note: %s: left out %d OpenStreetMap features whose tags make no zone or road (%s%s); "
                             "sketch.geojson's \"osm\" member counts them all\n",
                 file.file.c_str(), total, tags.c_str(), most.size() > 4 ? ", ..." : "");
  }
  for (const Sketch::OsmCounts& file : sketch.osm_counts)
    for (const std::string& what : file.repaired)
      std::fprintf(stderr, "exacity: note: %s: %s\n", file.file.c_str(), what.c_str());
  // Each kind of note names its first few, then counts the rest; report.json lists every
  // one (an OSM extract can have thousands of land-use areas no street reaches).
  auto first_few = [&](const char* key, const char* what, auto&& note) {
    constexpr std::size_t kNotesOfAKind = 5;
    const auto& list = result.report[key];
    for (std::size_t i = 0; i < list.size() && i < kNotesOfAKind; ++i) note(list[i]);
    if (list.size() > kNotesOfAKind)
      std::fprintf(stderr, "exacity: note: and %zu more %s (%s lists them all under \"%s\")\n", list.size() - kNotesOfAKind,
                   what, (out / "report.json").string().c_str(), key);
  };
  first_few("empty_zones", "zones got no lots", [&](const nlohmann::ordered_json& z) {
    const std::string zone = z["zone"].get<std::string>(), why = z["why"].get<std::string>();
    if (z.contains("grid_cell"))
      std::fprintf(stderr, "exacity: note: %s: the %s region there got no lots: %s\n",
                   z["grid_cell"].get<std::string>().c_str(), zone.c_str(), why.c_str());
    else if (z.contains("source"))
      std::fprintf(stderr, "exacity: note: %s (%s) got no lots: %s\n", z["source"].get<std::string>().c_str(),
                   zone.c_str(), why.c_str());
    else
      std::fprintf(stderr, "exacity: note: %s: features[%d] (%s) got no lots: %s\n", sketch.path.string().c_str(),
                   z["feature"].get<int>(), zone.c_str(), why.c_str());
  });
  first_few("roads_without_area", "roads have no road area", [&](const nlohmann::ordered_json& r) {
    std::fprintf(stderr, "exacity: note: %s: road %d%s has a centre line and no road area: %s\n",
                 (out / "vector" / "roads.geojson").string().c_str(), r["road"].get<int>(),
                 r.contains("feature") ? (" (sketch.geojson features[" + std::to_string(r["feature"].get<int>()) + "])").c_str() : "",
                 r["why"].get<std::string>().c_str());
  });
  for (const auto& z : result.report["placement_fallbacks"])
    std::fprintf(stderr, "exacity: note: %s: %s lots are filled on the grid only with library models: %s; they get extruded footprints in rows\n",
                 sketch.path.string().c_str(), z["zone"].get<std::string>().c_str(), z["why"].get<std::string>().c_str());
  if (!result.valid) {
    for (const auto& p : result.report["validation"]["problems"])
      std::fprintf(stderr, "exacity: invalid output: %s\n", p.get<std::string>().c_str());
    throw InternalError("the generated city failed validation (see report.json); please report this sketch");
  }
  return 0;
}

// "A:B" (inclusive) within the path's frames; all of them when empty.
std::pair<int, int> frame_range(const std::string& spec, int count) {
  if (spec.empty()) return {0, count - 1};
  int a = 0, b = 0;
  char colon = 0;
  std::istringstream in(spec);
  if (!(in >> a >> colon >> b) || colon != ':' || !in.eof() || a < 0 || b < a || b >= count)
    throw UserError("--frames " + spec + ": expected A:B with 0 <= A <= B <= " + std::to_string(count - 1) +
                    " (the path has " + std::to_string(count) + " frames)");
  return {a, b};
}

// Refuses, before any work, a folder a render could not write into: `dir` is a folder or does
// not exist yet, and the nearest of its parents that exists is a folder, not a file.
void expect_output_folder(const fs::path& dir, const std::string& what) {
  for (fs::path p = dir; !p.empty(); p = p.parent_path()) {
    std::error_code ec;
    const fs::file_status status = fs::status(p, ec);
    if (fs::exists(status)) {
      if (!fs::is_directory(status))
        throw UserError(p.string() + ": is a file, so " + what + " cannot be written there; choose a folder path with -o");
      return;
    }
    if (p == p.parent_path()) return;
  }
}

// Creates the folder a render writes into; a path the user cannot write is theirs to fix.
void create_output_folder(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw UserError(dir.string() + ": cannot create the folder (" + ec.message() + "); check the path and permissions");
}

// An output folder's file that exacity wrote (report.json, sketch.geojson).
std::string output_file(const fs::path& file) {
  return read_input(file, kMaxDataFileBytes, "the output folder's " + file.filename().string(),
                    "generate the city again");
}

// The frames of a camera path into a folder (-o, default OUT/render/frames):
// frame_NNNN.png with its .exr and .json, one independent still each.
int render_path_folder(const fs::path& out, const Sketch& sketch, const RenderOptions& o, const fs::path& dir_given,
                       bool quiet) {
  render::CameraPath path;
  try {
    path = render::load_camera_path(o.path, o.fov);
  } catch (const std::invalid_argument& e) {
    throw UserError(e.what());
  }
  auto [first, last] = frame_range(o.frames, path.frame_count());
  if (!o.shard.empty()) {
    int part = 0, parts = 0;
    char slash = 0;
    std::istringstream in(o.shard);
    if (!(in >> part >> slash >> parts) || slash != '/' || !in.eof() || parts < 1 || part < 0 || part >= parts)
      throw UserError("--shard " + o.shard + ": expected I/N with 0 <= I < N, such as 3/8");
    std::tie(first, last) = render::frame_share(first, last, part, parts);
    if (first > last) {
      std::printf("exacity: --shard %s: no frames left for this part (more parts than frames)\n", o.shard.c_str());
      return 0;
    }
  }
  const fs::path dir = dir_given.empty() ? out / "render" / "frames" : dir_given;
  if (dir.extension() == ".png") throw UserError(dir.string() + ": with --path, -o is the folder for the frames");
  expect_output_folder(dir, "the frames");
  ProgressReport progress(quiet);
  StageClock clock([&](int i, int n, const std::string& stage) { progress.stage(i, n, stage); }, kCityStages + 1);
  City city = build_city(sketch, clock);
  render::RenderRequest r = request_for(city, o, (out / "sketch.geojson").string());
  try {
    path.place(city, o.path.string());  // pedestrians and flyers on the ground; a road it has not stops us here
  } catch (const std::invalid_argument& e) {
    throw UserError(e.what());
  }
  create_output_folder(dir);
  clock.run("render", [&] {
    return render::render_path_frames(city, path, first, last, r, dir, [&](const std::string& stage, double f) {
      progress.fraction("frames " + stage, f);
    });
  });
  progress.finish();
  std::printf("exacity: wrote %s to %s in %s\n", render::frame_file_name(first).c_str(),
              render::frame_file_name(last).c_str(), dir.string().c_str());
  return 0;
}

// Rebuilds the city of an output folder in memory (same sketch, same seed: the same city)
// and renders it.
int render_folder(const fs::path& out, const RenderOptions& o, const fs::path& file, bool quiet) {
  const auto started = process_started();  // --time is the whole command's
  if (!fs::is_regular_file(out / "report.json") || !fs::is_regular_file(out / "sketch.geojson"))
    throw UserError(out.string() + ": not an output folder of exacity generate (no report.json or sketch.geojson); run exacity generate first");
  nlohmann::json report = nlohmann::json::parse(output_file(out / "report.json"), nullptr, false);
  if (report.is_discarded() || !report.contains("sketch_path"))
    throw UserError((out / "report.json").string() + ": unreadable or from an older exacity; generate the city again");
  // The copy's relative paths (heightmap, models) resolve where the original sketch was.
  Sketch sketch = parse_sketch(output_file(out / "sketch.geojson"), report["sketch_path"].get<std::string>());
  given_camera(sketch.camera, o, (out / "sketch.geojson").string());  // a bad camera or size stops us before any work
  image_size(o);
  time_of_day(o);
  day_of_year(o);
  if (!o.path.empty()) return render_path_folder(out, sketch, o, file, quiet);
  const fs::path still = file.empty() ? out / "render" / "still.png" : file;
  if (still.extension() != ".png") throw UserError(still.string() + ": the still is written as PNG; give a file ending in .png");
  if (fs::is_directory(still)) throw UserError(still.string() + ": is a folder; give the still's file name with -o");
  const fs::path dir = still.parent_path().empty() ? fs::path(".") : still.parent_path();
  expect_output_folder(dir, "the still");
  ProgressReport progress(quiet);
  StageClock clock([&](int i, int n, const std::string& stage) { progress.stage(i, n, stage); }, kCityStages + 1);
  City city = build_city(sketch, clock);
  render::RenderRequest r = request_for(city, o, (out / "sketch.geojson").string());
  r.started = started;
  r.still = still;
  create_output_folder(dir);
  r.overview_file = dir / "overview.png", r.minimap_file = dir / "minimap.png";
  nlohmann::ordered_json stats = clock.run("render", [&] { return render_with_progress(city, r, progress); });
  fs::path json = r.still;
  json.replace_extension(".json");
  std::ofstream(json, std::ios::binary) << stats.dump(2) << "\n";
  if (file.empty()) {
    // The folder's own render: report.json records it too (written aside, then renamed).
    nlohmann::ordered_json full = nlohmann::ordered_json::parse(output_file(out / "report.json"), nullptr, false);
    if (!full.is_discarded()) {
      full["render"] = stats;
      std::ofstream(out / ".report.json.partial", std::ios::binary) << full.dump(2) << "\n";
      fs::rename(out / ".report.json.partial", out / "report.json");
    }
  }
  progress.finish();
  std::printf("exacity: wrote %s and %s (%s)%s%s\n", r.still.string().c_str(), fs::path(r.still).replace_extension(".exr").string().c_str(),
              json.filename().string().c_str(), r.overview ? ", overview.png" : "", r.minimap ? ", minimap.png" : "");
  return 0;
}

int validate(const fs::path& out) {
  if (!fs::is_directory(out)) throw UserError(out.string() + ": not a folder; give an output folder of exacity generate");
  Validation v = validate_output(out);
  for (const auto& [layer, n] : v.features) std::printf("%-12s %6d features\n", layer.c_str(), n);
  std::printf("widest rounding sliver accepted: %.3g m\n", v.widest_sliver);
  for (const auto& p : v.problems) std::printf("problem: %s\n", p.c_str());
  std::printf("%s: %s\n", out.string().c_str(), v.ok() ? "valid" : "INVALID");
  return v.ok() ? 0 : 1;
}

// The city statistics of an output folder, recomputed from its layers, and of real data.
int stats(const fs::path& out, const std::vector<fs::path>& real) {
  if (!out.empty()) {
    if (!fs::is_regular_file(out / "sketch.geojson") || !fs::is_directory(out / "vector"))
      throw UserError(out.string() + ": not an output folder of exacity generate (no sketch.geojson or vector/); run exacity generate first");
    Sketch sketch = load_sketch(out / "sketch.geojson", false);
    std::vector<std::string> problems;
    const CityLayers layers = read_layers(out / "vector", problems);
    if (!problems.empty()) throw UserError(problems.front() + "; generate the city again");
    std::printf("%s\n%s", out.string().c_str(), format_statistics(city_statistics(layers, &sketch, &sketch)).c_str());
  }
  for (const fs::path& file : real) std::printf("%s (real)\n%s", file.string().c_str(), format_statistics(real_statistics(file)).c_str());
  return 0;
}

// This program's own path, for the benchmarks that run it (or the builds beside it).
fs::path this_program(const char* argv0) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::absolute(argv0) : self;
}

// Runs the robustness benchmark with the builds beside this program, and prints its table.
int robustness_benchmark(bench::RobustnessOptions o, const char* argv0) {
  o.programs = this_program(argv0).parent_path();
  try {
    bench::run_robustness(o, std::cout);
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  std::ifstream table(o.out / "robustness.md");
  std::cout << table.rdbuf();
  return 0;
}

// Runs the scale benchmark with this program, and prints its tables.
int scale_benchmark(bench::ScaleOptions o, const char* argv0) {
  o.program = this_program(argv0);
  try {
    bench::run_scale(o, std::cout);
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  std::printf("wrote %s (scale.json, scale.md, scale.svg)\n", o.out.string().c_str());
  return 0;
}

// Options more than one subcommand takes, each bound once.
struct SharedOptions {
  bool quiet = false;
  int threads = 0;
  RenderOptions render;  // generate --render takes the render subcommand's image options
};

struct GenerateCommand {
  CLI::App* app = nullptr;
  std::vector<fs::path> sketch, buildings;
  fs::path models, like, out = "out";
  bool render = false;
  ExportOptions exports;
};

struct PlanCommand {
  CLI::App* app = nullptr;
  Plan given;  // tasks: 4 unless --tasks (add_plan)
  fs::path out = "plan";
};

struct PlanTaskCommand {
  CLI::App* app = nullptr;
  fs::path plan;
  int task = 0;
  std::string step;
};

struct MergeCommand {
  CLI::App* app = nullptr;
  fs::path plan, out = "out";
  ExportOptions exports;
};

struct RenderCommand {
  CLI::App* app = nullptr;
  fs::path folder, file;
};

struct ValidateCommand {
  CLI::App* app = nullptr;
  fs::path folder;
};

struct StatsCommand {
  CLI::App* app = nullptr;
  fs::path folder;
  std::vector<fs::path> real;
};

struct RobustnessCommand {
  CLI::App* app = nullptr;
  bench::RobustnessOptions options;
  fs::path export_dir;  // write the cases there instead of running them
};

struct ScaleCommand {
  CLI::App* app = nullptr;
  bench::ScaleOptions options;
};

void add_program_options(CLI::App& app, SharedOptions& shared) {
  app.set_version_flag("--version", std::string("exacity ") + kVersion + ", kernel " + geom::kernel_name());
  app.require_subcommand(1);
  app.add_flag("-q,--quiet", shared.quiet, "Hide progress");
}

void add_image_options(CLI::App* c, RenderOptions& o) {
  c->add_option("--fov", o.fov, "Vertical field of view, degrees")
      ->check(CLI::Range(5.0, 150.0))
      ->capture_default_str();
  c->add_option("--size", o.size, "Image size WIDTHxHEIGHT")->capture_default_str();
  c->add_option("--spp", o.spp, "Samples per pixel")->check(CLI::Range(1, 65536))->capture_default_str();
  c->add_option("--haze", o.haze,
                "Haze for aerial perspective and light shafts: the visibility in metres (0: clear air)")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
  c->add_flag("--mark-mapped", o.mark_mapped,
              "Colour buildings by where they come from: mapped (read from the sketch) light grey, generated orange");
  c->add_option("--denoise", o.denoise, "The edge-aware denoiser, on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  c->add_option("--landscape-trees", o.landscape_trees,
                "The trees of the woods and hedgerows beyond the city, on or off (off: the fields stay, bare; the "
                "land as city.glb has it, for comparing renderers)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  c->add_option("--exposure", o.exposure_ev, "Exposure in stops (EV) over the default")
      ->check(CLI::Range(-20.0, 20.0))
      ->capture_default_str();
  c->add_option("--white-balance", o.white_balance_k,
                "The light's colour temperature in kelvin to make neutral (6500: none; lower: cooler image)")
      ->check(CLI::Range(static_cast<double>(render::kLeastKelvin), static_cast<double>(render::kMostKelvin)))
      ->capture_default_str();
  c->add_option("--time", o.time_s,
                "Progressive: passes of --spp samples while the whole command, the denoiser included, fits in "
                "this many seconds (still.json records the passes)")
      ->check(CLI::Range(0.0, 1e6));
  auto* hour = c->add_option("--time-of-day", o.time_of_day,
                             "HH:MM of local solar time at the city's latitude (from the sketch's CRS; 50 degrees "
                             "north without one), on an equinox unless --date: the sun by the hour, and after "
                             "sunset the twilight, the street lamps and a share of the windows lit (the overview "
                             "and minimap stay by day)");
  c->add_flag("--night", o.night, "Night: the same as --time-of-day 22:00")->excludes(hour);
  c->add_option("--date", o.date, "MM-DD or YYYY-MM-DD: the day --time-of-day's sun is reckoned on (default an equinox)");
  c->add_option("--aperture", o.aperture,
                "Depth of field: the thin lens's diameter in metres (0: a pinhole, all sharp; a few metres over "
                "a city for a miniature look)")
      ->check(CLI::Range(0.0, 1e4))
      ->capture_default_str();
  c->add_option("--focus-distance", o.focus_distance,
                "With --aperture: metres ahead to the plane in focus (0: the camera's target)")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
  c->add_option("--focus-tilt", o.focus_tilt,
                "With --aperture: the plane in focus turned by DEG about the image's horizontal axis (tilt-shift; "
                "90 less the view's angle below the horizon lays it on flat ground)")
      ->check(CLI::Range(-89.0, 89.0))
      ->capture_default_str();
}

// The options of what is written besides the always-written files: generate's and merge's.
void add_export_options(CLI::App* app, ExportOptions& exports) {
  app->add_option("--vector-format", exports.vector_formats,
                  "Also write the vector layers as " + optional_vector_formats_text() +
                      "; repeatable; GeoJSON is always written")
      ->check(CLI::IsMember(vector_format_names()));
  app->add_flag("--cityjson-seq", exports.cityjson_seq,
                "Also write the CityJSON as CityJSONSeq (OUT/city.city.jsonl: a first line of what the objects "
                "share, then one CityJSONFeature a line with its own vertices), the form cjio and 3D BAG stream "
                "large cities in");
  app->add_option("--osm-ids-from", exports.osm_first_id,
                  "Number city.osm's nodes and ways from N up (a range kept for this city) in place of new "
                  "objects' negative ids, which GDAL's OSM driver (and so QGIS) reads only with "
                  "OSM_USE_CUSTOM_INDEXING=NO")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{1'000'000'000'000'000}));
}

void add_generate(CLI::App& app, GenerateCommand& c, SharedOptions& shared) {
  c.app = app.add_subcommand("generate", "Generate a city from a sketch: GeoJSON, a grid map, any vector file OGR reads, or an OSM extract");
  c.app->add_option("SKETCH", c.sketch,
                    "The sketch: GeoJSON (metres, or lon/lat projected to its UTM zone), a grid map (.grid), a vector "
                    "file OGR reads (.gpkg, .shp, .kml, .fgb, .gml; settings in NAME.exacity.json beside it), or an "
                    "OpenStreetMap extract (.osm, .osm.pbf); several read as one (land use and streets, say), "
                    "sharing a CRS, with the first one's settings")
      ->required();
  add_export_options(c.app, c.exports);
  c.app->add_option("--buildings", c.buildings,
                    "A file of building footprints in any vector format OGR reads (BAG, Overture, Microsoft's, a "
                    "GeoPackage's layer of polygons), kept as mapped buildings beside the sketch and raised from "
                    "its height, levels or roof fields; repeatable");
  c.app->add_option("--models", c.models,
                    "A model library (JSON manifest) in place of the sketch's own \"models\"");
  c.app->add_option("--like", c.like,
                    "Take the zone parameters (footprint sizes, heights, setbacks, gaps, lot sizes) from the mapped "
                    "buildings of this OSM extract or file of footprints (the sketch itself, say), per zone type; "
                    "in place of the sketch's own \"like\"");
  c.app->add_option("-o,--output", c.out, "Output folder (replaced if an earlier exacity run wrote it)")
      ->capture_default_str();
  c.app->add_flag("-q,--quiet", shared.quiet, "Hide progress");
  c.app->add_option("--threads", shared.threads, "Worker threads (0: one per core); the output does not depend on it")
      ->check(CLI::Range(0, 1024));
  c.app->add_flag("--render", c.render, "Also render the default still, the overview and the minimap into OUT/render");
  add_image_options(c.app, shared.render);
}

void add_plan(CLI::App& app, PlanCommand& plan, PlanTaskCommand& task, MergeCommand& merge, SharedOptions& shared) {
  constexpr int kMaxTasks = 100000;  // tasks of a step; Slurm allows job arrays of 1,001 unless MaxArraySize says more
  plan.app = app.add_subcommand("plan", "Plan a city as tasks of a job array (scripts/generate_city.sbatch): "
                                        "plan, each step's tasks, then merge");
  plan.app->add_option("SKETCH", plan.given.sketch, "The sketch, as exacity generate reads it (its files read as one)")
      ->required();
  plan.app->add_option("--buildings", plan.given.buildings, "As exacity generate's: files of mapped building footprints; repeatable");
  plan.app->add_option("--models", plan.given.models, "As exacity generate's: a model library in place of the sketch's own");
  plan.app->add_option("--like", plan.given.like,
                       "As exacity generate's: the place whose mapped buildings give the zone parameters, in place of "
                       "the sketch's own \"like\"");
  plan.app->add_option("-o,--output", plan.out, "The plan's folder, new or empty, on storage every node sees")
      ->capture_default_str();
  plan.given.tasks = 4;
  plan.app->add_option("--tasks", plan.given.tasks, "Tasks of each step (a job array's size)")
      ->check(CLI::Range(1, kMaxTasks))
      ->capture_default_str();
  task.app = app.add_subcommand("plan-task", "Compute one task's share of a plan's step, into PLAN/tasks/TASK/STEP.items");
  task.app->add_option("PLAN", task.plan, "A folder of exacity plan")->required();
  task.app->add_option("--task", task.task, "The task, from 0")->required()->check(CLI::Range(0, kMaxTasks - 1));
  task.app->add_option("--step", task.step,
                       "roads (the regions' road plans), lots (the blocks' lot plans: needs every task's roads) or "
                       "buildings (the lots' structures: needs every task's lots)")
      ->required()
      ->check(CLI::IsMember({"roads", "lots", "buildings"}));
  task.app->add_option("--threads", shared.threads, "Worker threads (0: one per core); the items do not depend on it")
      ->check(CLI::Range(0, 1024));
  merge.app = app.add_subcommand("merge", "Join a plan's tasks into the city exacity generate makes of its sketch, "
                                          "byte for byte, validated");
  merge.app->add_option("PLAN", merge.plan, "A folder of exacity plan whose tasks ran every step")->required();
  merge.app->add_option("-o,--output", merge.out, "Output folder (replaced if an earlier exacity run wrote it)")
      ->capture_default_str();
  add_export_options(merge.app, merge.exports);
  merge.app->add_flag("-q,--quiet", shared.quiet, "Hide progress");
  merge.app->add_option("--threads", shared.threads, "Worker threads (0: one per core); the output does not depend on it")
      ->check(CLI::Range(0, 1024));
}

int plan_task(const PlanTaskCommand& c) {
  PlanStep step = PlanStep::Roads;
  for (PlanStep s : kPlanSteps)
    if (c.step == step_name(s)) step = s;
  const int items = run_plan_task(c.plan, c.task, step);
  std::printf("exacity: task %d, step %s: %d items\n", c.task, c.step.c_str(), items);
  return 0;
}

void add_render(CLI::App& app, RenderCommand& c, SharedOptions& shared) {
  RenderOptions& o = shared.render;
  c.app = app.add_subcommand("render", "Render a generated city: a still, and the overview and minimap if asked");
  c.app->add_option("OUT", c.folder, "An output folder of exacity generate")->required();
  c.app->add_option("--camera", o.camera,
                    "orbit:target=X,Y,Z,azimuth=DEG,elevation=DEG,distance=M, look:from=X,Y,Z,to=X,Y,Z, "
                    "pedestrian:road=ID,along=M[,ahead=M][,eye=M], pedestrian:at=X,Y,heading=DEG[,pitch=DEG][,eye=M] "
                    "or flyer:at=X,Y,height=M,heading=DEG[,pitch=DEG] (default: the sketch's camera, else from the "
                    "south-west)");
  add_image_options(c.app, o);
  c.app->add_flag("--overview", o.overview, "Also render the whole city from straight above (overview.png)");
  c.app->add_flag("--orthographic", o.orthographic, "Make the overview orthographic");
  c.app->add_flag("--minimap", o.minimap, "Also draw the minimap (minimap.png) and set it into the still");
  auto* path = c.app->add_option("--path", o.path,
                    "A camera path (JSON: {\"fps\": N, \"keys\": [{\"t\": SECONDS, \"camera\": SPEC}, ...]}): "
                    "renders its frames as DIR/frame_NNNN.png");
  c.app->add_option("--frames", o.frames, "With --path, only frames A:B (inclusive, from 0)")->needs(path);
  c.app->add_option("--shard", o.shard,
                    "With --path, only the I-th of N near-equal runs of those frames (I/N, from 0): a job array's task")
      ->needs(path);
  c.app->add_option("-o,--output", c.file,
                    "The still, a .png (default OUT/render/still.png; the .exr goes beside it); with --path, the "
                    "frames' folder (default OUT/render/frames)");
  c.app->add_flag("-q,--quiet", shared.quiet, "Hide progress");
  c.app->add_option("--threads", shared.threads, "Worker threads (0: one per core); the image does not depend on it")
      ->check(CLI::Range(0, 1024));
}

void add_validate(CLI::App& app, ValidateCommand& c, SharedOptions& shared) {
  c.app = app.add_subcommand("validate", "Re-check every invariant of an output folder exactly");
  c.app->add_option("OUT", c.folder, "An output folder of exacity generate")->required();
  c.app->add_option("--threads", shared.threads, "Worker threads (0: one per core); the answer does not depend on it")
      ->check(CLI::Range(0, 1024));
}

void add_stats(CLI::App& app, StatsCommand& c) {
  c.app = app.add_subcommand("stats",
                             "Print a city's statistics (block, lot and footprint sizes, streets), and real data's");
  c.app->add_option("OUT", c.folder, "An output folder of exacity generate");
  c.app->add_option("--real", c.real,
                    "GeoJSON of real footprints or streets (metres or lon/lat), measured the same way");
}

void add_bench_scale(CLI::App& benchmarks, ScaleCommand& c) {
  bench::ScaleOptions& o = c.options;
  c.app = benchmarks.add_subcommand(
      "scale", "The sketch tiled to several sizes, each generated as a user runs it: seconds and memory per stage");
  c.app->add_option("SKETCH", o.sketch, "The sketch to tile")->check(CLI::ExistingFile)->capture_default_str();
  c.app->add_option("--sizes", o.sizes, "Areas in copies of the sketch, square numbers (1 4 9: 1x1, 2x2, 3x3)")
      ->delimiter(',')
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  c.app->add_option("--threads", o.threads, "generate's --threads (0: one per core)")->check(CLI::Range(0, 1024));
  c.app->add_option("--runs", o.runs, "Runs a size (medians)")->check(CLI::Range(1, 100))->capture_default_str();
  c.app->add_option("-o,--output", o.out, "Folder for the tiled sketches, the cities and scale.json, .md, .svg")
      ->capture_default_str();
}

void add_bench(CLI::App& app, RobustnessCommand& c, ScaleCommand& scale) {
  bench::RobustnessOptions& o = c.options;
  auto* benchmarks = app.add_subcommand("bench", "Benchmarks");
  benchmarks->require_subcommand(1);
  add_bench_scale(*benchmarks, scale);
  c.app = benchmarks->add_subcommand(
      "robustness", "The exact build against its floating-point builds on families of near-degenerate sketches");
  std::vector<std::string> family_names;
  for (const bench::Family& f : bench::families()) family_names.push_back(f.name);
  c.app->add_option("--family", o.families, "Only these families (default: all)")->check(CLI::IsMember(family_names));
  c.app->add_option("--cases", o.cases, "Cases per family")->check(CLI::Range(1, 100000))->capture_default_str();
  c.app->add_option("--seed", o.seed, "Seed of the families' sketches")->capture_default_str();
  c.app->add_option("-o,--output", o.out, "Folder for robustness.json, .md, .svg and failed cases")
      ->capture_default_str();
  c.app->add_option("--time-limit", o.time_limit, "Seconds a build may take on one case")
      ->check(CLI::Range(1.0, 86400.0))
      ->capture_default_str();
  c.app->add_option("--jobs", o.jobs, "Cases run at once (0: one per core)")->check(CLI::Range(0, 1024));
  c.app->add_option("--build", o.builds, "Only these builds, exact among them (default: every one built)")
      ->check(CLI::IsMember(bench::kBuildNames));
  c.app->add_flag("--keep", o.keep_outputs, "Keep every output, not only those of failed cases");
  c.app->add_option("--export", c.export_dir,
                    "Write every case as DIR/FAMILY/N.geojson and the invariants the judge checks as N.json; run nothing");
}

// Parses the command line; the exit code when it is wrong or only asked for help or the
// version, nullopt when there is work to do.
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv, const StatsCommand& stats) {
  try {
    app.parse(argc, argv);
    if (*stats.app && stats.folder.empty() && stats.real.empty())
      throw CLI::ValidationError("stats", "give OUT, --real FILE or both");
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  return std::nullopt;
}

// TBB's worker threads capped while it lives; none for 0 (one per core).
std::unique_ptr<tbb::global_control> thread_limit(int threads) {
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  return limit;
}

// Runs the subcommand given, with exit codes for what it throws: 2 for the user's
// mistakes, 3 for ours.
template <class Run>
int exit_code_of(const Run& run) {
  try {
    return run();
  } catch (const UserError& e) {
    std::fprintf(stderr, "exacity: error: %s\n", e.what());
    return 2;
  } catch (const InternalError& e) {
    std::fprintf(stderr, "exacity: internal error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exacity: internal error: %s\n", e.what());
    return 3;
  }
}

}  // namespace

int main(int argc, char** argv) {
  clean_up_on_interrupt();
  CLI::App app{"Exacity: a city sketch to a whole city, exactly."};
  SharedOptions shared;
  GenerateCommand gen;
  RenderCommand ren;
  ValidateCommand val;
  StatsCommand sta;
  RobustnessCommand rob;
  ScaleCommand scale;
  ServeCommand srv;
  PlanCommand pla;
  PlanTaskCommand pta;
  MergeCommand mer;
  // In this order --help lists them.
  add_program_options(app, shared);
  add_generate(app, gen, shared);
  add_render(app, ren, shared);
  add_validate(app, val, shared);
  add_stats(app, sta);
  add_serve(app, srv);
  add_plan(app, pla, pta, mer, shared);
  add_bench(app, rob, scale);
  if (const std::optional<int> code = parse_command_line(app, argc, argv, sta)) return *code;

  return exit_code_of([&] {
    const std::unique_ptr<tbb::global_control> limit = thread_limit(shared.threads);
    if (*gen.app) return generate(gen.sketch, gen.buildings, gen.models, gen.like, gen.out, shared.quiet,
                                  gen.render ? &shared.render : nullptr, gen.exports);
    if (*pla.app) {
      const Plan plan = write_plan(pla.given, pla.out);
      std::printf("exacity: wrote %s: %d tasks a step; run steps roads, lots, buildings (scripts/generate_city.sbatch), "
                  "then exacity merge %s\n", pla.out.string().c_str(), plan.tasks, pla.out.string().c_str());
      return 0;
    }
    if (*pta.app) return plan_task(pta);
    if (*mer.app) return generate({}, {}, {}, {}, mer.out, shared.quiet, nullptr, mer.exports, mer.plan);
    if (*ren.app) return render_folder(ren.folder, shared.render, ren.file, shared.quiet);
    if (*val.app) return validate(val.folder);
    if (*sta.app) return stats(sta.folder, sta.real);
    if (*srv.app) return run_serve(srv);
    if (*rob.app && !rob.export_dir.empty()) {
      const int n = bench::export_cases(rob.options, rob.export_dir);
      std::printf("wrote %d cases into %s\n", n, rob.export_dir.string().c_str());
      return 0;
    }
    if (*rob.app) return robustness_benchmark(rob.options, argv[0]);
    if (*scale.app) return scale_benchmark(scale.options, argv[0]);
    return 0;
  });
}
