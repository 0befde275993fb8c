#include "generate/export/geojson.h"
#include "generate/export/geojson_written.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>

#include "generate/cancel.h"
#include "generate/errors.h"
#include "generate/export/cancellable_file.h"
#include "generate/export/read_lines.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

void write_position(std::ostream& out, geom::Vec2 p) {
  out << '[' << format_number(p.x) << ',' << format_number(p.y) << ']';
}

void write_ring(std::ostream& out, const geom::Ring& r) {
  out << '[';
  for (const geom::Vec2& p : r) write_position(out, p), out << ',';
  write_position(out, r.front());
  out << ']';
}

}  // namespace

namespace {

void write_layer(const Layer& layer, const nlohmann::ordered_json& crs, const fs::path& file, bool points) {
  std::ofstream out(file, std::ios::binary);
  if (!out) throw UserError(file.string() + ": cannot write this file; check the output folder's permissions");
  out << "{\"type\":\"FeatureCollection\",\"name\":" << json(layer.name).dump();
  if (!crs.is_null()) out << ",\"crs\":" << crs.dump();
  out << ",\"features\":[";
  const CancelCheck cancel;
  for (std::size_t i = 0; i < layer.features.size(); ++i) {
    cancel.check();
    const VectorFeature& f = layer.features[i];
    out << (i ? ",\n" : "\n") << "{\"type\":\"Feature\",\"properties\":" << f.properties.dump()
        << ",\"geometry\":{\"type\":";
    if (points) {
      out << "\"Point\",\"coordinates\":";
      write_position(out, f.line.at(0));
      out << "}}";
      continue;
    }
    if (layer.lines) {
      out << "\"LineString\",\"coordinates\":[";
      for (std::size_t k = 0; k < f.line.size(); ++k) out << (k ? "," : ""), write_position(out, f.line[k]);
    } else {
      out << "\"Polygon\",\"coordinates\":[";
      write_ring(out, f.polygon.outer);
      for (const geom::Ring& h : f.polygon.holes) out << ',', write_ring(out, h);
    }
    out << "]}}";
  }
  out << "\n]}\n";
  if (!out) throw UserError(file.string() + ": write failed (disk full?)");
}

}  // namespace

void write_geojson(const Layer& layer, const nlohmann::ordered_json& crs, const fs::path& file) {
  write_layer(layer, crs, file, false);
}

void write_point_geojson(const Layer& layer, const nlohmann::ordered_json& crs, const fs::path& file) {
  write_layer(layer, crs, file, true);
}

namespace {

// One element of a FeatureCollection's "features" as a VectorFeature; false (with the
// problem appended) when it is malformed or of a geometry type no layer holds.
bool read_feature(const json& f, const std::string& where, Layer& layer, VectorFeature& vf,
                  std::vector<std::string>& problems) {
  auto position = [](const json& p) { return geom::Vec2{p.at(0).get<double>(), p.at(1).get<double>()}; };
  try {
    vf.properties = f.at("properties");
    const json& g = f.at("geometry");
    std::string type = g.at("type");
    const json& c = g.at("coordinates");
    if (type == "Point") {
      vf.line = {position(c)};
    } else if (type == "LineString") {
      layer.lines = true;
      for (const json& p : c) vf.line.push_back(position(p));
    } else if (type == "Polygon") {
      bool closed = true;
      auto ring = [&](const json& r) {
        geom::Ring ring;
        for (const json& p : r) ring.push_back(position(p));
        if (ring.size() < 4 || !(ring.front() == ring.back())) closed = false;
        else ring.pop_back();
        return ring;
      };
      vf.polygon.outer = ring(c.at(0));
      for (std::size_t k = 1; k < c.size(); ++k) vf.polygon.holes.push_back(ring(c[k]));
      if (!closed) {
        problems.push_back(where + ": a ring is not closed or has fewer than 4 positions");
        return false;
      }
    } else {
      problems.push_back(where + ": unexpected geometry type " + type);
      return false;
    }
    return true;
  } catch (const json::exception& e) {
    problems.push_back(where + ": malformed feature (" + e.what() + ")");
    return false;
  }
}

// The layout write_layer writes, read by a scanner of its own: a first line ending in
// "features":[, one feature a line (each but the last followed by a comma), then "]}".
// nlohmann's parser spent most of validation's reading in its lexer and in a JSON value per
// number; here each feature's properties alone go through it, and numbers through
// from_chars, as that parser reads them (an integer as an integer, then as a double: "-0" is
// 0; others correctly rounded, as strtod rounds). Anything else (another writer's spacing, a
// tampered or malformed feature, a ring not closed) is not this layout: nullopt, and the
// caller reads the file with nlohmann's parser, which names what is wrong.
class WrittenLayout {
 public:
  explicit WrittenLayout(std::string_view line) : p_(line.data()), end_(line.data() + line.size()) {}

  // One feature line: the feature, and whether a comma followed it.
  bool feature(Layer& layer, VectorFeature& f, bool& comma) {
    if (!literal(R"({"type":"Feature","properties":)")) return false;
    const char* const start = p_;
    if (!plain_object(f.properties)) {
      p_ = start;
      if (!skip_object()) return false;
      // Through nlohmann::json, as the parser below reads them: its keys in its order.
      const json properties = json::parse(start, p_, nullptr, false);
      if (!properties.is_object()) return false;
      f.properties = properties;
    }
    if (!literal(R"(,"geometry":{"type":)")) return false;
    if (literal(R"("Polygon","coordinates":[)")) {
      // The outer ring, then the holes, each closed (its last position its first, dropped).
      auto ring = [&](geom::Ring& r) {
        if (!positions(r) || r.size() < 4 || !(r.front() == r.back())) return false;
        r.pop_back();
        return true;
      };
      if (!ring(f.polygon.outer)) return false;
      while (literal(",")) {
        f.polygon.holes.emplace_back();
        if (!ring(f.polygon.holes.back())) return false;
      }
      if (!literal("]")) return false;
    } else if (literal(R"("LineString","coordinates":)")) {
      layer.lines = true;
      if (!literal("[]") && !positions(f.line)) return false;
    } else if (literal(R"("Point","coordinates":)")) {
      f.line.emplace_back();
      if (!position(f.line.back())) return false;
    } else {
      return false;
    }
    if (!literal("}}")) return false;
    comma = literal(",");
    return p_ == end_;
  }

 private:
  bool literal(std::string_view s) {
    if (static_cast<std::size_t>(end_ - p_) < s.size() || std::string_view(p_, s.size()) != s) return false;
    p_ += s.size();
    return true;
  }

  // A properties object of plain values, as json::parse reads it into nlohmann::json and
  // ordered_json then holds it (keys sorted, as json's map sorts them), built straight from
  // the text: nlohmann's lexer and a map node per key were most of validation's reading.
  // Plain: no spaces, strings of printable ASCII without escapes, numbers, true, false,
  // null, and arrays of these; anything else (a nested object, an escape, a repeated key,
  // a number out of range) is false, and nlohmann's parser reads the object as before.
  bool plain_object(nlohmann::ordered_json& out) {
    if (!literal("{")) return false;
    members_.clear();
    if (!literal("}")) {
      do {
        std::string_view key;
        if (!plain_string(key) || !literal(":")) return false;
        members_.emplace_back(key, nlohmann::ordered_json());
        if (!plain_value(members_.back().second, true)) return false;
      } while (literal(","));
      if (!literal("}")) return false;
    }
    std::sort(members_.begin(), members_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 1; i < members_.size(); ++i)
      if (members_[i - 1].first == members_[i].first) return false;
    out = nlohmann::ordered_json::object();
    auto& object = out.get_ref<nlohmann::ordered_json::object_t&>();
    object.reserve(members_.size());
    for (auto& [key, value] : members_) object.emplace_back(std::string(key), std::move(value));
    return true;
  }

  bool plain_value(nlohmann::ordered_json& v, bool array_allowed) {
    if (p_ == end_) return false;
    if (*p_ == '"') {
      std::string_view text;
      if (!plain_string(text)) return false;
      v = std::string(text);
    } else if (literal("true")) {
      v = true;
    } else if (literal("false")) {
      v = false;
    } else if (literal("null")) {
      v = nullptr;
    } else if (array_allowed && literal("[")) {
      v = nlohmann::ordered_json::array();
      if (literal("]")) return true;
      do {
        nlohmann::ordered_json element;
        if (!plain_value(element, false)) return false;
        v.push_back(std::move(element));
      } while (literal(","));
      return literal("]");
    } else {
      return plain_number(v);
    }
    return true;
  }

  bool plain_string(std::string_view& text) {
    if (!literal("\"")) return false;
    const char* const from = p_;
    for (; p_ < end_ && *p_ != '"'; ++p_)
      if (*p_ == '\\' || static_cast<unsigned char>(*p_) < 0x20 || static_cast<unsigned char>(*p_) >= 0x80) return false;
    if (p_ == end_) return false;
    text = std::string_view(from, static_cast<std::size_t>(p_ - from));
    ++p_;
    return true;
  }

  // A number of JSON's grammar as nlohmann's lexer types it: an integer as a signed one when
  // it has a minus sign, else unsigned; anything with a fraction or an exponent as a double
  // (correctly rounded, as strtod rounds).
  bool plain_number(nlohmann::ordered_json& v) {
    const char* const start = p_;
    bool integer = true;
    if (!number_text(integer)) return false;
    if (integer && *start == '-') {
      std::int64_t i = 0;
      const auto [end, ec] = std::from_chars(start, p_, i);
      if (ec != std::errc() || end != p_) return false;
      v = i;
    } else if (integer) {
      std::uint64_t u = 0;
      const auto [end, ec] = std::from_chars(start, p_, u);
      if (ec != std::errc() || end != p_) return false;
      v = u;
    } else {
      double d = 0;
      const auto [end, ec] = std::from_chars(start, p_, d);
      if (ec != std::errc() || end != p_) return false;
      v = d;
    }
    return true;
  }

  // Past a JSON object's closing brace, strings' braces and escapes left alone; the parser
  // then decides whether it is one.
  bool skip_object() {
    int depth = 0;
    bool in_string = false;
    for (; p_ < end_; ++p_) {
      const char c = *p_;
      if (in_string) {
        if (c == '\\') ++p_;
        else if (c == '"') in_string = false;
      } else if (c == '"') {
        in_string = true;
      } else if (c == '{' || c == '[') {
        ++depth;
      } else if (c == '}' || c == ']') {
        if (--depth == 0) return ++p_, true;
      }
    }
    return false;
  }

  // "[[x,y],[x,y],...]", at least one position.
  bool positions(std::vector<geom::Vec2>& out) {
    if (!literal("[")) return false;
    do {
      out.emplace_back();
      if (!position(out.back())) return false;
    } while (literal(","));
    return literal("]");
  }

  bool position(geom::Vec2& v) { return literal("[") && number(v.x) && literal(",") && number(v.y) && literal("]"); }

  // A JSON number as nlohmann's parser gives it to get<double>().
  bool number(double& v) {
    const char* const start = p_;
    bool integer = true;
    if (!number_text(integer)) return false;
    if (integer) {
      if (*start == '-') {
        std::int64_t i = 0;
        if (std::from_chars(start, p_, i).ec == std::errc()) return v = static_cast<double>(i), true;
      } else {
        std::uint64_t u = 0;
        if (std::from_chars(start, p_, u).ec == std::errc()) return v = static_cast<double>(u), true;
      }
    }
    return std::from_chars(start, p_, v).ec == std::errc();
  }

  // Past a number of JSON's grammar; `integer`: whether it has neither a fraction nor an
  // exponent.
  bool number_text(bool& integer) {
    if (p_ < end_ && *p_ == '-') ++p_;
    if (p_ < end_ && *p_ == '0') ++p_;
    else if (!digits()) return false;
    if (p_ < end_ && *p_ == '.') {
      ++p_, integer = false;
      if (!digits()) return false;
    }
    if (p_ < end_ && (*p_ == 'e' || *p_ == 'E')) {
      ++p_, integer = false;
      if (p_ < end_ && (*p_ == '+' || *p_ == '-')) ++p_;
      if (!digits()) return false;
    }
    return true;
  }

  bool digits() {
    const char* const from = p_;
    while (p_ < end_ && *p_ >= '0' && *p_ <= '9') ++p_;
    return p_ != from;
  }

  const char* p_;
  const char* const end_;
  std::vector<std::pair<std::string_view, nlohmann::ordered_json>> members_;  // plain_object's
};

// Whether `line` is the written layout's first: with the array closed, a whole object whose
// last member is "features".
bool written_head(std::string_view line) {
  if (!line.ends_with(R"("features":[)")) return false;
  const json head = json::parse(std::string(line) + "]}", nullptr, false);
  return head.is_object() && head.contains("features") && head["features"].empty();
}

}  // namespace

std::optional<Layer> read_written_geojson(const fs::path& file) {
  CancellableInput in(file);
  std::string line;
  if (!in || !std::getline(in, line) || !written_head(line)) return std::nullopt;
  Layer layer;
  layer.name = file.stem().string();
  const CancelCheck cancel;
  bool more = true;  // a comma after the last feature: another follows
  while (std::getline(in, line)) {
    if (line == "]}") {
      if (more && !layer.features.empty()) return std::nullopt;
      more = false;
      break;
    }
    cancel.check();
    if (!more) return std::nullopt;
    VectorFeature f;
    if (!WrittenLayout(line).feature(layer, f, more)) return std::nullopt;
    layer.features.push_back(std::move(f));
  }
  if (more || std::getline(in, line) || !in.eof()) return std::nullopt;
  return layer;
}

namespace {

// Each feature is taken out of the parse as soon as it is read and dropped from the
// document, so no more than one feature's JSON is held at once (a whole layer's document
// takes several times its text's size).
Layer read_whole(const fs::path& file, std::istream& in, std::vector<std::string>& problems) {
  Layer layer;
  layer.name = file.stem().string();
  const std::size_t problems_before = problems.size();
  const CancelCheck cancel;
  std::string key;           // the top-level member being read
  bool in_features = false;  // within the top-level "features" array
  std::size_t index = 0;     // the next feature's
  auto feature_read = [&](int depth, json::parse_event_t event, json& parsed) {
    if (depth == 1 && event == json::parse_event_t::key) key = parsed.get<std::string>();
    if (depth == 1 && event == json::parse_event_t::array_start && key == "features") {
      // A later "features" member replaces an earlier one, as in the parsed document.
      in_features = true, index = 0, layer.lines = false, layer.features.clear(), problems.resize(problems_before);
      return true;
    }
    if (depth == 1 && event == json::parse_event_t::array_end) in_features = false;
    if (!in_features || depth != 2 ||
        (event != json::parse_event_t::object_end && event != json::parse_event_t::array_end &&
         event != json::parse_event_t::value))
      return true;
    cancel.check();
    VectorFeature vf;
    if (read_feature(parsed, file.filename().string() + ": features[" + std::to_string(index++) + "]", layer, vf, problems))
      layer.features.push_back(std::move(vf));
    return false;  // read: not kept in the document
  };
  json doc = json::parse(in, feature_read, false);
  if (doc.is_discarded() || !doc.is_object() || !doc.contains("features") || !doc["features"].is_array()) {
    problems.resize(problems_before);
    problems.push_back(file.string() + ": not a GeoJSON FeatureCollection");
    layer.lines = false, layer.features.clear();
    return layer;
  }
  return layer;
}

// `text` read line by line as write_layer lays it out, each line not in `known` by the
// written layout's scanner, or nothing when it is laid out otherwise (the whole reading
// then says what is wrong, as it would have).
std::optional<Layer> read_by_line(const fs::path& file, const std::string& text, ReadLines& known) {
  std::size_t end = text.find('\n');
  if (end == std::string::npos || !written_head(std::string_view(text.data(), end))) return std::nullopt;
  Layer layer;
  layer.name = file.stem().string();
  ReadLines now;
  const CancelCheck cancel;
  bool more = true;  // the line before ended in a comma, or was the first
  for (std::size_t at = end + 1, index = 0;; ++index) {
    if (index % 1024 == 0) cancel.check();
    end = text.find('\n', at);
    if (end == std::string::npos) return std::nullopt;
    std::string_view line(text.data() + at, end - at);
    at = end + 1;
    if (line == "]}") {
      if ((index > 0 && more) || text.find_first_not_of(" \t\r\n", at) != std::string::npos) return std::nullopt;
      break;
    }
    if (!more) return std::nullopt;
    more = line.ends_with(',');
    if (more) line.remove_suffix(1);
    auto read = now.by_text.find(line);
    if (read == now.by_text.end()) {
      if (auto was = known.by_text.find(line); was != known.by_text.end()) {
        read = now.by_text.insert(known.by_text.extract(was)).position;
        ++now.reused;
      } else {
        Layer kind;
        VectorFeature vf;
        bool comma = false;  // taken off above
        if (!WrittenLayout(line).feature(kind, vf, comma)) return std::nullopt;
        read = now.by_text.emplace(std::string(line), ReadLines::Read{std::move(vf), kind.lines}).first;
        ++now.parsed;
      }
    } else {
      ++now.reused;
    }
    layer.lines |= read->second.line_string;
    layer.features.push_back(read->second.feature);
  }
  known = std::move(now);
  return layer;
}

}  // namespace

Layer read_geojson(const fs::path& file, std::vector<std::string>& problems) {
  if (std::optional<Layer> layer = read_written_geojson(file)) return std::move(*layer);
  CancellableInput in(file);
  if (!in) {
    problems.push_back(file.string() + ": missing");
    Layer layer;
    layer.name = file.stem().string();
    return layer;
  }
  return read_whole(file, in, problems);
}

Layer read_geojson(const fs::path& file, std::vector<std::string>& problems, ReadLines& known) {
  std::string text;
  {
    CancellableInput in(file);
    if (!in) return read_geojson(file, problems);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (std::optional<Layer> layer = read_by_line(file, text, known)) return std::move(*layer);
  known = {};
  std::istringstream in(text);
  return read_whole(file, in, problems);
}

}  // namespace exacity
