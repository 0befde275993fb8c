#include "benchmarks/robustness.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

#include "benchmarks/child_process.h"
#include "benchmarks/families.h"
#include "benchmarks/figures.h"
#include "benchmarks/judge.h"

namespace exacity::bench {
namespace fs = std::filesystem;
namespace {

struct Build {
  std::string name;
  fs::path program;
  std::vector<std::string> args;  // after generate's own
  // Exacity's builds write a whole city, which the exact build's validator checks too; the
  // partition baselines (CGAL's snap rounding, GEOS) write blocks and lots only, for the judge.
  bool validated = true;
};

// The build's program beside the exact one: exacity-<name>, or exacity-geos at a precision.
Build build_named(const std::string& name, const fs::path& programs) {
  if (name == "exact") return {name, programs / "exacity", {}, true};
  if (name == "cgal-snap") return {name, programs / "exacity-cgal-snap", {}, false};
  if (name.starts_with("geos-"))
    return {name, programs / "exacity-geos", {"--precision", name.substr(5)}, false};
  return {name, programs / ("exacity-" + name), {}, true};
}

// The builds asked for (all by default), exact first, each program beside the exact one,
// which validates the others' outputs.
std::vector<Build> builds_in(const RobustnessOptions& o, std::ostream& log) {
  if (!fs::exists(o.programs / "exacity"))
    throw std::runtime_error("the exact build, exacity, is not in " + o.programs.string());
  if (!o.builds.empty() && std::find(o.builds.begin(), o.builds.end(), "exact") == o.builds.end())
    throw std::runtime_error("--build: the exact build is what the others are measured against; include exact");
  // A name that is no build would otherwise just be left out, and a run the caller thought
  // measured it would not.
  for (const std::string& name : o.builds)
    if (std::find(kBuildNames.begin(), kBuildNames.end(), name) == kBuildNames.end()) {
      std::string known;
      for (const std::string& k : kBuildNames) known += (known.empty() ? "" : ", ") + k;
      throw std::runtime_error("--build " + name + ": no such build; use one of " + known);
    }
  std::vector<Build> found;
  for (const std::string& name : kBuildNames) {
    const bool asked = std::find(o.builds.begin(), o.builds.end(), name) != o.builds.end();
    if (!o.builds.empty() && !asked) continue;
    const Build build = build_named(name, o.programs);
    if (fs::exists(build.program)) {
      found.push_back(build);
      continue;
    }
    const std::string why = build.program.string() + " is not built; configure with -DEXACITY_FLOAT=ON (the release preset does)";
    if (asked) throw std::runtime_error(why);
    log << "left out: " << why << "\n";
  }
  return found;
}

// One build on one case.
struct Result {
  enum Kind { Passed, Crash, Hang, Error, Rejected } kind = Passed;
  static constexpr const char* kWords[] = {"passed", "crash", "hang", "error", "rejected"};
  std::vector<std::string> rejected;  // kinds, for Rejected
  double seconds = 0;
  std::map<std::string, double> stage_s;  // report.json's timings_s, when it passed
};

std::map<std::string, double> stage_times(const fs::path& out) {
  std::ifstream in(out / "report.json");
  const auto report = nlohmann::json::parse(in, nullptr, false);
  std::map<std::string, double> times;
  if (report.is_discarded() || !report.contains("timings_s")) return times;
  for (const auto& [stage, s] : report["timings_s"].items())
    if (s.is_number()) times[stage] = s.get<double>();
  return times;
}

bool failed_validation(const fs::path& out) {
  std::ifstream in(out / "report.json");
  auto report = nlohmann::json::parse(in, nullptr, false);
  return !report.is_discarded() && report.contains("validation") && !report["validation"].value("ok", true);
}

Result run_case(const Build& build, const fs::path& exact_program, const fs::path& sketch, const fs::path& dir,
                double limit) {
  const fs::path out = dir / build.name, log = dir / (build.name + ".log");
  fs::remove_all(out);
  std::vector<std::string> args = {build.program.string(), "generate", sketch.string(), "-o", out.string(), "-q", "--threads", "1"};
  args.insert(args.end(), build.args.begin(), build.args.end());
  Run run = run_child(args, log, limit);
  Result r;
  r.seconds = run.seconds;
  if (run.status == Run::TimedOut) r.kind = Result::Hang;
  else if (run.status == Run::Signalled) r.kind = Result::Crash;
  else if (run.code == 3 && failed_validation(out)) r.kind = Result::Rejected, r.rejected.push_back("validate");
  else if (run.code == 3) r.kind = Result::Crash;  // a failed CGAL precondition or internal check
  else if (run.code != 0) r.kind = Result::Error;
  if (r.kind != Result::Passed) return r;

  const Verdict verdict = judge(out);
  for (const auto& [kind, n] : verdict.rejected) r.rejected.push_back(kind);
  if (build.name != "exact" && build.validated) {
    // The exact build's validator, on what a float build wrote (the exact build validated
    // its own output already, inside generate).
    Run check = run_child({exact_program.string(), "validate", out.string()}, dir / (build.name + ".validate.log"), limit);
    if (check.status != Run::Exited || check.code != 0) r.rejected.push_back("validate");
  }
  if (!r.rejected.empty()) r.kind = Result::Rejected;
  else r.stage_s = stage_times(out);
  return r;
}

nlohmann::ordered_json to_json(const Outcome& o) {
  return {{"passed", o.passed},
          {"failures", o.failures()},
          {"crash", o.crash},
          {"hang", o.hang},
          {"error", o.error},
          {"rejected", o.rejected},
          {"rejected_by_kind", o.rejected_by_kind},
          {"median_s", std::round(o.median_s * 1000) / 1000}};
}

// What a family's degeneracy level measures (benchmarks/families.h).
std::string level_of(const std::string& family) {
  for (const Family& f : families())
    if (f.name == family) return f.level;
  return {};
}

// How the report names a build: the two float builds without tolerances say so.
std::string build_label(const std::string& name) {
  if (name == "float-grid") return "float-grid (practitioner, 1e-6 m grid)";
  if (name == "float-snapped") return "float-snapped (practitioner, iterated snap rounding)";
  if (name == "float-simple-snapped") return "float-simple-snapped (practitioner, plain doubles)";
  if (name == "float") return "float, Epick (no tolerance)";
  if (name == "float-simple") return "float-simple (no tolerance)";
  if (name == "cgal-snap") return "CGAL snap rounding on Epick (blocks and lots only)";
  if (name == "geos-floating") return "GEOS, floating (blocks and lots only)";
  if (name == "geos-fixed") return "GEOS, fixed 2^-24 m (blocks and lots only)";
  return name;
}

// Failure rate against degeneracy level, one panel per family, one line per build; cases
// are binned by their level rounded to a whole number.
std::string svg_chart(const std::vector<FamilyResult>& results, const std::vector<Build>& builds) {
  // The legend in rows of three builds.
  const int legend_rows = (static_cast<int>(builds.size()) + 2) / 3;
  const int columns = 4, panel_w = 230, panel_h = 150, gap_x = 40, gap_y = 70, left = 50, top = 24 + 16 * legend_rows;
  const int rows = (static_cast<int>(results.size()) + columns - 1) / columns;
  const int width = left + columns * (panel_w + gap_x), height = top + rows * (panel_h + gap_y) + 30;
  // One per build of kBuildNames, in its order (the snapped build on plain doubles a lighter
  // dotted blue beside the one on Epick).
  static const char* colours[] = {"#2b7a3d", "#e0a100", "#1f5fa8", "#5b9bd5", "#138d90",
                                  "#7b3fa0", "#c23c8c", "#d9822b", "#b8322a"};
  static const char* dashes[] = {"", "", "", "3 2", "", "", "4 2", "6 3", "2 3"};
  static_assert(std::size(colours) == std::size(dashes));
  // A build keeps its style whichever builds ran.
  std::vector<std::size_t> style(builds.size());
  for (std::size_t b = 0; b < builds.size(); ++b)
    style[b] = static_cast<std::size_t>(std::find(kBuildNames.begin(), kBuildNames.end(), builds[b].name) - kBuildNames.begin()) %
               std::size(colours);
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << left << "\" y=\"18\" font-size=\"13\">Failure rate against degeneracy level, per family "
    << "(share of the cases at each level not passed)</text>\n";
  for (std::size_t b = 0; b < builds.size(); ++b) {
    const std::size_t x = left + 360 * (b % 3), y = 28 + 16 * (b / 3);
    s << "<line x1=\"" << x << "\" x2=\"" << x + 20 << "\" y1=\"" << y << "\" y2=\"" << y << "\" stroke=\""
      << colours[style[b]] << "\" stroke-width=\"2\" stroke-dasharray=\"" << dashes[style[b]] << "\"/><text x=\"" << x + 24
      << "\" y=\"" << y + 4 << "\">" << build_label(builds[b].name) << "</text>\n";
  }
  for (std::size_t f = 0; f < results.size(); ++f) {
    const FamilyResult& fr = results[f];
    const int x0 = left + static_cast<int>(f % columns) * (panel_w + gap_x);
    const int y0 = top + 15 + static_cast<int>(f / columns) * (panel_h + gap_y);
    // Per whole level: cases, and failures per build.
    std::map<long, std::pair<int, std::vector<int>>> bins;
    for (const CaseResult& c : fr.cases) {
      auto& bin = bins[std::lround(c.level)];
      bin.second.resize(builds.size());
      ++bin.first;
      for (std::size_t b = 0; b < c.results.size(); ++b) bin.second[b] += c.results[b] != "passed";
    }
    if (bins.empty()) continue;
    const double lo = static_cast<double>(bins.begin()->first) - (bins.size() == 1 ? 1 : 0);
    const double hi = static_cast<double>(bins.rbegin()->first) + (bins.size() == 1 ? 1 : 0);
    auto x_of = [&](double level) { return x0 + (level - lo) / (hi - lo) * panel_w; };
    auto y_of = [&](double rate) { return y0 + panel_h - rate * panel_h; };
    s << "<text x=\"" << x0 << "\" y=\"" << y0 - 6 << "\" font-size=\"12\">" << fr.family << "</text>\n";
    for (int t = 0; t <= 4; ++t)
      s << "<line x1=\"" << x0 << "\" x2=\"" << x0 + panel_w << "\" y1=\"" << y_of(t / 4.0) << "\" y2=\"" << y_of(t / 4.0)
        << "\" stroke=\"#ddd\"/>" << (f % columns == 0 ? "<text x=\"" + std::to_string(x0 - 4) + "\" y=\"" +
                                                           fixed(y_of(t / 4.0) + 4, 1) + "\" text-anchor=\"end\">" +
                                                           std::to_string(t * 25) + "%</text>"
                                                     : std::string())
        << "\n";
    for (const auto& [level, bin] : bins)
      s << "<text x=\"" << fixed(x_of(static_cast<double>(level)), 1) << "\" y=\"" << y0 + panel_h + 13
        << "\" text-anchor=\"middle\">" << level << "</text>\n";
    s << "<text x=\"" << x0 + panel_w / 2 << "\" y=\"" << y0 + panel_h + 28 << "\" text-anchor=\"middle\" fill=\"#555\">"
      << level_of(fr.family) << "</text>\n";
    for (std::size_t b = 0; b < builds.size(); ++b) {
      std::ostringstream points;
      for (const auto& [level, bin] : bins)
        points << fixed(x_of(static_cast<double>(level)), 1) << "," << fixed(y_of(static_cast<double>(bin.second[b]) / bin.first), 1) << " ";
      s << "<polyline points=\"" << points.str() << "\" fill=\"none\" stroke=\"" << colours[style[b]]
        << "\" stroke-width=\"2\" stroke-dasharray=\"" << dashes[style[b]] << "\"/>\n";
      for (const auto& [level, bin] : bins)
        s << "<circle cx=\"" << fixed(x_of(static_cast<double>(level)), 1) << "\" cy=\""
          << fixed(y_of(static_cast<double>(bin.second[b]) / bin.first), 1) << "\" r=\"2.5\" fill=\"" << colours[style[b]]
          << "\"/>\n";
    }
  }
  s << "</svg>\n";
  return s.str();
}

// "low → high" failures of a build on a family, or "—" where its cases share one level.
std::string trend_cell(const FamilyResult& f, std::size_t b) {
  const LevelTrend t = level_trend(f, b);
  if (!t.high_cases) return "—";
  return std::to_string(t.low_failed) + "/" + std::to_string(t.low_cases) + " → " + std::to_string(t.high_failed) +
         "/" + std::to_string(t.high_cases) + (t.rises() ? " (rises)" : "");
}

std::string markdown(const std::vector<FamilyResult>& results, const std::vector<Build>& builds,
                     const RobustnessOptions& o, const std::vector<std::vector<StageRatio>>& stages) {
  std::ostringstream s;
  s << "# Robustness: the exact build against floating-point builds of itself\n\n"
    << "Each case is a sketch written by the family (deterministic in the seed); each build generates it in a child\n"
    << "process limited to " << o.time_limit << " s, on one thread. A case passes when the build exits 0 and its output\n"
    << "passes the GEOS judge and the exact build's `exacity validate`. Failures: crash (a signal, or exit 3: a\n"
    << "failed CGAL precondition or internal check, or a GEOS exception), hang (over the limit), error (another exit\n"
    << "code), rejected (the judge's or the validator's kinds, in brackets). The CGAL snap rounding and GEOS rows are\n"
    << "the partition stage only (zones, water and road areas overlaid into blocks, blocks cut into lots by a fishnet;\n"
    << "no growth, no buildings), judged by the judge alone. The time ratio is the exact build's median time over the other's on\n"
    << "the cases both passed (— where none did: a crash's time says nothing of the cost).\n\n"
    << "| family | cases |";
  for (const Build& b : builds) s << " " << build_label(b.name) << " passed | " << b.name << " failures |";
  s << " median s (" << builds.front().name << ") |";
  for (std::size_t b = 1; b < builds.size(); ++b) s << " time " << builds.front().name << "/" << builds[b].name << " |";
  s << "\n|---|---|";
  for (std::size_t b = 0; b < builds.size(); ++b) s << "---|---|";
  s << "---|";
  for (std::size_t b = 1; b < builds.size(); ++b) s << "---|";
  s << "\n";
  for (const FamilyResult& f : results) {
    s << "| " << f.family << " | " << f.builds.front().second.cases << " |";
    for (const auto& [name, out] : f.builds) {
      std::ostringstream why;
      auto add = [&](const char* what, int n) {
        if (n) why << (why.tellp() ? ", " : "") << n << " " << what;
      };
      add("crash", out.crash), add("hang", out.hang), add("error", out.error);
      if (out.rejected) {
        std::ostringstream kinds;
        for (const auto& [k, n] : out.rejected_by_kind) kinds << (kinds.tellp() ? ", " : "") << k << " " << n;
        why << (why.tellp() ? ", " : "") << out.rejected << " rejected (" << kinds.str() << ")";
      }
      s << " " << out.passed << " | " << out.failures() << (out.failures() ? " (" + why.str() + ")" : "") << " |";
    }
    s << " " << fixed(f.builds.front().second.median_s, 2) << " |";
    for (double ratio : f.time_ratio) s << " " << (ratio > 0 ? fixed(ratio, 2) : "—") << " |";
    s << "\n";
  }
  // Whether failures rise with the level, per family and build.
  s << "\nFailures against degeneracy: failed/cases at or below each family's median level → above it (\"rises\"\n"
    << "where the rate above is higher).\n\n| family | median level |";
  for (const Build& b : builds) s << " " << b.name << " |";
  s << "\n|---|---|";
  for (std::size_t b = 0; b < builds.size(); ++b) s << "---|";
  s << "\n";
  std::vector<int> rising(builds.size(), 0);
  int swept = 0;
  for (const FamilyResult& f : results) {
    s << "| " << f.family << " | " << fixed(level_trend(f, 0).median_level, 1) << " |";
    for (std::size_t b = 0; b < builds.size(); ++b) s << " " << trend_cell(f, b) << " |";
    s << "\n";
    if (!level_trend(f, 0).high_cases) continue;
    ++swept;
    for (std::size_t b = 0; b < builds.size(); ++b) rising[b] += level_trend(f, b).rises();
  }
  s << "| rises on | |";
  for (int n : rising) s << " " << n << " of " << swept << " |";
  s << "\n";
  // Per stage, for the builds that write report.json's timings (Exacity's, not GEOS's).
  std::vector<std::size_t> timed;
  for (std::size_t b = 1; b < builds.size(); ++b)
    if (!stages[b].empty()) timed.push_back(b);
  if (!timed.empty()) {
    s << "\nThe exact build's time over each build's per stage of generate (report.json's `timings_s`), on the cases\n"
      << "of every family both passed: median (25th–75th percentile); a stage either build spent under a millisecond\n"
      << "on is left out of that case.\n\n| stage |";
    for (std::size_t b : timed) s << " " << builds.front().name << "/" << builds[b].name << " |";
    s << "\n|---|";
    for (std::size_t i = 0; i < timed.size(); ++i) s << "---|";
    s << "\n";
    std::vector<std::string> names;
    for (std::size_t b : timed)
      for (const StageRatio& r : stages[b])
        if (std::find(names.begin(), names.end(), r.stage) == names.end()) names.push_back(r.stage);
    for (const std::string& stage : names) {
      s << "| " << stage << " |";
      for (std::size_t b : timed) {
        auto r = std::find_if(stages[b].begin(), stages[b].end(), [&](const StageRatio& x) { return x.stage == stage; });
        if (r == stages[b].end()) s << " — |";
        else s << " " << fixed(r->median, 2) << " (" << fixed(r->low, 2) << "–" << fixed(r->high, 2) << ", " << r->cases << " cases) |";
      }
      s << "\n";
    }
  }
  s << "\n![failure rate against degeneracy level](robustness.svg)\n\nReproduce (release preset, which builds the float programs too):\n\n"
    << "```\ncmake --workflow --preset release\nbuild/release/cli/exacity bench robustness --cases " << o.cases
    << " --seed " << o.seed;
  if (o.jobs > 0) s << " --jobs " << o.jobs;
  for (const std::string& b : o.builds) s << " --build " << b;
  s << "\n```\n\nFamilies:\n\n";
  for (const Family& f : families()) s << "- `" << f.name << "`: " << f.about << " (level: " << f.level << ")\n";
  return s.str();
}

// The families asked for (all by default); an unknown one stops us before any run.
std::vector<std::string> family_names(const RobustnessOptions& o) {
  std::vector<std::string> names = o.families;
  if (names.empty())
    for (const Family& f : families()) names.push_back(f.name);
  for (const std::string& n : names) (void)family_sketch(n, 0, o.seed);
  return names;
}

struct Job {
  std::size_t family;
  int index;
  double level = 0;  // the case's, known once it has run
};

// Every (family, case) in a fixed order; results land by index, whatever order they finish in.
std::vector<Job> case_jobs(std::size_t families, int cases) {
  std::vector<Job> jobs;
  for (std::size_t f = 0; f < families; ++f)
    for (int i = 0; i < cases; ++i) jobs.push_back({f, i});
  return jobs;
}

// Every build on one case; returns its progress line. Passed outputs are removed unless kept.
std::string run_job(const RobustnessOptions& o, const std::string& family, Job& job, const std::vector<Build>& builds,
                    std::vector<Result>& results) {
  const int index = job.index;
  const fs::path dir = o.out / "cases" / family / std::to_string(index);
  fs::create_directories(dir);
  const fs::path sketch = dir / "sketch.geojson";
  const FamilyCase c = family_case(family, index, o.seed);
  job.level = c.level;
  std::ofstream(sketch, std::ios::binary) << c.sketch;
  bool all_passed = true;
  std::ostringstream line;
  line << family << " " << index << ":";
  for (std::size_t b = 0; b < builds.size(); ++b) {
    Result r = run_case(builds[b], o.programs / "exacity", sketch, dir, o.time_limit);
    line << " " << builds[b].name << " " << Result::kWords[r.kind];
    for (const std::string& k : r.rejected) line << " " << k;
    all_passed &= r.kind == Result::Passed;
    if (r.kind == Result::Passed && !o.keep_outputs) fs::remove_all(dir / builds[b].name);
    results[b] = std::move(r);
  }
  if (all_passed && !o.keep_outputs) fs::remove_all(dir);
  return line.str();
}

// Runs the jobs on o.jobs threads (one per core by default); results[job][build].
std::vector<std::vector<Result>> run_jobs(const RobustnessOptions& o, const std::vector<std::string>& names,
                                          std::vector<Job>& jobs, const std::vector<Build>& builds,
                                          std::ostream& log) {
  std::vector<std::vector<Result>> results(jobs.size(), std::vector<Result>(builds.size()));
  fs::create_directories(o.out);
  std::atomic<std::size_t> next{0};
  std::mutex log_mutex;
  // A job that throws stops the others; its exception is the run's, once they have stopped
  // (thrown inside a thread it would end the program).
  std::exception_ptr failure;
  auto work = [&] {
    try {
      for (std::size_t j; (j = next++) < jobs.size();) {
        const std::string line = run_job(o, names[jobs[j].family], jobs[j], builds, results[j]);
        std::lock_guard<std::mutex> lock(log_mutex);
        log << line << "\n" << std::flush;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(log_mutex);
      if (!failure) failure = std::current_exception();
      next = jobs.size();
    }
  };
  const int threads = o.jobs > 0 ? o.jobs : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return results;
}

// Build b's results on family f's cases.
Outcome outcome_of(const std::vector<Job>& jobs, const std::vector<std::vector<Result>>& results, std::size_t f,
                   std::size_t b) {
  Outcome oc;
  std::vector<double> times;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (jobs[j].family != f) continue;
    const Result& r = results[j][b];
    ++oc.cases;
    oc.passed += r.kind == Result::Passed, oc.crash += r.kind == Result::Crash, oc.hang += r.kind == Result::Hang;
    oc.error += r.kind == Result::Error, oc.rejected += r.kind == Result::Rejected;
    for (const std::string& k : r.rejected) ++oc.rejected_by_kind[k];
    if (r.kind != Result::Hang) times.push_back(r.seconds);
  }
  oc.median_s = median(times);
  return oc;
}

// The exact build's median time over build b's, on family f's cases both passed; 0 if none.
double time_ratio(const std::vector<Job>& jobs, const std::vector<std::vector<Result>>& results, std::size_t f,
                  std::size_t b) {
  std::vector<double> exact_s, other_s;
  for (std::size_t j = 0; j < jobs.size(); ++j)
    if (jobs[j].family == f && results[j][0].kind == Result::Passed && results[j][b].kind == Result::Passed)
      exact_s.push_back(results[j][0].seconds), other_s.push_back(results[j][b].seconds);
  return exact_s.empty() ? 0 : median(exact_s) / median(other_s);
}

// The q-quantile of sorted values, by nearest rank.
double quantile(const std::vector<double>& sorted, double q) {
  return sorted[static_cast<std::size_t>(std::lround(q * static_cast<double>(sorted.size() - 1)))];
}

// Per build after the first, its stage ratios (StageRatio) over every case both passed.
std::vector<std::vector<StageRatio>> stage_ratios(const std::vector<std::vector<Result>>& results, std::size_t builds) {
  std::vector<std::vector<StageRatio>> out(builds);
  for (std::size_t b = 1; b < builds; ++b) {
    std::map<std::string, std::vector<double>> ratios;
    for (const std::vector<Result>& r : results) {
      if (r[0].kind != Result::Passed || r[b].kind != Result::Passed) continue;
      for (const auto& [stage, exact_s] : r[0].stage_s) {
        const auto other = r[b].stage_s.find(stage);
        if (exact_s >= 1e-3 && other != r[b].stage_s.end() && other->second >= 1e-3)
          ratios[stage].push_back(exact_s / other->second);
      }
    }
    for (auto& [stage, v] : ratios) {
      std::sort(v.begin(), v.end());
      out[b].push_back({stage, static_cast<int>(v.size()), median(v), quantile(v, 0.25), quantile(v, 0.75)});
    }
  }
  return out;
}

std::vector<FamilyResult> summarise(const std::vector<std::string>& names, const std::vector<Job>& jobs,
                                    const std::vector<Build>& builds, const std::vector<std::vector<Result>>& results) {
  std::vector<FamilyResult> out;
  for (std::size_t f = 0; f < names.size(); ++f) {
    FamilyResult fr{names[f], {}, {}, {}};
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      if (jobs[j].family != f) continue;
      CaseResult c{jobs[j].index, jobs[j].level, {}};
      for (const Result& r : results[j]) c.results.push_back(Result::kWords[r.kind]);
      fr.cases.push_back(std::move(c));
    }
    for (std::size_t b = 0; b < builds.size(); ++b) {
      fr.builds.push_back({builds[b].name, outcome_of(jobs, results, f, b)});
      if (b == 0) continue;
      fr.time_ratio.push_back(time_ratio(jobs, results, f, b));
    }
    out.push_back(std::move(fr));
  }
  return out;
}

nlohmann::ordered_json robustness_json(const RobustnessOptions& o, const std::vector<Build>& builds,
                                       const std::vector<FamilyResult>& out,
                                       const std::vector<std::vector<StageRatio>>& stages) {
  nlohmann::ordered_json doc = {{"seed", o.seed}, {"cases_per_family", o.cases}, {"time_limit_s", o.time_limit}};
  for (const Build& b : builds) doc["builds"][b.name] = b.program.filename().string();
  doc["families"] = nlohmann::ordered_json::array();
  for (const FamilyResult& f : out) {
    nlohmann::ordered_json entry = {{"family", f.family}, {"cases", f.builds.front().second.cases}};
    for (std::size_t b = 0; b < f.builds.size(); ++b) {
      entry[f.builds[b].first] = to_json(f.builds[b].second);
      if (b > 0) entry[f.builds[b].first]["exact_over_this_time"] = f.time_ratio[b - 1] > 0 ? nlohmann::ordered_json(f.time_ratio[b - 1]) : nullptr;
      if (const LevelTrend t = level_trend(f, b); t.high_cases)
        entry[f.builds[b].first]["by_level"] = {{"median_level", t.median_level}, {"failed_at_or_below", t.low_failed},
                                                 {"cases_at_or_below", t.low_cases}, {"failed_above", t.high_failed},
                                                 {"cases_above", t.high_cases}, {"rises", t.rises()}};
    }
    entry["level"] = level_of(f.family);
    entry["per_case"] = nlohmann::ordered_json::array();
    for (const CaseResult& c : f.cases) {
      nlohmann::ordered_json one = {{"case", c.index}, {"level", std::round(c.level * 1000) / 1000}};
      for (std::size_t b = 0; b < builds.size(); ++b) one[builds[b].name] = c.results[b];
      entry["per_case"].push_back(one);
    }
    doc["families"].push_back(entry);
  }
  // The exact build's time over each build's, per stage, on every case both passed.
  doc["exact_over_this_time_by_stage"] = nlohmann::ordered_json::object();
  for (std::size_t b = 1; b < builds.size(); ++b) {
    nlohmann::ordered_json per_stage = nlohmann::ordered_json::object();
    for (const StageRatio& r : stages[b])
      per_stage[r.stage] = {{"cases", r.cases}, {"median", r.median}, {"p25", r.low}, {"p75", r.high}};
    doc["exact_over_this_time_by_stage"][builds[b].name] = per_stage;
  }
  return doc;
}

void write_reports(const RobustnessOptions& o, const std::vector<Build>& builds, const std::vector<FamilyResult>& out,
                   const std::vector<std::vector<StageRatio>>& stages) {
  const nlohmann::ordered_json doc = robustness_json(o, builds, out, stages);
  std::ofstream(o.out / "robustness.json", std::ios::binary) << doc.dump(2) << "\n";
  std::ofstream(o.out / "robustness.md", std::ios::binary) << markdown(out, builds, o, stages);
  std::ofstream(o.out / "robustness.svg", std::ios::binary) << svg_chart(out, builds);
}

}  // namespace

LevelTrend level_trend(const FamilyResult& family, std::size_t build) {
  LevelTrend t;
  std::vector<double> levels;
  for (const CaseResult& c : family.cases) levels.push_back(c.level);
  t.median_level = median(levels);
  for (const CaseResult& c : family.cases) {
    const bool failed = c.results.at(build) != "passed";
    if (c.level > t.median_level) ++t.high_cases, t.high_failed += failed;
    else ++t.low_cases, t.low_failed += failed;
  }
  return t;
}

std::vector<FamilyResult> run_robustness(const RobustnessOptions& o, std::ostream& log) {
  const std::vector<Build> builds = builds_in(o, log);
  const std::vector<std::string> names = family_names(o);
  std::vector<Job> jobs = case_jobs(names.size(), o.cases);
  const std::vector<std::vector<Result>> results = run_jobs(o, names, jobs, builds, log);
  std::vector<FamilyResult> out = summarise(names, jobs, builds, results);
  write_reports(o, builds, out, stage_ratios(results, builds.size()));
  return out;
}

int export_cases(const RobustnessOptions& o, const fs::path& dir) {
  int written = 0;
  for (const std::string& family : family_names(o)) {
    fs::create_directories(dir / family);
    for (int i = 0; i < o.cases; ++i) {
      const FamilyCase c = family_case(family, i, o.seed);
      const std::string name = std::to_string(i);
      std::ofstream(dir / family / (name + ".geojson"), std::ios::binary) << c.sketch;
      nlohmann::ordered_json about = {{"family", family},
                                      {"case", i},
                                      {"seed", o.seed},
                                      {"level", c.level},
                                      {"level_measures", level_of(family)},
                                      {"sketch", name + ".geojson"},
                                      {"judge", judge_invariants()}};
      std::ofstream(dir / family / (name + ".json"), std::ios::binary) << about.dump(2) << "\n";
      ++written;
    }
  }
  return written;
}

}  // namespace exacity::bench
