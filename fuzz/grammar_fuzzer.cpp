// A split grammar on any bytes, grown over a square root as a zone's layout would grow it:
// a tree of leaves or one UserError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_target.h"
#include "generate/layout/grammar.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  exacity::fuzz::expect_user_errors_only([&] {
    const exacity::Grammar grammar = exacity::parse_grammar(text, "fuzz.grammar");
    exacity::grow_layout(grammar, {{{0, 0}, {400, 0}, {400, 300}, {0, 300}}}, 8, 100, 1);
  });
  return 0;
}
