#include "benchmarks/robustness.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

#include "benchmarks/families.h"
#include "benchmarks/judge.h"

extern char** environ;

namespace exacity::bench {
namespace fs = std::filesystem;
namespace {

struct Build {
  std::string name;
  fs::path program;
};

// The builds asked for (all by default), exact first, each program beside the exact one,
// which validates the others' outputs.
std::vector<Build> builds_in(const RobustnessOptions& o, std::ostream& log) {
  if (!fs::exists(o.programs / "exacity"))
    throw std::runtime_error("the exact build, exacity, is not in " + o.programs.string());
  if (!o.builds.empty() && std::find(o.builds.begin(), o.builds.end(), "exact") == o.builds.end())
    throw std::runtime_error("--build: the exact build is what the others are measured against; include exact");
  std::vector<Build> found;
  for (const std::string name : {"exact", "float", "float-simple"}) {
    const bool asked = std::find(o.builds.begin(), o.builds.end(), name) != o.builds.end();
    if (!o.builds.empty() && !asked) continue;
    const fs::path program = o.programs / (name == "exact" ? "exacity" : "exacity-" + name);
    if (fs::exists(program)) {
      found.push_back({name, program});
      continue;
    }
    const std::string why = program.string() + " is not built; configure with -DEXACITY_FLOAT=ON (the release preset does)";
    if (asked) throw std::runtime_error(why);
    log << "left out: " << why << "\n";
  }
  return found;
}

struct Run {
  enum Status { Exited, Signalled, TimedOut } status = Exited;
  int code = 0;  // exit code, or signal
  double seconds = 0;
};

// Runs the program with its output into `log`, killed after `limit` seconds.
Run run_child(const std::vector<std::string>& args, const fs::path& log, double limit) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int failed = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (failed) throw std::runtime_error("cannot run " + args[0]);
  Run run;
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (elapsed() > limit) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      run.status = Run::TimedOut;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  run.seconds = elapsed();
  if (run.status == Run::TimedOut) return run;
  if (WIFSIGNALED(status)) run.status = Run::Signalled, run.code = WTERMSIG(status);
  else run.code = WEXITSTATUS(status);
  return run;
}

// One build on one case.
struct Result {
  enum Kind { Passed, Crash, Hang, Error, Rejected } kind = Passed;
  std::vector<std::string> rejected;  // kinds, for Rejected
  double seconds = 0;
};

bool failed_validation(const fs::path& out) {
  std::ifstream in(out / "report.json");
  auto report = nlohmann::json::parse(in, nullptr, false);
  return !report.is_discarded() && report.contains("validation") && !report["validation"].value("ok", true);
}

Result run_case(const Build& build, const fs::path& exact_program, const fs::path& sketch, const fs::path& dir,
                double limit) {
  const fs::path out = dir / build.name, log = dir / (build.name + ".log");
  fs::remove_all(out);
  Run run = run_child({build.program.string(), "generate", sketch.string(), "-o", out.string(), "-q", "--threads", "1"},
                      log, limit);
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
  if (build.name != "exact") {
    // The exact build's validator, on what a float build wrote (the exact build validated
    // its own output already, inside generate).
    Run check = run_child({exact_program.string(), "validate", out.string()}, dir / (build.name + ".validate.log"), limit);
    if (check.status != Run::Exited || check.code != 0) r.rejected.push_back("validate");
  }
  if (!r.rejected.empty()) r.kind = Result::Rejected;
  return r;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
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

// A grouped bar chart of failure rate by family, one bar per build.
std::string svg_chart(const std::vector<FamilyResult>& results, const std::vector<Build>& builds) {
  const int bar = 14, group = static_cast<int>(builds.size()) * bar + 16, left = 50, top = 30, height = 200;
  const int width = left + group * static_cast<int>(results.size()) + 20;
  static const char* colours[] = {"#2b7a3d", "#d9822b", "#b8322a"};
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << top + height + 120
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << left << "\" y=\"18\" font-size=\"13\">Failure rate by family (share of cases not passed)</text>\n";
  for (int t = 0; t <= 4; ++t) {
    const int y = top + height - t * height / 4;
    s << "<line x1=\"" << left << "\" x2=\"" << width - 10 << "\" y1=\"" << y << "\" y2=\"" << y
      << "\" stroke=\"#ddd\"/><text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">" << t * 25
      << "%</text>\n";
  }
  for (std::size_t f = 0; f < results.size(); ++f) {
    const int x0 = left + static_cast<int>(f) * group + 8;
    for (std::size_t b = 0; b < results[f].builds.size(); ++b) {
      const Outcome& o = results[f].builds[b].second;
      const double rate = o.cases ? static_cast<double>(o.failures()) / o.cases : 0;
      const int h = static_cast<int>(std::lround(rate * height));
      s << "<rect x=\"" << x0 + static_cast<int>(b) * bar << "\" y=\"" << top + height - h << "\" width=\"" << bar - 2
        << "\" height=\"" << std::max(h, 1) << "\" fill=\"" << colours[b % 3] << "\"/>\n";
    }
    s << "<text transform=\"translate(" << x0 + 4 << "," << top + height + 10 << ") rotate(40)\">" << results[f].family
      << "</text>\n";
  }
  for (std::size_t b = 0; b < builds.size(); ++b)
    s << "<rect x=\"" << left + 160 * b << "\" y=\"" << top + height + 95 << "\" width=\"10\" height=\"10\" fill=\""
      << colours[b % 3] << "\"/><text x=\"" << left + 160 * b + 14 << "\" y=\"" << top + height + 104 << "\">"
      << builds[b].name << "</text>\n";
  s << "</svg>\n";
  return s.str();
}

std::string markdown(const std::vector<FamilyResult>& results, const std::vector<Build>& builds,
                     const RobustnessOptions& o) {
  std::ostringstream s;
  s << "# Robustness: the exact build against floating-point builds of itself\n\n"
    << "Each case is a sketch written by the family (deterministic in the seed); each build generates it in a child\n"
    << "process limited to " << o.time_limit << " s, on one thread. A case passes when the build exits 0 and its output\n"
    << "passes the GEOS judge and the exact build's `exacity validate`. Failures: crash (a signal, or exit 3: a\n"
    << "failed CGAL precondition or internal check), hang (over the limit), error (another exit code), rejected\n"
    << "(the judge's or the validator's kinds, in brackets). The time ratio is the exact build's median time over\n"
    << "the other's on the cases both passed (— where none did: a crash's time says nothing of the cost).\n\n"
    << "| family | cases |";
  for (const Build& b : builds) s << " " << b.name << " passed | " << b.name << " failures |";
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
  s << "\n![failure rate by family](robustness.svg)\n\nReproduce (release preset, which builds the float programs too):\n\n"
    << "```\ncmake --workflow --preset release\nbuild/release/cli/exacity bench robustness --cases " << o.cases
    << " --seed " << o.seed << "\n```\n\nFamilies:\n\n";
  for (const Family& f : families()) s << "- `" << f.name << "`: " << f.about << "\n";
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
};

// Every (family, case) in a fixed order; results land by index, whatever order they finish in.
std::vector<Job> case_jobs(std::size_t families, int cases) {
  std::vector<Job> jobs;
  for (std::size_t f = 0; f < families; ++f)
    for (int i = 0; i < cases; ++i) jobs.push_back({f, i});
  return jobs;
}

// Every build on one case; returns its progress line. Passed outputs are removed unless kept.
std::string run_job(const RobustnessOptions& o, const std::string& family, int index, const std::vector<Build>& builds,
                    std::vector<Result>& results) {
  const fs::path dir = o.out / "cases" / family / std::to_string(index);
  fs::create_directories(dir);
  const fs::path sketch = dir / "sketch.geojson";
  std::ofstream(sketch, std::ios::binary) << family_sketch(family, index, o.seed);
  bool all_passed = true;
  std::ostringstream line;
  line << family << " " << index << ":";
  for (std::size_t b = 0; b < builds.size(); ++b) {
    Result r = run_case(builds[b], o.programs / "exacity", sketch, dir, o.time_limit);
    static const char* words[] = {"passed", "crash", "hang", "error", "rejected"};
    line << " " << builds[b].name << " " << words[r.kind];
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
                                          const std::vector<Job>& jobs, const std::vector<Build>& builds,
                                          std::ostream& log) {
  std::vector<std::vector<Result>> results(jobs.size(), std::vector<Result>(builds.size()));
  fs::create_directories(o.out);
  std::atomic<std::size_t> next{0};
  std::mutex log_mutex;
  auto work = [&] {
    for (std::size_t j; (j = next++) < jobs.size();) {
      const std::string line = run_job(o, names[jobs[j].family], jobs[j].index, builds, results[j]);
      std::lock_guard<std::mutex> lock(log_mutex);
      log << line << "\n" << std::flush;
    }
  };
  const int threads = o.jobs > 0 ? o.jobs : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
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

std::vector<FamilyResult> summarise(const std::vector<std::string>& names, const std::vector<Job>& jobs,
                                    const std::vector<Build>& builds, const std::vector<std::vector<Result>>& results) {
  std::vector<FamilyResult> out;
  for (std::size_t f = 0; f < names.size(); ++f) {
    FamilyResult fr{names[f], {}, {}};
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
                                       const std::vector<FamilyResult>& out) {
  nlohmann::ordered_json doc = {{"seed", o.seed}, {"cases_per_family", o.cases}, {"time_limit_s", o.time_limit}};
  for (const Build& b : builds) doc["builds"][b.name] = b.program.filename().string();
  doc["families"] = nlohmann::ordered_json::array();
  for (const FamilyResult& f : out) {
    nlohmann::ordered_json entry = {{"family", f.family}, {"cases", f.builds.front().second.cases}};
    for (std::size_t b = 0; b < f.builds.size(); ++b) {
      entry[f.builds[b].first] = to_json(f.builds[b].second);
      if (b > 0) entry[f.builds[b].first]["exact_over_this_time"] = f.time_ratio[b - 1] > 0 ? nlohmann::ordered_json(f.time_ratio[b - 1]) : nullptr;
    }
    doc["families"].push_back(entry);
  }
  return doc;
}

void write_reports(const RobustnessOptions& o, const std::vector<Build>& builds, const std::vector<FamilyResult>& out) {
  const nlohmann::ordered_json doc = robustness_json(o, builds, out);
  std::ofstream(o.out / "robustness.json", std::ios::binary) << doc.dump(2) << "\n";
  std::ofstream(o.out / "robustness.md", std::ios::binary) << markdown(out, builds, o);
  std::ofstream(o.out / "robustness.svg", std::ios::binary) << svg_chart(out, builds);
}

}  // namespace

std::vector<FamilyResult> run_robustness(const RobustnessOptions& o, std::ostream& log) {
  const std::vector<Build> builds = builds_in(o, log);
  const std::vector<std::string> names = family_names(o);
  const std::vector<Job> jobs = case_jobs(names.size(), o.cases);
  const std::vector<std::vector<Result>> results = run_jobs(o, names, jobs, builds, log);
  std::vector<FamilyResult> out = summarise(names, jobs, builds, results);
  write_reports(o, builds, out);
  return out;
}

}  // namespace exacity::bench
