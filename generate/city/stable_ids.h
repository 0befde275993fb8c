// The ids the outputs write (docs/design.md, Regions and regenerating: ids): each feature's
// drawn from what it is as written (its kind, geometry and properties, not its ids or
// what it names), never from its place in a list, so that an edit leaves the ids, and so
// the lines, of every feature it does not reach as they were, and a full build of the
// edited sketch writes the same ids as the build that reused them.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <numeric>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "generate/city/random.h"
#include "geom/plain.h"

namespace exacity {

// A 64-bit hash of a feature's content, fed value by value (doubles by their bits).
class ContentHash {
 public:
  explicit ContentHash(std::uint64_t kind) : h_(mix(kind)) {}
  ContentHash& add(std::uint64_t v) {
    h_ = mix(h_, v);
    return *this;
  }
  ContentHash& add(double v) { return add(std::bit_cast<std::uint64_t>(v == 0 ? 0.0 : v)); }  // -0 as 0
  ContentHash& add(int v) { return add(static_cast<std::uint64_t>(static_cast<std::int64_t>(v))); }
  ContentHash& add(std::string_view text) { return add(content_id(text)); }
  ContentHash& add(geom::Vec2 p) { return add(p.x).add(p.y); }
  ContentHash& add(const std::vector<geom::Vec2>& points) {
    add(static_cast<std::uint64_t>(points.size()));
    for (geom::Vec2 p : points) add(p);
    return *this;
  }
  ContentHash& add(const geom::Polygon& polygon) {
    add(polygon.outer);
    for (const geom::Ring& hole : polygon.holes) add(hole);
    return *this;
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_;
};

inline constexpr std::uint32_t kStableIds = 1u << 31;  // ids are 0 .. 2^31 - 1: an int in every reader

// Ids for features of one numbering from their content hashes: each the top 31 bits of its
// hash, or where two meet, the next free one, given in the order of the whole hashes (the
// index where two hashes are equal, as their features then are), so the ids depend on the
// set of features, not their order. Two of n features meet with a chance of about
// n^2 / 2^32; then the one later in that order takes another id.
inline std::vector<int> stable_ids(const std::vector<std::uint64_t>& hashes) {
  std::vector<std::size_t> order(hashes.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return hashes[a] != hashes[b] ? hashes[a] < hashes[b] : a < b;
  });
  std::vector<int> ids(hashes.size());
  std::unordered_set<std::uint32_t> taken;
  taken.reserve(hashes.size());
  for (std::size_t i : order) {
    std::uint32_t id = static_cast<std::uint32_t>(hashes[i] >> 33);
    while (!taken.insert(id).second) id = (id + 1) % kStableIds;
    ids[i] = static_cast<int>(id);
  }
  return ids;
}

}  // namespace exacity
