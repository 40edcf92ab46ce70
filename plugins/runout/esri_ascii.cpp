#include "esri_ascii.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <fstream>
#include <sstream>
#include <string_view>

#include "talus/error.hpp"

namespace talus::runout {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw InputError("error: " + path + ":" + std::to_string(line) + ": " + what);
}

std::string text_of(double v) {
  char t[32];
  std::snprintf(t, sizeof t, "%.0f", v);
  return t;
}

bool parse_number(std::string_view token, double& out) {
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, out);
  return ec == std::errc() && ptr == end && std::isfinite(out);
}

// Splits on blanks; reuses `tokens`.
void split(const std::string& line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t s = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > s) tokens.emplace_back(line.data() + s, i - s);
  }
}

}  // namespace

Grid read_esri_ascii(const std::string& path, bool allow_nodata) {
  std::ifstream in(path);
  if (!in) throw InputError("error: " + path + ": cannot open the grid file: " + std::strerror(errno));

  double ncols = -1, nrows = -1, cellsize = -1, xll = NAN, yll = NAN, nodata = -9999.0;
  bool x_centre = false, y_centre = false, have_nodata = false, have_x = false, have_y = false;
  std::string line;
  std::vector<std::string_view> tokens;
  int line_no = 0;
  bool data_started = false;
  // Header: "key value" lines until the first line that starts with a number.
  while (std::getline(in, line)) {
    ++line_no;
    split(line, tokens);
    if (tokens.empty()) continue;
    double first;
    if (parse_number(tokens[0], first)) {
      data_started = true;
      break;
    }
    const std::string key = lower(std::string(tokens[0]));
    double value;
    if (tokens.size() != 2 || !parse_number(tokens[1], value))
      fail(path, line_no, "header line '" + line + "' must be 'KEY NUMBER'");
    if (key == "ncols") ncols = value;
    else if (key == "nrows") nrows = value;
    else if (key == "cellsize") cellsize = value;
    else if (key == "xllcorner" || key == "xllcenter") { xll = value; x_centre = key == "xllcenter"; have_x = true; }
    else if (key == "yllcorner" || key == "yllcenter") { yll = value; y_centre = key == "yllcenter"; have_y = true; }
    else if (key == "nodata_value") { nodata = value; have_nodata = true; }
    else
      fail(path, line_no, "unknown header key '" + std::string(tokens[0]) +
                              "'; known: ncols, nrows, xllcorner, xllcenter, yllcorner, yllcenter, cellsize, "
                              "NODATA_value (dx/dy rectangular cells are not supported)");
  }
  auto missing = [&](const char* key) {
    throw InputError("error: " + path + ": header has no '" + key +
                     "'; an ESRI ASCII grid starts with ncols, nrows, xllcorner (or xllcenter), yllcorner (or "
                     "yllcenter), cellsize and optionally NODATA_value");
  };
  if (ncols < 0) missing("ncols");
  if (nrows < 0) missing("nrows");
  if (cellsize < 0) missing("cellsize");
  if (!have_x) missing("xllcorner");
  if (!have_y) missing("yllcorner");
  if (ncols < 2 || nrows < 2 || ncols != std::floor(ncols) || nrows != std::floor(nrows))
    throw InputError("error: " + path + ": ncols and nrows must be whole numbers >= 2 (got " +
                     std::to_string(ncols) + " x " + std::to_string(nrows) + ")");
  if (ncols > std::numeric_limits<int>::max() || nrows > std::numeric_limits<int>::max())
    throw InputError("error: " + path + ": ncols and nrows must be at most " +
                     std::to_string(std::numeric_limits<int>::max()) + " (got " + text_of(ncols) + " x " +
                     text_of(nrows) + ")");
  if (!(cellsize > 0.0)) throw InputError("error: " + path + ": cellsize must be > 0");
  if (!data_started)
    throw InputError("error: " + path + ":" + std::to_string(line_no) + ": the grid has a header but no values");
  // A large grid's promise is checked against the file before the grid is
  // allocated (every value takes at least a digit and a separator); a small
  // one is read, and a shortfall reported with its line.
  if (ncols * nrows > 1e6) {
    std::error_code ec;
    const double file_size = static_cast<double>(std::filesystem::file_size(path, ec));
    const double data_bytes = file_size - static_cast<double>(in.tellg()) + static_cast<double>(line.size()) + 1.0;
    if (!ec && in.tellg() >= 0 && data_bytes < 2.0 * ncols * nrows - 1.0)
      throw InputError("error: " + path + ": the header promises " + text_of(ncols) + " x " + text_of(nrows) +
                       " values, but the file holds only " + text_of(data_bytes) +
                       " bytes of them (size mismatch)");
  }
  require_dem_memory(ncols, nrows, path);

  Grid g;
  g.cell = cellsize;
  g.nodata = nodata;
  g.resize(static_cast<int>(ncols), static_cast<int>(nrows), 0.0);
  g.x0 = x_centre ? xll : xll + 0.5 * cellsize;
  g.y0 = y_centre ? yll : yll + 0.5 * cellsize;

  // One row per line, north row first.
  int row = 0;
  do {
    split(line, tokens);
    if (tokens.empty()) continue;
    if (row >= g.nrows)
      fail(path, line_no, "more rows than nrows = " + std::to_string(g.nrows) + " (size mismatch)");
    if (static_cast<int>(tokens.size()) != g.ncols)
      fail(path, line_no, "row " + std::to_string(row + 1) + " has " + std::to_string(tokens.size()) +
                              " values, ncols = " + std::to_string(g.ncols) + " (size mismatch)");
    const int south_row = g.nrows - 1 - row;
    for (int c = 0; c < g.ncols; ++c) {
      double v;
      if (!parse_number(tokens[c], v))
        fail(path, line_no, "'" + std::string(tokens[c]) + "' at row " + std::to_string(row + 1) + ", column " +
                                std::to_string(c + 1) + " is not a finite number");
      if (have_nodata && v == nodata && !allow_nodata)
        fail(path, line_no, "no-data value " + std::string(tokens[c]) + " at row " + std::to_string(row + 1) +
                                ", column " + std::to_string(c + 1) +
                                ": the terrain has a hole; fill it (e.g. gdal_fillnodata) before use");
      g.at(c, south_row) = v;
    }
    ++row;
  } while (std::getline(in, line) && ++line_no);
  if (row != g.nrows)
    throw InputError("error: " + path + ":" + std::to_string(line_no) + ": found " + std::to_string(row) +
                     " rows, header says nrows = " + std::to_string(g.nrows) + " (size mismatch)");
  return g;
}

void write_esri_ascii(const std::string& path, const Grid& g, int precision) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw RunError("cannot write " + tmp + ": " + std::strerror(errno));
    char buf[64];
    out << "ncols " << g.ncols << "\nnrows " << g.nrows << "\n";
    std::snprintf(buf, sizeof buf, "%.10g", g.x0 - 0.5 * g.cell);
    out << "xllcorner " << buf << "\n";
    std::snprintf(buf, sizeof buf, "%.10g", g.y0 - 0.5 * g.cell);
    out << "yllcorner " << buf << "\n";
    std::snprintf(buf, sizeof buf, "%.10g", g.cell);
    out << "cellsize " << buf << "\n";
    std::snprintf(buf, sizeof buf, "%.10g", g.nodata);
    out << "NODATA_value " << buf << "\n";
    std::string row;
    for (int r = g.nrows - 1; r >= 0; --r) {
      row.clear();
      for (int c = 0; c < g.ncols; ++c) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, g.at(c, r));
        if (c) row += ' ';
        row += buf;
      }
      out << row << '\n';
    }
    out.flush();
    if (!out) throw RunError("cannot write " + tmp + ": " + std::strerror(errno));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw RunError("cannot rename " + tmp + " to " + path + ": " + std::strerror(errno));
}

}  // namespace talus::runout
