// A plain 3-vector for the hot loops. Header-only and trivially copyable so
// the compiler keeps it in registers; Eigen is used where matrices are needed.
// 2D scenes use x and y with z = 0.
#pragma once

#include <cmath>
#include <type_traits>

namespace talus {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;

  constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  constexpr Vec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
};

constexpr Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
constexpr Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
constexpr Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(Vec3 a, double s) { return a *= s; }
constexpr Vec3 operator*(double s, Vec3 a) { return a *= s; }
constexpr Vec3 operator/(const Vec3& a, double s) { return {a.x / s, a.y / s, a.z / s}; }
constexpr bool operator==(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr double norm2(const Vec3& a) { return dot(a, a); }
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline bool is_finite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

// A 3-vector kept in single precision (a field stored in float under mixed
// precision, particles.hpp). Storage only: it converts to and from Vec3 both
// ways, and the arithmetic is Vec3's, in double.
struct Vec3f {
  float x = 0.0f, y = 0.0f, z = 0.0f;

  constexpr Vec3f() = default;
  constexpr Vec3f(const Vec3& v)
      : x(static_cast<float>(v.x)), y(static_cast<float>(v.y)), z(static_cast<float>(v.z)) {}
  constexpr operator Vec3() const { return {x, y, z}; }
};

inline bool is_finite(const Vec3f& a) { return is_finite(Vec3(a)); }

// The type a vector field of Real (double or float) components is stored in.
template <class Real>
using VectorOf = std::conditional_t<std::is_same_v<Real, float>, Vec3f, Vec3>;

}  // namespace talus
