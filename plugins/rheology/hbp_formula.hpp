// The Herschel-Bulkley-Papanastasiou apparent viscosity, shared by the hbp,
// herschel_bulkley, power_law (and, in form, bingham) models so that their
// limits coincide by construction and can be tested against each other.
//
// Written with the shear rate gd = |D| = sqrt(2 D:D) of the wcsph stage, so
// that in simple shear the stress is tau = mu gd:
//   mu = tau_y (1 - exp(-m gd)) / gd + K gd^(n-1)
// (Papanastasiou 1987, J. Rheol. 31; the coastline seed §2.3.2, whose
// "2 mu |4 Pi_D|^((n-1)/2)" with Pi_D = gd^2/4 is K gd^(n-1), K = 2 mu,
// i.e. our K is the consistency of the simple-shear law tau = tau_y + K gd^n).
// m = 0 with n = 1: Newtonian; m -> inf: Herschel-Bulkley; n = 1: Bingham.
#pragma once

#include <algorithm>
#include <cmath>

namespace talus::rheology {

// (1 - exp(-m gd)) / gd, accurate as gd -> 0 (limit m).
inline double papanastasiou_factor(double m, double gd) {
  const double x = m * gd;
  return x > 1e-12 ? -std::expm1(-x) / gd : m;
}

// K gd^(n-1) with gd bounded below by gd_min (power index n < 1 diverges at rest).
inline double power_law_viscosity(double k, double n, double gd, double gd_min) {
  if (n == 1.0) return k;
  return k * std::pow(std::max(gd, gd_min), n - 1.0);
}

// Pressure-dependent yield stress (coastline seed Table 3: cohesion c, friction
// angle phi), with the compressive pressure p >= 0 (no tensile strength beyond c):
//   Mohr-Coulomb:    tau_y = c + p tan(phi)
//   Drucker-Prager:  tau_y = sqrt(3) (kappa_c + alpha_phi p), the von Mises
//     equivalent shear stress of the cone matched to Mohr-Coulomb in plane
//     strain, alpha_phi = tan(phi)/sqrt(9 + 12 tan^2 phi), kappa_c =
//     3 c/sqrt(9 + 12 tan^2 phi) (Fourtakas & Rogers 2016, Adv. Water Resour. 92, eq. 22).
enum class YieldModel { constant, mohr_coulomb, drucker_prager };

struct YieldStress {
  YieldModel model = YieldModel::constant;
  double tau0 = 0.0;     // constant yield stress, Pa
  double cohesion = 0.0; // c, Pa
  double slope = 0.0;    // d tau_y / d p
  double offset = 0.0;   // tau_y at p = 0

  static YieldStress make(YieldModel model, double tau0, double c, double phi_deg) {
    YieldStress y;
    y.model = model;
    y.tau0 = tau0;
    y.cohesion = c;
    const double t = std::tan(phi_deg * 3.14159265358979323846 / 180.0);
    if (model == YieldModel::constant) {
      y.offset = tau0;
    } else if (model == YieldModel::mohr_coulomb) {
      y.offset = c;
      y.slope = t;
    } else {
      const double s = std::sqrt(9.0 + 12.0 * t * t);
      y.offset = std::sqrt(3.0) * 3.0 * c / s;
      y.slope = std::sqrt(3.0) * t / s;
    }
    return y;
  }
  double at(double p) const { return offset + slope * std::max(p, 0.0); }
};

}  // namespace talus::rheology
