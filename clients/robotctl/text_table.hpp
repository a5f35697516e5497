// A plain-text table: a heading row, then rows, each column as wide as its widest cell.
#pragma once

#include <string>
#include <vector>

namespace robotctl {

class TextTable {
 public:
  explicit TextTable(std::vector<std::string> headings);

  /// Missing cells print empty; cells beyond the headings are dropped.
  void add_row(std::vector<std::string> cells);
  bool empty() const { return rows_.empty(); }
  /// Columns two spaces apart, every line ending in '\n', no trailing spaces.
  std::string render() const;

 private:
  std::vector<std::string> headings_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace robotctl
