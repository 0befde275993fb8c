// The robustness benchmark's judge: an output folder checked with GEOS (its C API), apart
// from Exacity's own exact validator, so that a bug in one is caught by the other.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace exacity::bench {

// What a judge rejects, by kind: "unreadable" (a layer missing or not GeoJSON), "invalid"
// (a polygon not valid by OGC rules), "overlap" (a tiling's parts cover more than their
// union), "gap" (drawn zones left uncovered), "label" (a zone written with another type than
// the sketch's zone on top there), "outside" (a lot outside its block, a building
// outside its lot), "network" (centre lines that cross between vertices, overlap, or fall
// apart into pieces of which some reach no road the sketch drew).
struct Verdict {
  std::map<std::string, int> rejected;  // kind -> how many problems
  std::vector<std::string> problems;    // one line each, the first few of every kind

  bool passed() const { return rejected.empty(); }
  void reject(const std::string& kind, const std::string& detail);
};

// Areas compare to 1e-9 of the areas involved, as the JTS/GEOS overlay tests do.
constexpr double kRelativeArea = 1e-9;

Verdict judge(const std::filesystem::path& out);

// What judge() checks, as data: the layers it reads, and each invariant with its kind, the
// layers it concerns and its tolerance (for `exacity bench robustness --export`).
nlohmann::ordered_json judge_invariants();

}  // namespace exacity::bench
