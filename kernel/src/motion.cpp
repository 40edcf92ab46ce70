#include "talus/motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "talus/error.hpp"

namespace talus {

namespace {
// Rodrigues rotation of v by angle a about unit axis k.
Vec3 rotate(const Vec3& v, const Vec3& k, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1.0 - c));
}
}  // namespace

void PrescribedMotion::declare(ParamSet& body) {
  auto b = body.one_of("motion").doc("how the body moves; absent: it stays put").optional();

  ParamSet sine{"sine", "translation x(t) = amplitude sin(2 pi t / period + phase) direction (piston)"};
  sine.vector("direction").doc("direction of the stroke (normalised)");
  sine.real("amplitude").unit("m").min(0.0).doc("half the stroke");
  sine.real("period").unit("s").greater_than(0.0).doc("period of the oscillation");
  sine.real("phase").unit("rad").default_value(0.0).doc("phase at t = 0");
  b.alternative("sine", sine);

  ParamSet velocity{"velocity", "translation at constant velocity"};
  velocity.vector("velocity").unit("m/s").doc("velocity of the body");
  b.alternative("velocity", velocity);

  ParamSet table{"table", "piecewise-linear displacement table, held after the last entry"};
  table.real_list("time").unit("s").doc("increasing times, the first one 0");
  table.vector_list("displacement").unit("m").doc("displacement at each time");
  table.check([](const ParamValues& v, Diagnostics& d) {
    const auto& t = v.reals("time");
    if (t.size() != v.vectors("displacement").size())
      d.error(v, "displacement", "has " + std::to_string(v.vectors("displacement").size()) + " entries but time has " +
                                     std::to_string(t.size()));
    if (t.empty() || t.front() != 0.0) d.error(v, "time", "must start at 0");
    if (!std::is_sorted(t.begin(), t.end()) || std::adjacent_find(t.begin(), t.end()) != t.end())
      d.error(v, "time", "must be strictly increasing");
  });
  b.alternative("table", table);

  ParamSet hinge{"hinge", "rotation a(t) = amplitude sin(2 pi t / period + phase) about a hinge line (flap)"};
  hinge.vector("point").unit("m").doc("a point on the hinge line");
  hinge.vector("axis").length(3).doc("direction of the hinge line (normalised)");
  hinge.real("amplitude").unit("rad").min(0.0).doc("angular amplitude");
  hinge.real("period").unit("s").greater_than(0.0).doc("period of the oscillation");
  hinge.real("phase").unit("rad").default_value(0.0).doc("phase at t = 0");
  b.alternative("hinge", hinge);
}

PrescribedMotion::PrescribedMotion(const std::string& alternative, const ParamValues& v) {
  auto unit = [&](const char* name, Vec3 d) {
    const double n = norm(d);
    if (!(n > 0.0)) v.fail(name, "must not be the zero vector");
    return d / n;
  };
  if (alternative == "sine") {
    kind_ = Kind::sine;
    direction_ = unit("direction", v.vector("direction"));
    amplitude_ = v.real("amplitude");
    omega_ = 2.0 * std::numbers::pi / v.real("period");
    phase_ = v.real("phase");
  } else if (alternative == "velocity") {
    kind_ = Kind::velocity;
    direction_ = v.vector("velocity");
  } else if (alternative == "table") {
    kind_ = Kind::table;
    times_ = v.reals("time");
    displacements_ = v.vectors("displacement");
  } else if (alternative == "hinge") {
    kind_ = Kind::hinge;
    point_ = v.vector("point");
    axis_ = unit("axis", v.vector("axis"));
    amplitude_ = v.real("amplitude");
    omega_ = 2.0 * std::numbers::pi / v.real("period");
    phase_ = v.real("phase");
  } else {
    throw InputError("unknown motion '" + alternative + "'");
  }
}

Vec3 PrescribedMotion::position(const Vec3& x0, double t) const {
  switch (kind_) {
    case Kind::none: return x0;
    case Kind::sine: return x0 + direction_ * (amplitude_ * (std::sin(omega_ * t + phase_) - std::sin(phase_)));
    case Kind::velocity: return x0 + direction_ * t;
    case Kind::table: {
      if (t >= times_.back()) return x0 + displacements_.back();
      const auto k = static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()) - 1;
      const double f = (t - times_[k]) / (times_[k + 1] - times_[k]);
      return x0 + displacements_[k] * (1.0 - f) + displacements_[k + 1] * f;
    }
    case Kind::hinge: {
      const double a = amplitude_ * (std::sin(omega_ * t + phase_) - std::sin(phase_));
      return point_ + rotate(x0 - point_, axis_, a);
    }
  }
  return x0;
}

Vec3 PrescribedMotion::initial_position(const Vec3& x, double t) const {
  if (kind_ == Kind::hinge) {
    const double a = amplitude_ * (std::sin(omega_ * t + phase_) - std::sin(phase_));
    return point_ + rotate(x - point_, axis_, -a);
  }
  return x - position(Vec3{}, t);  // the other motions translate every point alike
}

Vec3 PrescribedMotion::velocity(const Vec3& x0, double t) const {
  switch (kind_) {
    case Kind::none: return {};
    case Kind::sine: return direction_ * (amplitude_ * omega_ * std::cos(omega_ * t + phase_));
    case Kind::velocity: return direction_;
    case Kind::table: {
      if (t >= times_.back()) return {};
      const auto k = static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()) - 1;
      return (displacements_[k + 1] - displacements_[k]) / (times_[k + 1] - times_[k]);
    }
    case Kind::hinge: {
      const double rate = amplitude_ * omega_ * std::cos(omega_ * t + phase_);
      return cross(axis_ * rate, position(x0, t) - point_);
    }
  }
  return {};
}

}  // namespace talus
