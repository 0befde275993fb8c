// The row of a choice table (road layouts, lot layouts, placers) that the program names
// itself; a name from the sketch goes through SettingsReader::row, which refuses it in the
// user's terms.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace exacity {

template <class Row>
const Row& named_row(const std::vector<Row>& table, std::string_view name, const char* what) {
  for (const Row& r : table)
    if (r.name == name) return r;
  throw std::logic_error(std::string("no ") + what + " " + std::string(name));
}

}  // namespace exacity
