#include "io/csv.hpp"

#include <algorithm>
#include <sstream>

#include "io/files.hpp"

namespace twinflow::io {

int CsvTable::find(const std::string& name) const {
  const auto it = std::find(header.begin(), header.end(), name);
  return it == header.end() ? -1 : static_cast<int>(it - header.begin());
}

std::size_t CsvTable::column(const std::string& name, const std::string& source) const {
  const int k = find(name);
  if (k < 0) throw InputError(source + ": no column '" + name + "'");
  return static_cast<std::size_t>(k);
}

CsvTable parse_csv(const std::string& text, bool header) {
  CsvTable table;
  std::istringstream in(text);
  bool header_read = !header;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      table.comments += line + "\n";
      continue;
    }
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (!header_read) {
      table.header = std::move(cells);
      header_read = true;
    } else {
      table.rows.push_back(std::move(cells));
    }
  }
  return table;
}

} // namespace twinflow::io
