// Neighbour records: the fields a fluid pair reads of its neighbour j, side by
// side in one record per particle, and their gather into a pass's lanes. From
// the columns, a chunk of pairs costs one load and one insert per field and
// pair; from records, a few loads and a transpose bring in several pairs'
// fields at once.
//
// In float (mixed precision) a record holds v, rho, p and c in 24 bytes:
// eight pairs come in with eight 32-byte loads and an 8 x 8 transpose. Each
// load also reads the first two fields of the next record, which the
// transpose drops: an array of records ends with one spare. 1/rho is formed
// in the lanes as the stage forms its column, float(1/rho).
//
// In double a record holds rho, p, c and 1/rho in 32 bytes, aligned so that
// it never straddles a cache line, and v stays in its column: four pairs
// come in with four aligned loads, four masked loads of v and two 4 x 4
// transposes. A pair then touches about two cache lines of j's, against
// five from the columns. v in the record as well would take it past half a
// cache line, and the run past the memory it is allowed (the speed case's
// 260 bytes a particle, issue 23).
#pragma once

#include <cstdint>
#include <type_traits>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "talus/config.hpp"
#include "talus/vec3.hpp"

namespace talus::sph {

// Trivial types: a pass fills its records in scratch it does not clear.
struct NeighbourRecord {
  float vx, vy, vz, rho, p, c;
};
struct alignas(32) NeighbourRecordDouble {
  double rho, p, c, inv_rho;
};
template <class Real>
using NeighbourRecordOf = std::conditional_t<std::is_same_v<Real, float>, NeighbourRecord, NeighbourRecordDouble>;

// A term that reads j's fields from records (its neighbours are
// GatheredNeighbourFields, fluid_terms.hpp): only the mutual pass gathers them.
template <class Term>
concept ReadsRecords = requires(const Term& t) { t.nb.record; };

// j's gathered fields, lane by lane, in double (the terms' arithmetic).
template <int Size>
struct GatheredLanes {
  double vx[Size], vy[Size], vz[Size], rho[Size], p[Size], c[Size], inv_rho[Size];
};

#if defined(__AVX2__)
namespace detail {
// Rows r[k] (record of lane k) to columns r[f] (field f of the eight lanes).
TALUS_PAIR_INLINE void transpose8(__m256 r[8]) {
  __m256 t[8], s[8];
  for (int k = 0; k < 8; k += 2) {
    t[k] = _mm256_unpacklo_ps(r[k], r[k + 1]);
    t[k + 1] = _mm256_unpackhi_ps(r[k], r[k + 1]);
  }
  for (int k = 0; k < 8; k += 4) {
    s[k] = _mm256_shuffle_ps(t[k], t[k + 2], 0x44);
    s[k + 1] = _mm256_shuffle_ps(t[k], t[k + 2], 0xEE);
    s[k + 2] = _mm256_shuffle_ps(t[k + 1], t[k + 3], 0x44);
    s[k + 3] = _mm256_shuffle_ps(t[k + 1], t[k + 3], 0xEE);
  }
  for (int k = 0; k < 4; ++k) {
    r[k] = _mm256_permute2f128_ps(s[k], s[k + 4], 0x20);
    r[k + 4] = _mm256_permute2f128_ps(s[k], s[k + 4], 0x31);
  }
}

// Rows r[k] (four doubles of lane k) to columns r[f] (field f of the four lanes).
TALUS_PAIR_INLINE void transpose4(__m256d r[4]) {
  const __m256d l01 = _mm256_unpacklo_pd(r[0], r[1]), h01 = _mm256_unpackhi_pd(r[0], r[1]);
  const __m256d l23 = _mm256_unpacklo_pd(r[2], r[3]), h23 = _mm256_unpackhi_pd(r[2], r[3]);
  r[0] = _mm256_permute2f128_pd(l01, l23, 0x20);
  r[1] = _mm256_permute2f128_pd(h01, h23, 0x20);
  r[2] = _mm256_permute2f128_pd(l01, l23, 0x31);
  r[3] = _mm256_permute2f128_pd(h01, h23, 0x31);
}

TALUS_PAIR_INLINE void store_as_double(double* to, __m256 v) {
  _mm256_storeu_pd(to, _mm256_cvtps_pd(_mm256_castps256_ps128(v)));
  _mm256_storeu_pd(to + 4, _mm256_cvtps_pd(_mm256_extractf128_ps(v, 1)));
}

// float(1/rho) of four densities, in double: divided in double and rounded
// to float as a static_cast does (the default rounding mode).
TALUS_PAIR_INLINE __m256d reciprocal_as_float(__m128 rho) {
  const __m256d inv = _mm256_div_pd(_mm256_set1_pd(1.0), _mm256_cvtps_pd(rho));
  return _mm256_cvtps_pd(_mm256_cvtpd_ps(inv));
}
}  // namespace detail
#endif

// The records of j[0..n) into `out`. j must hold valid rows up to n rounded
// up to eight (the lanes past n are gathered and not used), and `records`
// one spare record after the last row.
template <int Size>
TALUS_PAIR_INLINE void gather_records(const NeighbourRecord* records, const Index* j, int n, GatheredLanes<Size>& out) {
  static_assert(Size % 8 == 0, "lanes are gathered eight at a time");
#if defined(__AVX2__)
  for (int k = 0; k < n; k += 8) {
    __m256 r[8];
    for (int l = 0; l < 8; ++l) r[l] = _mm256_loadu_ps(&records[j[k + l]].vx);
    detail::transpose8(r);
    detail::store_as_double(out.vx + k, r[0]);
    detail::store_as_double(out.vy + k, r[1]);
    detail::store_as_double(out.vz + k, r[2]);
    detail::store_as_double(out.rho + k, r[3]);
    detail::store_as_double(out.p + k, r[4]);
    detail::store_as_double(out.c + k, r[5]);
    _mm256_storeu_pd(out.inv_rho + k, detail::reciprocal_as_float(_mm256_castps256_ps128(r[3])));
    _mm256_storeu_pd(out.inv_rho + k + 4, detail::reciprocal_as_float(_mm256_extractf128_ps(r[3], 1)));
  }
#else
  for (int k = 0; k < n; ++k) {
    const NeighbourRecord& r = records[j[k]];
    out.vx[k] = r.vx;
    out.vy[k] = r.vy;
    out.vz[k] = r.vz;
    out.rho[k] = r.rho;
    out.p[k] = r.p;
    out.c[k] = r.c;
    out.inv_rho[k] = static_cast<float>(1.0 / r.rho);
  }
#endif
}

// The same in double: rho, p, c and 1/rho from the records and v from its
// column, four lanes at a time; nothing past either array is read.
template <int Size>
TALUS_PAIR_INLINE void gather_records(const NeighbourRecordDouble* records, const Vec3* velocity, const Index* j,
                                      int n, GatheredLanes<Size>& out) {
  static_assert(Size % 8 == 0, "lanes are gathered eight at a time");
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
#if defined(__AVX2__)
  const __m256i xyz = _mm256_setr_epi64x(-1, -1, -1, 0);
  for (int k = 0; k < n; k += 4) {
    __m256d a[4], v[4];
    for (int l = 0; l < 4; ++l) {
      a[l] = _mm256_load_pd(&records[j[k + l]].rho);
      v[l] = _mm256_maskload_pd(&velocity[j[k + l]].x, xyz);
    }
    detail::transpose4(a);
    detail::transpose4(v);
    _mm256_storeu_pd(out.rho + k, a[0]);
    _mm256_storeu_pd(out.p + k, a[1]);
    _mm256_storeu_pd(out.c + k, a[2]);
    _mm256_storeu_pd(out.inv_rho + k, a[3]);
    _mm256_storeu_pd(out.vx + k, v[0]);
    _mm256_storeu_pd(out.vy + k, v[1]);
    _mm256_storeu_pd(out.vz + k, v[2]);
  }
#else
  for (int k = 0; k < n; ++k) {
    const NeighbourRecordDouble& r = records[j[k]];
    out.vx[k] = velocity[j[k]].x;
    out.vy[k] = velocity[j[k]].y;
    out.vz[k] = velocity[j[k]].z;
    out.rho[k] = r.rho;
    out.p[k] = r.p;
    out.c[k] = r.c;
    out.inv_rho[k] = r.inv_rho;
  }
#endif
}

}  // namespace talus::sph
