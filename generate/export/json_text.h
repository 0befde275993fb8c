// JSON written as text directly, the same bytes nlohmann's dump() gives the same values:
// the large exports make their many small arrays this way rather than as JSON values.
#pragma once

#include <cmath>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace exacity {

// A double as nlohmann's dump() writes it (Grisu2, "1.0" for whole numbers, null when not
// finite). Not append_number's shortest round trip, which writes 1 for 1.0.
inline void append_json_number(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  char buf[64];
  const char* end = nlohmann::detail::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, static_cast<std::size_t>(end - buf));
}

// A string as dump() writes it: quoted, escaped where JSON needs it.
inline void append_json_string(std::string& out, std::string_view s) {
  for (char c : s)
    if (c < 0x20 || c > 0x7e || c == '"' || c == '\\') {
      out += nlohmann::json(std::string(s)).dump();
      return;
    }
  out += '"', out += s, out += '"';
}

}  // namespace exacity
