// Numbers and vectors as the simulation's messages and plan print them: four
// significant digits by default (std::setprecision), shorter than the
// round-trip form of text::number, which echoes a value as the user wrote it.
#pragma once

#include <iomanip>
#include <sstream>
#include <string>

#include "talus/vec3.hpp"

namespace talus {

inline std::string fixed(double v, int precision = 4) {
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

inline std::string vec_text(const Vec3& v, int dim) {
  return "(" + fixed(v.x) + ", " + fixed(v.y) + (dim == 3 ? ", " + fixed(v.z) : "") + ")";
}

}  // namespace talus
