// Small CSV files read by the tests: the committed FE contact reference's rows
// (verification/data/fe_reference) and the program's numeric columns.
#pragma once

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace epicycle::test {

/// @throws std::runtime_error naming the file when it cannot be read.
inline std::vector<std::vector<std::string>> ReadCsvRows(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be read");
  std::vector<std::vector<std::string>> rows;
  std::string line;
  std::getline(f, line);
  while (std::getline(f, line)) {
    std::vector<std::string> row;
    std::stringstream s(line);
    for (std::string field; std::getline(s, field, ',');) row.push_back(field);
    rows.push_back(row);
  }
  return rows;
}

/// A CSV the program writes (its provenance lines, starting with '#', skipped; no quoting in
/// numeric files) as header name → the column's numbers (text cells left out). Fails the
/// reading (std::runtime_error naming the file and line) on a row whose field count is not the
/// header's.
inline std::map<std::string, std::vector<double>> ReadCsvColumns(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be read");
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> columns;
  std::string line;
  for (int number = 1; std::getline(f, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (line.back() == ',') cells.emplace_back();  // an empty last field
    if (names.empty()) {
      names = cells;
      continue;
    }
    if (cells.size() != names.size())
      throw std::runtime_error(path + ":" + std::to_string(number) + ": " +
                               std::to_string(cells.size()) + " fields under a header of " +
                               std::to_string(names.size()));
    for (std::size_t c = 0; c < cells.size(); ++c) {
      char* end = nullptr;
      const double v = std::strtod(cells[c].c_str(), &end);
      if (end != cells[c].c_str()) columns[names[c]].push_back(v);
    }
  }
  return columns;
}

}  // namespace epicycle::test
