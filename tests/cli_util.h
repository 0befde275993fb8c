// Helpers for the tests that run the exacity program and the checkers in tests/.
#pragma once

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cli_util {

namespace fs = std::filesystem;

inline const fs::path kSource = EXACITY_SOURCE_DIR;

struct Result {
  int code;
  std::string out;  // stdout and stderr
};

// Runs a shell command line, stderr merged into stdout.
inline Result shell(const std::string& command) {
  Result r{0, ""};
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  std::array<char, 4096> buf;
  while (fgets(buf.data(), buf.size(), pipe)) r.out += buf.data();
  int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

#ifdef EXACITY_BINARY
inline Result run(const std::string& args) { return shell(std::string(EXACITY_BINARY) + " " + args); }
#endif

inline std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A validator from tests/js, which scripts/install-deps.sh installs with npm.
inline std::string node_tool(const std::string& script) {
  EXPECT_TRUE(fs::exists(kSource / "tests" / "js" / "node_modules")) << "run scripts/install-deps.sh to install tests/js";
  return "node " + (kSource / "tests" / "js" / script).string();
}

// The GEOS cross-check of an output folder's layers.
inline std::string geos_check(const fs::path& out) {
  return "/usr/bin/python3 " + (kSource / "tests" / "check_layers.py").string() + " " + out.string();
}

// Every example sketch, the grid maps in examples/grid and the extracts in examples/osm.
inline std::vector<fs::path> examples() {
  std::vector<fs::path> v;
  for (const auto& e : fs::directory_iterator(kSource / "examples"))
    if (e.path().extension() == ".geojson") v.push_back(e.path());
  for (const auto& e : fs::directory_iterator(kSource / "examples" / "grid"))
    if (e.path().extension() == ".grid") v.push_back(e.path());
  for (const auto& e : fs::directory_iterator(kSource / "examples" / "osm"))
    if (e.path().extension() == ".osm") v.push_back(e.path());
  std::sort(v.begin(), v.end());
  return v;
}

// The official CityJSON 2.0.2 schemas are in ../shared/data (not ours to commit).
inline fs::path cityjson_schemas() { return kSource / ".." / "shared" / "data" / "cityjson-2.0.2-schemas"; }

}  // namespace cli_util
