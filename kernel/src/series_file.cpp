#include "talus/series_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "talus/error.hpp"
#include "text.hpp"

namespace talus {

namespace {

std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  return cells;
}

// The file's complete lines after the comments: the header first.
std::vector<std::string> data_lines(const std::string& path, bool& readable) {
  std::string text;
  readable = text::read_file(path, text);
  if (!text.empty() && text.back() != '\n') text.erase(text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1);
  std::vector<std::string> lines;
  std::stringstream all(text);
  std::string line;
  while (std::getline(all, line))
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  return lines;
}

}  // namespace

std::vector<std::string> series_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);  // up to the header only: the rows can be long
  std::string line;
  while (std::getline(in, line) && (line.empty() || line[0] == '#')) {
  }
  return in && !line.empty() && line[0] != '#' ? split_row(line) : std::vector<std::string>{};
}

std::vector<std::vector<double>> read_series(const std::string& path, const std::vector<std::string>& columns) {
  bool readable = false;
  const auto lines = data_lines(path, readable);
  if (!readable) throw RunError(path + ": cannot open: " + std::strerror(errno));
  const auto header = lines.empty() ? std::vector<std::string>{} : split_row(lines.front());
  std::vector<std::size_t> index;
  for (const auto& name : columns) {
    const auto at = std::find(header.begin(), header.end(), name);
    if (at == header.end()) throw RunError(path + ": no column '" + name + "'");
    index.push_back(static_cast<std::size_t>(at - header.begin()));
  }
  std::vector<std::vector<double>> values(columns.size());
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto cells = split_row(lines[k]);
    if (cells.size() != header.size()) continue;
    for (std::size_t c = 0; c < index.size(); ++c) values[c].push_back(std::strtod(cells[index[c]].c_str(), nullptr));
  }
  return values;
}

}  // namespace talus
