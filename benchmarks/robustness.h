// The geometric-robustness benchmark (docs/benchmarks.md): every build of Exacity (the exact one and
// the floating-point ones, geom/exact.h) generates every case of every family in a child
// process with a time limit; each output is judged by GEOS (benchmarks/judge.h) and by the
// exact build's `exacity validate`. Writes robustness.json, robustness.md and robustness.svg.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace exacity::bench {

// The builds, in report order: the exact one, the practitioner's float build as the issue
// describes it (plain doubles, constructions on a 1e-6 m grid, noded in one pass), the
// practitioner's float build with iterated snap rounding on a 2^-24 m grid on exact
// predicates (Epick) and on plain doubles, CGAL's snap
// rounding on its inexact kernel and GEOS's overlay in floating and in fixed precision (the
// partition stage only: benchmarks/cgal_snap_partition.cpp and geos_partition.cpp), and the
// two float builds with no tolerance (geom/exact.h).
inline const std::vector<std::string> kBuildNames = {
    "exact",         "float-grid", "float-snapped", "float-simple-snapped", "cgal-snap",
    "geos-floating", "geos-fixed", "float",         "float-simple"};

struct RobustnessOptions {
  std::vector<std::string> families;  // empty: all
  int cases = 40;                     // per family
  std::uint64_t seed = 1;
  std::filesystem::path out = "out/robustness";
  double time_limit = 60;  // seconds per run of a build on a case
  int jobs = 0;            // cases run at once (0: one per core)
  // Where exacity, exacity-<build>, exacity-cgal-snap and exacity-geos are; builds not there are left out.
  std::filesystem::path programs;
  std::vector<std::string> builds;  // of kBuildNames; empty: every build found
  bool keep_outputs = false;        // else only failed cases' outputs stay
};

struct Outcome {
  int cases = 0, passed = 0, crash = 0, hang = 0, error = 0, rejected = 0;
  std::map<std::string, int> rejected_by_kind;  // as the judge names them, and "validate"
  double median_s = 0;
  int failures() const { return cases - passed; }
};

// One case of a family: its degeneracy level and each build's result ("passed", "crash",
// "hang", "error" or "rejected"), in build order.
struct CaseResult {
  int index = 0;
  double level = 0;
  std::vector<std::string> results;
};

// A build's time over the exact build's, per stage of generate (report.json's timings_s),
// on the cases of every family both passed: the exact build's seconds over this build's,
// median and quartiles. A stage either build spent under a millisecond on is left out of
// that case (its ratio is timer noise).
struct StageRatio {
  std::string stage;
  int cases = 0;
  double median = 0, low = 0, high = 0;  // low and high: the 25th and 75th percentiles
};

struct FamilyResult {
  std::string family;
  std::vector<std::pair<std::string, Outcome>> builds;  // in build order
  std::vector<CaseResult> cases;
  // Per build after the first: the exact build's median time over its own, on the cases
  // both passed (0 when none did: a crash's time says nothing of the cost).
  std::vector<double> time_ratio;
};

// Whether a build fails more often as a family's cases near degeneracy: its failure rate on
// the cases above the family's median level against that on the others (the lower half).
// A family whose cases share one level (the control) has no upper half.
struct LevelTrend {
  double median_level = 0;
  int low_cases = 0, low_failed = 0, high_cases = 0, high_failed = 0;
  double low_rate() const { return low_cases ? static_cast<double>(low_failed) / low_cases : 0; }
  double high_rate() const { return high_cases ? static_cast<double>(high_failed) / high_cases : 0; }
  bool rises() const { return high_cases > 0 && high_rate() > low_rate(); }
};
LevelTrend level_trend(const FamilyResult& family, std::size_t build);

// Runs the benchmark and writes its files into options.out; progress lines go to `log`.
std::vector<FamilyResult> run_robustness(const RobustnessOptions& options, std::ostream& log);

// Writes every case of the families asked for, for another tool to run: DIR/FAMILY/N.geojson
// (the sketch) and DIR/FAMILY/N.json (the family, case, seed, degeneracy level and the
// invariants the judge checks, benchmarks/judge.h). Returns how many cases it wrote.
int export_cases(const RobustnessOptions& options, const std::filesystem::path& dir);

}  // namespace exacity::bench
