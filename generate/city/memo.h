// A cache of one pure computation's results by the whole of its input written out (a key),
// for regenerating a city from an edited sketch (docs/design.md, Regions and regenerating).
// Equal keys give the value computed before, so reusing it changes no output byte; a key
// must therefore hold everything the computation reads, written exactly.
#pragma once

#include <cstdio>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "generate/city/features.h"
#include "geom/hex_text.h"
#include "geom/plain.h"

namespace exacity {

template <typename Value>
class Memo {
 public:
  // The value for `key`, computed by `compute` when no build since the last `next_build`
  // but one has asked for it. Threads may ask at once; two computing one key compute the
  // same value.
  template <typename Compute>
  Value get(const std::string& key, Compute&& compute) {
    {
      const std::lock_guard lock(mutex_);
      if (auto it = entries_.find(key); it != entries_.end()) {
        it->second.build = build_;
        ++hits_;
        return it->second.value;
      }
    }
    if (others)
      if (std::optional<Value> stand_in = others(key)) return *std::move(stand_in);
    Value value = compute();
    const std::lock_guard lock(mutex_);
    ++misses_;
    entries_.insert_or_assign(key, Entry{value, build_});
    return value;
  }
  // Starts a build whose items share `context` (what every key would hold: the settings,
  // the sketch roads), which a key then leaves out: a new context forgets everything. Else
  // it forgets what the last build did not ask for, so the cache holds one city's worth.
  // Hits and misses are counted afresh.
  void next_build(const std::string& context) {
    const std::lock_guard lock(mutex_);
    if (context != context_) entries_.clear();
    for (auto it = entries_.begin(); it != entries_.end();)
      it = it->second.build < build_ ? entries_.erase(it) : std::next(it);
    context_ = context;
    ++build_;
    hits_ = misses_ = 0;
  }
  // Puts `key`'s value as if this build had computed it (a plan's merge loads its tasks'
  // items so: generate/plan/plan.h). Call after next_build.
  void put(std::string key, Value value) {
    const std::lock_guard lock(mutex_);
    entries_.insert_or_assign(std::move(key), Entry{std::move(value), build_});
  }
  // Visits every entry held, in no particular order.
  template <typename Visit>
  void for_each(Visit&& visit) const {
    const std::lock_guard lock(mutex_);
    for (const auto& [key, entry] : entries_) visit(key, entry.value);
  }
  // Keys another process computes (a plan's task leaves the other tasks' items to them):
  // for such a key, when not held, `others` gives a value that stands in for it, neither
  // computed nor kept nor counted; nullopt for the keys to compute here. Called from many
  // threads at once.
  std::function<std::optional<Value>(const std::string&)> others;

  int hits() const { return hits_; }
  int misses() const { return misses_; }

 private:
  struct Entry {
    Value value;
    long build;
  };
  mutable std::mutex mutex_;
  std::string context_;
  std::unordered_map<std::string, Entry> entries_;
  long build_ = 0;
  int hits_ = 0, misses_ = 0;
};

// Writes numbers into a key exactly: a double as a hex float, printf's %a text and a space
// (made by to_chars: printf was about 3% of answering an edit, which keys every structure).
inline void append_key(std::string& key, double v) { geom::append_hex_text(key, v); }
inline void append_key(std::string& key, const geom::Ring& ring) {
  key += "ring ";
  for (geom::Vec2 p : ring) append_key(key, p.x), append_key(key, p.y);
}
inline void append_key(std::string& key, const geom::Polygon& polygon) {
  append_key(key, polygon.outer);
  for (const geom::Ring& hole : polygon.holes) key += "hole ", append_key(key, hole);
}

// The drawn zones whose outer rings' box meets `box` (grown by a metre, as a cell's box is
// rounded), in drawing order: all that says which zone lies at any point of the box.
inline void append_zones_over(std::string& key, const std::vector<ZoneFeature>& zones, geom::Box box) {
  box.min_x -= 1, box.min_y -= 1, box.max_x += 1, box.max_y += 1;
  for (const ZoneFeature& zone : zones) {
    geom::Box drawn = geom::Box::none();
    for (const geom::Polygon& polygon : zone.polygons)
      for (geom::Vec2 p : polygon.outer) drawn.add(p);
    if (!drawn.meets(box)) continue;
    key += "zone " + std::to_string(static_cast<int>(zone.type)) + " ";
    for (const geom::Polygon& polygon : zone.polygons) append_key(key, polygon);
  }
}

}  // namespace exacity
