// The generate job: sketch to every output, stage after stage (docs/design.md, The pipeline).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "generate/city.h"
#include "generate/export/formats.h"
#include "generate/sketch/sketch.h"
#include "generate/version.h"

namespace exacity {

// Called as each stage starts: its position (1-based), the stage count, its name.
using ProgressFn = std::function<void(int, int, const std::string&)>;

// The largest resident set this process has had, in MiB.
double peak_resident_mib();

// Times stages and tells the progress callback as each begins.
class StageClock {
 public:
  StageClock(ProgressFn progress, int count) : progress_(std::move(progress)), count_(count) {}
  template <typename F>
  auto run(const std::string& name, F&& f) {
    if (progress_) progress_(++index_, count_, name);
    const auto start = std::chrono::steady_clock::now();
    struct Record {
      StageClock& clock;
      const std::string& name;
      std::chrono::steady_clock::time_point start;
      ~Record() {
        clock.seconds[name] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        clock.peak_mib[name] = peak_resident_mib();
      }
    } record{*this, name, start};
    return f();
  }
  nlohmann::ordered_json seconds = nlohmann::ordered_json::object();
  // The process's largest resident set so far, as each stage ended (report.json's
  // peak_memory_mib): where the peak is reached.
  nlohmann::ordered_json peak_mib = nlohmann::ordered_json::object();

 private:
  ProgressFn progress_;
  int count_, index_ = 0;
};

inline constexpr int kCityStages = 10;

struct RegionCache;  // generate/regenerate.h

// What build_city keeps of its exact work (the map, the blocks, the lots and what stands
// on them) once the ground is made: by default nothing, as nothing after the ground reads
// it (the clutter asks a compact copy, StandingMap, and the report's figures of it are
// counted then: City::exact_report), so none of it is held through the clutter, the vector
// layers and the exports. Tests that look into it keep it.
enum class ExactWork { Freed, Kept };

// Runs the city's stages on `clock` (kCityStages of them). With a cache, each region's road
// plan, each block's lot plan and each lot's structures are reused from the cache's last
// build where their input is the same (generate/regenerate.h), and the city keeps the cache.
City build_city(const Sketch& sketch, StageClock& clock, std::shared_ptr<RegionCache> cache = {},
                ExactWork exact = ExactWork::Freed);

struct GenerateResult {
  nlohmann::ordered_json report;  // as written to report.json
  bool valid = false;
};

// Writes every output into `dir`, which must exist and be empty. `extra_stages` more
// stages follow on the same clock (the caller's), counted in the progress total.
GenerateResult generate_city(const Sketch& sketch, const std::filesystem::path& dir, const ProgressFn& progress);
// What write_city writes besides what it always writes: vector formats other than GeoJSON
// (generate/export/gis_export.h).
struct ExportOptions {
  std::vector<std::string> vector_formats;
  // city.osm's ids from here up (an id range the user keeps for this city), else new
  // objects' negative ids.
  std::optional<std::int64_t> osm_first_id;
  // The 3D files (CityJSON, glTF, OBJ, PLY) in a "3d export" stage. exacity serve leaves
  // them out and writes them with write_3d_files when first downloaded: they cost an edit's
  // update about as much as its other stages together (docs/design.md, Serving).
  bool three_d = true;
  // The validation stage. exacity serve leaves it out, answers the page, and then
  // validates with validate_written (docs/design.md, Serving: jobs).
  bool validate = true;
  // With the 3D files, city.city.jsonl: the CityJSON as CityJSONSeq (generate/export/cityjson_export.h).
  bool cityjson_seq = false;

  // What exacity serve writes before it answers the page: neither the 3D files nor validation.
  static ExportOptions before_answer() {
    ExportOptions o;
    o.three_d = o.validate = false;
    return o;
  }
};
// `sketch` is the one `city` was built from: OUT/sketch.geojson is its copy.
GenerateResult write_city(const Sketch& sketch, const City& city, const std::filesystem::path& dir, StageClock& clock,
                          const ExportOptions& options = {});
// The same for a city nothing reads afterwards: what no export reads of it (the exact map,
// blocks and lots, when build_city kept them) is freed once the report is made, and the
// vector layers once they are written, so the exports' files and the 3D export's meshes
// are not held beside them.
GenerateResult write_city(const Sketch& sketch, City&& city, const std::filesystem::path& dir, StageClock& clock,
                          const ExportOptions& options = {});
inline constexpr int kWriteStages = 3;

// Validates what write_city wrote into `dir` with ExportOptions::validate false, in a
// "validation" stage on `stages` (that write's clock), and writes `report` (its report,
// with what the caller added) again with the validation, the stages' seconds and peaks in
// their places. The city is the one written: with a cache, only what changed since the
// last validation that passed is checked again (generate/export/validate_window.h).
GenerateResult validate_written(const City& city, const std::filesystem::path& dir, nlohmann::ordered_json report,
                                StageClock& stages);

struct ThreeDFiles {
  // False: the structures' meshes and the ground's pieces are made afresh rather than
  // through the city's cache, which a build may be using.
  bool through_cache = true;
  bool cityjson_seq = false;  // city.city.jsonl as well
};
// The 3D formats of kCityFormats (city.city.json, city.glb, city.obj and city.ply) of
// `city` into `dir` (write_city's 3d export stage).
ThreeDCounts write_3d_files(const City& city, const std::filesystem::path& dir, const ThreeDFiles& files = ThreeDFiles());

}  // namespace exacity
