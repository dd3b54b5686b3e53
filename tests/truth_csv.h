// A synthetic sequence's truth/joints.csv (or effects.csv): a header of
// column names, then one row of numbers per frame; read into one series per
// column.
#pragma once

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace efc::test {

inline std::map<std::string, std::vector<double>> read_joints_csv(const std::string& path) {
  std::map<std::string, std::vector<double>> cols;
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> header;
  if (!std::getline(in, line)) return cols;
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ',');) header.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    size_t i = 0;
    for (std::string cell; std::getline(ls, cell, ','); ++i)
      if (i < header.size()) cols[header[i]].push_back(std::strtod(cell.c_str(), nullptr));  // stod throws on denormals
  }
  return cols;
}

}  // namespace efc::test
