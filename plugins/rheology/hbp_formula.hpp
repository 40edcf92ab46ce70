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
//   Drucker-Prager:  tau_y = kappa_c + alpha_phi I1 = kappa_c + 3 alpha_phi p,
//     the cone sqrt(J2) = kappa_c + alpha_phi I1 (I1 = 3p) matched to
//     Mohr-Coulomb in plane strain, alpha_phi = tan(phi)/sqrt(9 + 12 tan^2 phi),
//     kappa_c = 3 c/sqrt(9 + 12 tan^2 phi) (Drucker & Prager 1952; the form
//     Fourtakas & Rogers 2016, Adv. Water Resour. 92, use for sediment).
//     tau_y is compared with mu gd, and mu gd = sqrt(J2) of the viscous stress
//     2 mu D, so tau_y is the cone's sqrt(J2) itself: at phi = 35 deg,
//     tau_y = 0.78 c + 0.545 p, i.e. a critical infinite slope of 28.6 deg.
//     (An extra factor sqrt(3), the von Mises sqrt(3 J2), would halve the
//     friction to 0.31 p, a critical slope of 17.5 deg: measured, a bank's core
//     under its phi-lines then fails.)
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
      y.offset = 3.0 * c / s;
      y.slope = 3.0 * t / s;
    }
    return y;
  }
  double at(double p) const { return offset + slope * std::max(p, 0.0); }
};

// Effective (skeleton) pressure of a saturated sediment, Terzaghi p' = p - p_w.
// Fourtakas & Rogers (2016, Adv. Water Resour. 92, §3) apply the yield
// criterion to the sediment skeleton, not to the total pressure of the
// water-sediment mixture. With only the particle's own p and rho at hand (the
// batch interface), the pore pressure is closed locally as hydrostatic in a
// saturated column, p_w = (rho_w / rho) p, so p' = p (1 - rho_w / rho): the
// submerged (buoyant) weight of the column above. Exact where no free water
// stands over the sediment column (emerged bank, dry-topped bed); under a
// water layer of depth H_w it overstates p' by (1 - rho_w/rho) rho_w g H_w
// (i.e. errs on the strong side). rho_w = 0 gives the total pressure.
inline double effective_pressure(double p, double rho, double rho_w) {
  return rho_w > 0.0 && rho > 0.0 ? p * (1.0 - rho_w / rho) : p;
}

// The bi-viscosity cap of the unyielded region (max_viscosity, mu_max):
// mu_eff = min(mu, mu_max). The regularised plug viscosity tau_y m (2e5 Pa s
// for the coastline seed's sediment) makes the explicit viscous step
// dt <= C h^2 rho / mu ~ 1e-6 s. The unyielded sediment is a very viscous
// fluid in these models (Fourtakas & Rogers 2016 §3); bounding its viscosity
// keeps the explicit step practical. With the cap the model is a bi-viscosity
// Bingham/HBP law (O'Donovan & Tanner 1984, J. Non-Newton. Fluid Mech. 15):
// the material is unyielded below the yield shear rate tau_y / mu_max and
// creeps there at gd = tau / mu_max. Choosing mu_max = rho h c0 makes the
// viscous step no smaller than the acoustic one, C h / c0.
inline double cap_viscosity(double mu, double mu_max) { return mu < mu_max ? mu : mu_max; }

}  // namespace talus::rheology
