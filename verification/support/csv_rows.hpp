// The rows of a small CSV file as fields (no quoting; the header row dropped): the committed FE
// contact reference (verification/data/fe_reference) read by the tests and the figure writer.
#pragma once

#include <fstream>
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

}  // namespace epicycle::test
