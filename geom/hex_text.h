// A double as C's %a text, made by std::to_chars: the same bytes as printf's, which cost
// most of writing the keys of an edit's memos and exact cells (generate/regenerate.h).
#pragma once

#include <charconv>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>

namespace geom {

// Appends v as printf("%a ") writes it (infinities and NaNs through printf itself).
inline void append_hex_text(std::string& out, double v) {
  char text[40];
  if (!std::isfinite(v)) {
    std::snprintf(text, sizeof text, "%a ", v);
    out += text;
    return;
  }
  char* at = text;
  if (std::signbit(v)) *at++ = '-';
  *at++ = '0', *at++ = 'x';
  at = std::to_chars(at, std::end(text), std::fabs(v), std::chars_format::hex).ptr;
  *at++ = ' ';
  out.append(text, at);
}

}  // namespace geom
