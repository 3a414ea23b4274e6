#pragma once
// CSV text as twinflow writes it: '#' comment lines, one header row, then rows of cells split at
// commas (no quoting: twinflow's cells never hold a comma). The one reader of that layout.

#include <string>
#include <vector>

namespace twinflow::io {

struct CsvTable {
  std::string comments; // the '#' lines, each with its newline
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  int find(const std::string& name) const; // the column's index, -1 when absent
  // The column's index; an InputError naming `source` and the column when absent.
  std::size_t column(const std::string& name, const std::string& source) const;
};

// Empty lines are skipped. header = false: every line that is not a comment is a row.
CsvTable parse_csv(const std::string& text, bool header = true);

} // namespace twinflow::io
