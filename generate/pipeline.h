// The generate job: sketch to every output, stage after stage (DESIGN.md, The pipeline).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "generate/sketch.h"

namespace exacity {

// Called as each stage starts: its position (1-based), the stage count, its name.
using ProgressFn = std::function<void(int, int, const std::string&)>;

struct GenerateResult {
  nlohmann::ordered_json report;  // as written to report.json
  bool valid = false;
};

// Writes every output into `dir`, which must exist and be empty.
GenerateResult generate_city(const Sketch& sketch, const std::filesystem::path& dir, const ProgressFn& progress);

inline constexpr const char* kVersion = "0.1.0";

}  // namespace exacity
