#include "generate/plan/memo_text.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "geom/cell.h"
#include "geom/hex_text.h"

namespace exacity {
namespace {

// One list of fields per type serves both ways (fields() below), so what is written is
// what is read. Numbers are words ended by a space; a string is its length, ':' and its bytes.
class TextOut {
 public:
  std::string text;
  void operator()(double v) { geom::append_hex_text(text, v); }
  void operator()(long v) { text += std::to_string(v) + ' '; }
  void operator()(std::string_view s) { text += std::to_string(s.size()) + ':', text += s, text += ' '; }
};

class TextIn {
 public:
  explicit TextIn(std::string_view text) : text_(text) {}
  bool done() const { return at_ >= text_.size(); }
  std::string_view word() {
    const auto end = text_.find(' ', at_);
    if (end == std::string_view::npos || end == at_) fail();
    const std::string_view w = text_.substr(at_, end - at_);
    at_ = end + 1;
    return w;
  }
  double real() {
    const std::string w(word());
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (end != w.c_str() + w.size()) fail();
    return v;
  }
  long integer() {
    const std::string_view w = word();
    long v = 0;
    if (std::from_chars(w.data(), w.data() + w.size(), v).ptr != w.data() + w.size()) fail();
    return v;
  }
  std::string_view string() {
    const auto colon = text_.find(':', at_);
    if (colon == std::string_view::npos) fail();
    std::size_t n = 0;
    if (std::from_chars(text_.data() + at_, text_.data() + colon, n).ptr != text_.data() + colon) fail();
    // A space ends it, or a line's end (memo_text's lines).
    if (colon + 1 + n >= text_.size() || (text_[colon + 1 + n] != ' ' && text_[colon + 1 + n] != '\n')) fail();
    const std::string_view s = text_.substr(colon + 1, n);
    at_ = colon + 2 + n;
    return s;
  }
  [[noreturn]] void fail() const {
    throw std::invalid_argument("not an item's text at character " + std::to_string(at_));
  }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
};

// The one field: written from, or read into, `v`.
void field(TextOut& out, const double& v) { out(v); }
void field(TextIn& in, double& v) { v = in.real(); }
template <typename Int>
  requires(std::is_integral_v<Int> || std::is_enum_v<Int>)
void field(TextOut& out, const Int& v) { out(static_cast<long>(v)); }
template <typename Int>
  requires(std::is_integral_v<Int> || std::is_enum_v<Int>)
void field(TextIn& in, Int& v) { v = static_cast<Int>(in.integer()); }
void field(TextOut& out, const std::string& s) { out(std::string_view(s)); }
void field(TextIn& in, std::string& s) { s = in.string(); }
void field(TextOut& out, const geom::Cell& c) { out(std::string_view(geom::exact_text(c))); }
void field(TextIn& in, geom::Cell& c) { c = geom::cell_from_exact_text(in.string()); }
void field(TextOut& out, const geom::Path& p) { out(std::string_view(geom::exact_text(p))); }
void field(TextIn& in, geom::Path& p) { p = geom::path_from_exact_text(in.string()); }
template <typename T>
void field(TextOut& out, const std::optional<T>& v) {
  out(static_cast<long>(v.has_value()));
  if (v) field(out, *v);
}
template <typename T>
void field(TextIn& in, std::optional<T>& v) {
  v.reset();
  if (in.integer()) field(in, v.emplace());
}
template <typename T>
void field(TextOut& out, const std::vector<T>& list) {
  out(static_cast<long>(list.size()));
  for (const T& item : list) field(out, item);
}
template <typename T>
void field(TextIn& in, std::vector<T>& list) {
  const long n = in.integer();
  if (n < 0) in.fail();
  list.assign(static_cast<std::size_t>(n), T{});
  for (T& item : list) field(in, item);
}
template <typename T, std::size_t N>
void field(TextOut& out, const std::array<T, N>& a) {
  for (const T& item : a) field(out, item);
}
template <typename T, std::size_t N>
void field(TextIn& in, std::array<T, N>& a) {
  for (T& item : a) field(in, item);
}
template <typename A, typename B>
void field(TextIn& in, std::pair<A, B>& p) {
  field(in, p.first), field(in, p.second);
}
template <typename A, typename B>
void field(TextOut& out, const std::pair<A, B>& p) {
  field(out, p.first), field(out, p.second);
}

// Structs: each lists its fields once, in declaration order, for both ways.
template <typename IO, typename... Fields>
void fields(IO& io, Fields&... f) {
  (field(io, f), ...);
}
#define EXACITY_FIELDS(Type, ...)                                                      \
  [[maybe_unused]] void field(TextOut& io, const Type& v) { fields(io, __VA_ARGS__); } \
  [[maybe_unused]] void field(TextIn& io, Type& v) { fields(io, __VA_ARGS__); }

EXACITY_FIELDS(geom::Vec2, v.x, v.y)
EXACITY_FIELDS(geom::Polygon, v.outer, v.holes)
EXACITY_FIELDS(LaidRoad, v.path, v.width, v.road_class, v.level, v.piece)
EXACITY_FIELDS(Junction, v.at, v.first_road)
EXACITY_FIELDS(Terminal, v.kind, v.type, v.density)
EXACITY_FIELDS(PlannedUse, v.ring, v.use)
EXACITY_FIELDS(RoadPlan, v.roads, v.piece_reaches_sketch, v.junctions, v.uses, v.levels, v.cells_without_access,
               v.dropped_roads)
EXACITY_FIELDS(PlannedLot, v.block, v.zone, v.ring, v.cell, v.model)
EXACITY_FIELDS(BuildingPart, v.polygon, v.bottom, v.height, v.eaves, v.roof, v.roof_faces, v.osm_id, v.tag, v.mapped)
EXACITY_FIELDS(Building, v.id, v.stable_id, v.lot, v.zone, v.polygon, v.height, v.roof, v.eaves, v.roof_faces, v.base,
               v.floor, v.mapped, v.osm_id, v.building_tag, v.source_id, v.parts)
EXACITY_FIELDS(Placement, v.model, v.position, v.angle, v.scale, v.tint)
EXACITY_FIELDS(Slab, v.bottom, v.top, v.outline)
EXACITY_FIELDS(ModelInstance, v.id, v.stable_id, v.lot, v.zone, v.kind, v.polygon, v.placed, v.height, v.base, v.floor,
               v.slabs)
EXACITY_FIELDS(Structures, v.buildings, v.models)
#undef EXACITY_FIELDS

}  // namespace

template <typename Value>
std::string value_text(const Value& value) {
  TextOut out;
  field(out, value);
  return std::move(out.text);
}

template <typename Value>
Value value_from_text(std::string_view text) {
  TextIn in(text);
  Value value{};
  field(in, value);
  if (!in.done()) in.fail();
  return value;
}

template <typename Value>
std::string memo_text(const Memo<Value>& memo) {
  std::vector<std::pair<std::string, std::string>> lines;
  memo.for_each([&](const std::string& key, const Value& value) { lines.emplace_back(key, value_text(value)); });
  std::sort(lines.begin(), lines.end());
  TextOut out;
  for (const auto& [key, value] : lines) out(std::string_view(key)), out(std::string_view(value)), out.text.back() = '\n';
  return std::move(out.text);
}

template <typename Value>
void read_memo_text(std::string_view text, Memo<Value>& memo) {
  TextIn in(text);
  while (!in.done()) {
    std::string key(in.string());
    std::string value(in.string());
    memo.put(std::move(key), value_from_text<Value>(value));
  }
}

template std::string value_text(const RoadPlan&);
template std::string value_text(const std::vector<PlannedLot>&);
template std::string value_text(const Structures&);
template RoadPlan value_from_text(std::string_view);
template std::vector<PlannedLot> value_from_text(std::string_view);
template Structures value_from_text(std::string_view);
template std::string memo_text(const Memo<RoadPlan>&);
template std::string memo_text(const Memo<std::vector<PlannedLot>>&);
template std::string memo_text(const Memo<Structures>&);
template void read_memo_text(std::string_view, Memo<RoadPlan>&);
template void read_memo_text(std::string_view, Memo<std::vector<PlannedLot>>&);
template void read_memo_text(std::string_view, Memo<Structures>&);

}  // namespace exacity
