#include "grid.hpp"

#include <algorithm>
#include <cmath>

namespace talus::runout {

double Grid::bilinear(double x, double y) const {
  const double fx = std::clamp((x - x0) / cell, 0.0, static_cast<double>(ncols - 1));
  const double fy = std::clamp((y - y0) / cell, 0.0, static_cast<double>(nrows - 1));
  const int i = std::min(static_cast<int>(fx), ncols - 2 < 0 ? 0 : ncols - 2);
  const int j = std::min(static_cast<int>(fy), nrows - 2 < 0 ? 0 : nrows - 2);
  const double tx = ncols > 1 ? fx - i : 0.0, ty = nrows > 1 ? fy - j : 0.0;
  const int i1 = ncols > 1 ? i + 1 : i, j1 = nrows > 1 ? j + 1 : j;
  const double a = at(i, j) + tx * (at(i1, j) - at(i, j));
  const double b = at(i, j1) + tx * (at(i1, j1) - at(i, j1));
  return a + ty * (b - a);
}

}  // namespace talus::runout
