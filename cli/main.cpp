// The exacity command: options, progress, error reporting and exit codes (0 ok, 2 bad
// input, 3 failed internal check). The work itself lives in generate/.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include "cli/progress.h"
#include "generate/errors.h"
#include "generate/output_folder.h"
#include "generate/pipeline.h"
#include "generate/sketch.h"
#include "generate/validate.h"

namespace fs = std::filesystem;
using namespace exacity;

namespace {

int generate(const fs::path& sketch_path, const fs::path& out, bool quiet) {
  Sketch sketch = load_sketch(sketch_path);
  OutputFolder folder(out);
  GenerateResult result;
  {
    ProgressReport progress(quiet);
    result = generate_city(sketch, folder.staging(), [&](int i, int n, const std::string& stage) {
      progress.stage(i, n, stage);
    });
  }
  folder.commit();
  const auto& counts = result.report["counts"];
  std::printf("exacity: wrote %s (roads %d, blocks %d, lots %d, buildings %d); open %s\n", out.string().c_str(),
              counts["roads"].get<int>(), counts["blocks"].get<int>(), counts["lots"].get<int>(),
              counts["buildings"].get<int>(), (out / "map.svg").string().c_str());
  if (!result.valid) {
    for (const auto& p : result.report["validation"]["problems"])
      std::fprintf(stderr, "exacity: invalid output: %s\n", p.get<std::string>().c_str());
    throw InternalError("the generated city failed validation (see report.json); please report this sketch");
  }
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Exacity: a city sketch to a whole city, exactly."};
  app.set_version_flag("--version", std::string("exacity ") + kVersion);
  app.require_subcommand(1);
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "Hide progress");

  fs::path sketch_path, out = "out";
  auto* gen = app.add_subcommand("generate", "Generate a city from a GeoJSON sketch");
  gen->add_option("SKETCH", sketch_path, "The sketch (GeoJSON FeatureCollection)")->required();
  gen->add_option("-o,--output", out, "Output folder (replaced if an earlier exacity run wrote it)")
      ->capture_default_str();
  gen->add_flag("-q,--quiet", quiet, "Hide progress");
  int threads = 0;
  gen->add_option("--threads", threads, "Worker threads (0: one per core); the output does not depend on it")
      ->check(CLI::Range(0, 1024));

  fs::path check_dir;
  auto* val = app.add_subcommand("validate", "Re-check every invariant of an output folder exactly");
  val->add_option("OUT", check_dir, "An output folder of exacity generate")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
      limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
    if (*gen) return generate(sketch_path, out, quiet);
    if (*val) return validate(check_dir);
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
  return 0;
}
