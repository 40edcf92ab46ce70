#include "trial_log.hpp"

#include <cmath>
#include <cstdio>

namespace talus::strength_reduction {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

std::string outcome(const TrialResult& t) {
  std::string s;
  auto add = [&](bool on, const char* what) {
    if (on) s += (s.empty() ? "" : ", ") + std::string(what);
  };
  add(t.budget, "no equilibrium");
  add(t.displaced, "displacement limit");
  add(t.growing, "displacement growing");
  add(t.slip_path, "slip path");
  if (!t.failed()) return s.empty() ? "stable" : "stable (not deciding: " + s + ")";
  return "fails: " + s;
}

std::string csv_header(std::size_t monitors) {
  std::string s =
      "trial,factor,outcome,steps,ratio,no_equilibrium,displacement_limit,displacement_growing,slip_path,"
      "displacement_m,contacts,open,closed,slip,bonded,released_blocks,released_mass_fraction,dissipated_J";
  for (std::size_t k = 0; k < monitors; ++k) {
    const std::string m = "monitor" + std::to_string(k);
    s += "," + m + "_dx_m," + m + "_dy_m," + m + "_dz_m," + m + "_d_m";
  }
  return s + ",wall_s\n";
}

std::string csv_row(std::size_t trial, const TrialResult& t) {
  std::string s = std::to_string(trial) + "," + (std::isinf(t.factor) ? std::string("elastic") : number(t.factor)) +
                  "," + (t.failed() ? "failed" : "stable") + "," + std::to_string(t.steps) + "," + number(t.ratio);
  for (bool b : {t.budget, t.displaced, t.growing, t.slip_path}) s += b ? ",1" : ",0";
  s += "," + number(t.displacement);
  for (std::uint64_t c : {t.contacts, t.open, t.stick, t.slip, t.bonded, t.released_blocks})
    s += "," + std::to_string(c);
  s += "," + number(t.released_mass) + "," + number(t.dissipated);
  for (const Vec3& d : t.monitors) s += "," + number(d.x) + "," + number(d.y) + "," + number(d.z) + "," + number(norm(d));
  return s + "," + number(t.wall_seconds) + "\n";
}

}  // namespace talus::strength_reduction
