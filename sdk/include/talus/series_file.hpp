// Reading a time-series CSV file as the probes writer writes it: '#' comment
// lines, a header row, then one row of numbers per output (docs/output-formats.md).
// A last line without its newline (a run killed while writing) is left out.
#pragma once

#include <string>
#include <vector>

#include "talus/config.hpp"

namespace talus {

// The header row's column names; empty if the file cannot be read or has none.
TALUS_API std::vector<std::string> series_header(const std::string& path);

// The named columns, in the order asked, over every complete row. Throws
// RunError naming the file for a file that cannot be read or a missing column.
TALUS_API std::vector<std::vector<double>> read_series(const std::string& path, const std::vector<std::string>& columns);

}  // namespace talus
