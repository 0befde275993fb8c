// Doubles' shortest texts (append_number's), remembered for the large text exports.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cstdint>
#include <string>

namespace exacity {

// append_number for doubles, each text remembered by the double's bits in a small table
// (one per thread: it is not shared): a mesh's vertices repeat their coordinates (a prism's
// x and y at its ground and at its roof, its z at one of two heights), and a text looked up
// costs a fraction of one worked out. The same characters as append_number.
class NumberTexts {
 public:
  void append(std::string& s, double v) {
    if (v == 0) v = 0;  // no "-0"
    const auto bits = std::bit_cast<std::uint64_t>(v);
    Text& t = texts_[(bits * 0x9e3779b97f4a7c15ull) >> (64 - kBits)];
    if (t.length == 0 || t.bits != bits) {
      auto [end, ec] = std::to_chars(t.chars, t.chars + sizeof t.chars, v);
      t.bits = bits, t.length = static_cast<std::uint8_t>(end - t.chars);
    }
    s.append(t.chars, std::min<std::size_t>(t.length, sizeof t.chars));
  }

 private:
  static constexpr int kBits = 8;
  struct Text {
    std::uint64_t bits = 0;
    std::uint8_t length = 0;  // 0: none yet
    char chars[32];
  };
  std::array<Text, std::size_t{1} << kBits> texts_{};
};

}  // namespace exacity
