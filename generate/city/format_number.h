// Numbers as Exacity writes them, in its files and its messages.
#pragma once

#include <charconv>
#include <string>

namespace exacity {

// Shortest text that reads back as the same double.
inline std::string format_number(double v) {
  if (v == 0) v = 0;  // no "-0"
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, end);
}

}  // namespace exacity
