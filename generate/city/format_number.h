// Numbers as Exacity writes them, in its files and its messages.
#pragma once

#include <algorithm>
#include <charconv>
#include <string>
#include <type_traits>

namespace exacity {

// Appends the shortest text that reads back as the same double.
inline void append_number(std::string& s, double v) {
  if (v == 0) v = 0;  // no "-0"
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, std::min(static_cast<std::size_t>(end - buf), sizeof buf));  // bounded for g++ 12's -Wstringop-overflow
}

// Appends an integer as a stream writes it (the large files' indices, without a stream's
// sentry and locale look-up for each number).
template <typename Integer>
  requires std::is_integral_v<Integer>
inline void append_number(std::string& s, Integer v) {
  char buf[24];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, std::min(static_cast<std::size_t>(end - buf), sizeof buf));
}

// Shortest text that reads back as the same double.
inline std::string format_number(double v) {
  std::string s;
  append_number(s, v);
  return s;
}

}  // namespace exacity
