// The mutual (one evaluation per pair) form of every fluid-fluid term against
// its gather form: the same accelerations, density rates and viscous rates on
// a jittered two-material cloud with random velocities, closed and periodic,
// 2D and 3D, on one and two threads; and bit-for-bit the same result when a
// run is repeated, on one or two threads, and from neighbour records.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "cubic_spline.hpp"
#include "muller.hpp"
#include "talus/error.hpp"
#include "talus/kernel_table.hpp"
#include "talus/neighbour_grid.hpp"
#include "talus/params.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/sph/mutual_pass.hpp"
#include "talus/sph/pair_loop.hpp"

namespace talus {
namespace {

// The i-state and sums the terms read (as wcsph's FluidSums).
struct Sums {
  Vec3 v;
  double m = 0, rho = 0, inv_rho = 0, p = 0, c = 0, mu = 0, kh = 0;
  std::int32_t mat = 0;
  Vec3 acc;
  double drho = 0, visc = 0;
};

struct Cloud {
  int dim = 3;
  double dp = 0.01;
  Vec3 lo, hi;
  std::array<bool, 3> periodic{};
  std::vector<Vec3> x, v;
  std::vector<double> m, rho, p, c, inv_rho, kh, mu_eff;
  std::vector<std::int32_t> mat;
  double mu_of_material[2] = {1e-3, 5.0};

  sph::Neighbours nb() const {
    return {v.data(), rho.data(), p.data(), c.data(), m.data(), mat.data(), inv_rho.data(), mu_eff.data()};
  }
};

// A jittered lattice of `per_axis` points per axis, the upper third of a
// second, denser material, with random velocities and densities.
Cloud make_cloud(int dim, int per_axis, std::array<bool, 3> periodic, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Cloud c;
  c.dim = dim;
  c.periodic = periodic;
  c.lo = {0, 0, 0};
  c.hi = {per_axis * c.dp, per_axis * c.dp, dim == 3 ? per_axis * c.dp : 0.0};
  const int nz = dim == 3 ? per_axis : 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < per_axis; ++j)
      for (int i = 0; i < per_axis; ++i) {
        Vec3 x{(i + 0.5 + 0.3 * u(rng)) * c.dp, (j + 0.5 + 0.3 * u(rng)) * c.dp, 0.0};
        if (dim == 3) x.z = (k + 0.5 + 0.3 * u(rng)) * c.dp;
        const bool heavy = j > 2 * per_axis / 3;
        const double rho0 = heavy ? 1900.0 : 1000.0, sound = heavy ? 30.0 : 20.0;
        const double rho = rho0 * (1.0 + 0.01 * u(rng));
        c.x.push_back(x);
        c.v.push_back({u(rng), u(rng), dim == 3 ? u(rng) : 0.0});
        c.m.push_back(rho0 * std::pow(c.dp, dim) * (1.0 + 0.05 * u(rng)));
        c.rho.push_back(rho);
        c.p.push_back(sound * sound * (rho - rho0));
        c.c.push_back(sound);
        c.inv_rho.push_back(1.0 / rho);
        c.kh.push_back(rho / (sound * sound));
        c.mat.push_back(heavy ? 1 : 0);
        c.mu_eff.push_back(heavy ? 2.0 + u(rng) : 1e-3);
      }
  return c;
}

struct Rates {
  std::vector<Vec3> acc;
  std::vector<double> drho;
  double visc_max = 0.0;  // the largest |v_ij . x_ij|/(r^2 + eta^2) of the rows' pairs
  sph::FluidReactions<> out() { return {acc.data(), drho.data()}; }
};

Rates zero_rates(std::size_t n, double fill = 0.0) {
  return {std::vector<Vec3>(n, Vec3{fill, fill, fill}), std::vector<double>(n, fill)};
}

Sums start_of(const Cloud& c, Index i) {
  Sums s;
  s.v = c.v[i];
  s.m = c.m[i];
  s.rho = c.rho[i];
  s.inv_rho = c.inv_rho[i];
  s.p = c.p[i];
  s.c = c.c[i];
  s.mu = c.mu_eff[i];
  s.kh = c.kh[i];
  s.mat = c.mat[i];
  return s;
}

// The gather form over the first `rows` particles (all by default).
template <class Term>
Rates gather(const Cloud& c, const NeighbourGrid& grid, const KernelTable& kernel, const Term& term,
             std::size_t rows = SIZE_MAX) {
  rows = std::min(rows, c.x.size());
  Rates r = zero_rates(c.x.size());
  std::vector<double> visc(rows, 0.0);
  auto start = [&](Index i) { return start_of(c, i); };
  auto finish = [&](Index i, const Sums& s) {
    r.acc[i] = s.acc;
    r.drho[i] = s.drho;
    visc[i] = s.visc;
  };
  sph::pair_pass(rows, std::span<const Vec3>(c.x), grid, kernel, sph::same_set, start, finish, term);
  for (double v : visc) r.visc_max = std::max(r.visc_max, v);
  return r;
}

// Rows from `owned` on play another MPI rank's halo copies.
template <class Term>
Rates mutual(const Cloud& c, const NeighbourGrid& grid, const KernelTable& kernel, const Term& term,
             std::size_t owned = SIZE_MAX, std::uint64_t* pairs = nullptr) {
  Rates r = zero_rates(c.x.size(), 9.0);  // not zero: the pass must clear its output
  auto start = [&](Index i) { return start_of(c, i); };
  const sph::MutualPassResult result = sph::mutual_pair_pass(grid, kernel, r.out(),
                                                             std::min(owned, c.x.size()), start, [](Index) {}, term);
  r.visc_max = result.visc_max;
  if (pairs) *pairs = result.evaluations;
  return r;
}

double largest(const std::vector<Vec3>& a) {
  double m = 0.0;
  for (const Vec3& v : a) m = std::max(m, norm(v));
  return m;
}
double largest(const std::vector<double>& a) {
  double m = 0.0;
  for (double v : a) m = std::max(m, std::abs(v));
  return m;
}

// Relative to the largest value of each rate: the two forms add the same
// pair contributions in a different order.
void expect_same_rates(const Rates& got, const Rates& want) {
  const double acc_scale = largest(want.acc), drho_scale = largest(want.drho);
  ASSERT_EQ(got.acc.size(), want.acc.size());
  EXPECT_NEAR(got.visc_max, want.visc_max, 1e-12 * want.visc_max);
  int bad = 0;
  for (std::size_t i = 0; i < want.acc.size() && bad < 5; ++i) {
    const bool ok = norm(got.acc[i] - want.acc[i]) <= 1e-12 * acc_scale &&
                    std::abs(got.drho[i] - want.drho[i]) <= 1e-12 * drho_scale;
    if (!ok) {
      ++bad;
      ADD_FAILURE() << "particle " << i << ": acc (" << got.acc[i].x << ", " << got.acc[i].y << ", " << got.acc[i].z
                    << ") vs (" << want.acc[i].x << ", " << want.acc[i].y << ", " << want.acc[i].z << "), drho "
                    << got.drho[i] << " vs " << want.drho[i];
    }
  }
}

struct Layout {
  int dim;
  std::array<bool, 3> periodic;
  int threads;
};

class MutualPass : public ::testing::TestWithParam<Layout> {
 protected:
  void SetUp() override {
    const Layout l = GetParam();
    omp_set_num_threads(l.threads);
    // 3D: 18^3 = 5832 points (above sph::parallel_min, so two threads really split the pass); 2D: 80^2.
    cloud = make_cloud(l.dim, l.dim == 3 ? 18 : 80, l.periodic, 11u + l.dim + 2 * l.periodic[0]);
    const ParamValues none;
    spline = std::make_unique<kernels::CubicSpline>(none);
    muller = std::make_unique<kernels::Muller>(none);
    const double h = 1.3 * cloud.dp;
    kernel = KernelTable(*spline, l.dim, h);
    laplacian_kernel = KernelTable(*muller, l.dim, h);
    grid.configure(l.dim, cloud.lo, cloud.hi, kernel.support_radius(), l.periodic);
    grid.build(cloud.x);
    muller_grid.configure(l.dim, cloud.lo, cloud.hi, laplacian_kernel.support_radius(), l.periodic);
    muller_grid.build(cloud.x);
  }
  void TearDown() override { omp_set_num_threads(omp_get_num_procs()); }

  template <class Term>
  void expect_mutual_matches_gather(const Term& term) {
    const Rates want = gather(cloud, grid, kernel, term);
    ASSERT_GT(largest(want.acc) + largest(want.drho), 0.0);  // the term really acts
    expect_same_rates(mutual(cloud, grid, kernel, term), want);
  }

  // same_rates(terms...)(other_terms...): the mutual pass gives the same
  // rates with either set of terms, bit for bit (the first set acts).
  auto same_rates(const auto&... on_columns) {
    return [&, this](const auto&... on_records) {
      const std::size_t n = cloud.x.size();
      Rates want = zero_rates(n), got = zero_rates(n, 9.0);
      auto start = [&](Index i) { return start_of(cloud, i); };
      want.visc_max = sph::mutual_pair_pass(grid, kernel, want.out(), n, start, [](Index) {}, on_columns...).visc_max;
      ASSERT_GT(largest(want.acc) + largest(want.drho), 0.0);
      got.visc_max = sph::mutual_pair_pass(grid, kernel, got.out(), n, start, [](Index) {}, on_records...).visc_max;
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(got.acc[i], want.acc[i]) << i;
        ASSERT_EQ(got.drho[i], want.drho[i]) << i;
      }
      EXPECT_EQ(got.visc_max, want.visc_max);
    };
  }

  // The dam break's terms, then the laminar set, on the columns and on the
  // records: the same rates bit for bit.
  template <class Columns, class Records>
  void expect_records_match_columns(const Columns& columns, const Records& gathered) {
    const double h = kernel.h(), eta2 = sph::laminar_eta2(h), delta_h_c0 = 0.1 * h * 30.0;
    const Vec3 g{0, -9.81, 0};
    same_rates(sph::PressureForce{columns}, sph::ArtificialViscosity{columns, 0.1 * h}, sph::Continuity{columns},
               sph::DensityDiffusion<true, Columns>{columns, delta_h_c0, g})(
        sph::PressureForce{gathered}, sph::ArtificialViscosity{gathered, 0.1 * h}, sph::Continuity{gathered},
        sph::DensityDiffusion<true, Records>{gathered, delta_h_c0, g});
    same_rates(sph::LaminarViscosity<false, Columns>{columns, cloud.mu_of_material, eta2},
               sph::DensityDiffusion<false, Columns>{columns, delta_h_c0, g})(
        sph::LaminarViscosity<false, Records>{gathered, cloud.mu_of_material, eta2},
        sph::DensityDiffusion<false, Records>{gathered, delta_h_c0, g});
  }

  // Sums carry mu = mu_eff[i]: with the materials' values, as for a Newtonian fluid.
  void use_material_viscosities() {
    for (std::size_t i = 0; i < cloud.x.size(); ++i) cloud.mu_eff[i] = cloud.mu_of_material[cloud.mat[i]];
  }

  Cloud cloud;
  std::unique_ptr<SmoothingKernel> spline, muller;
  KernelTable kernel, laplacian_kernel;
  NeighbourGrid grid, muller_grid;
};

TEST_P(MutualPass, PressureForce) { expect_mutual_matches_gather(sph::PressureForce{cloud.nb()}); }

TEST_P(MutualPass, ArtificialViscosity) {
  expect_mutual_matches_gather(sph::ArtificialViscosity{cloud.nb(), 0.1 * kernel.h()});
}

TEST_P(MutualPass, LaminarViscosityOfTheMaterials) {
  // As the wcsph stage's start(): Sums carry mu of i's material.
  use_material_viscosities();
  expect_mutual_matches_gather(sph::LaminarViscosity<false>{cloud.nb(), cloud.mu_of_material,
                                                            sph::laminar_eta2(kernel.h())});
}

TEST_P(MutualPass, LaminarViscosityFieldArithmeticAndHarmonic) {
  const double eta2 = sph::laminar_eta2(kernel.h());
  expect_mutual_matches_gather(sph::LaminarViscosityField<sph::ViscosityMean::arithmetic>{cloud.nb(), eta2});
  expect_mutual_matches_gather(sph::LaminarViscosityField<sph::ViscosityMean::harmonic>{cloud.nb(), eta2});
}

TEST_P(MutualPass, LaplacianViscosityWithEachParticlesOwnViscosity) {
  use_material_viscosities();
  const sph::LaplacianViscosity term{cloud.nb(), &laplacian_kernel, cloud.mu_of_material};
  const Rates want = gather(cloud, muller_grid, laplacian_kernel, term);
  ASSERT_GT(largest(want.acc), 0.0);
  expect_same_rates(mutual(cloud, muller_grid, laplacian_kernel, term), want);
}

TEST_P(MutualPass, ContinuityAcrossTheDensityJump) { expect_mutual_matches_gather(sph::Continuity{cloud.nb()}); }

TEST_P(MutualPass, DensityDiffusionMolteniAndFourtakas) {
  const double delta_h_c0 = 0.1 * kernel.h() * 30.0;
  expect_mutual_matches_gather(sph::DensityDiffusion<false>{cloud.nb(), delta_h_c0, {0, -9.81, 0}});
  expect_mutual_matches_gather(sph::DensityDiffusion<true>{cloud.nb(), delta_h_c0, {0, -9.81, 0}});
}

TEST_P(MutualPass, CountsEveryPairFromBothSidesAndRepeatsBitForBit) {
  const sph::PressureForce pressure{cloud.nb()};
  const sph::ArtificialViscosity viscosity{cloud.nb(), 0.1 * kernel.h()};
  const sph::Continuity continuity{cloud.nb()};
  auto start = [&](Index i) { return start_of(cloud, i); };
  const std::uint64_t gathered = sph::pair_pass(cloud.x.size(), std::span<const Vec3>(cloud.x), grid, kernel,
                                                sph::same_set, start, [](Index, const Sums&) {}, pressure);
  std::uint64_t first = 0, second = 0;
  Rates a, b;
  {
    Rates r = zero_rates(cloud.x.size());
    const auto one = sph::mutual_pair_pass(grid, kernel, r.out(), cloud.x.size(), start,
                                           [](Index) {}, pressure, viscosity, continuity);
    first = one.evaluations;
    a = r;
    a.visc_max = one.visc_max;
    const auto two = sph::mutual_pair_pass(grid, kernel, r.out(), cloud.x.size(), start,
                                           [](Index) {}, pressure, viscosity, continuity);
    second = two.evaluations;
    b = r;
    b.visc_max = two.visc_max;
  }
  EXPECT_EQ(first, gathered);
  EXPECT_EQ(second, gathered);
  for (std::size_t i = 0; i < cloud.x.size(); ++i) {
    ASSERT_EQ(a.acc[i], b.acc[i]) << i;
    ASSERT_EQ(a.drho[i], b.drho[i]) << i;
  }
  EXPECT_EQ(a.visc_max, b.visc_max);
  EXPECT_GT(a.visc_max, 0.0);
}

// Each particle receives its shares in an order the cells fix (the grid's
// write blocks), not the threads: one and two threads agree bit for bit.
TEST_P(MutualPass, SameBitsOnOneAndTwoThreads) {
  const sph::PressureForce pressure{cloud.nb()};
  const sph::ArtificialViscosity viscosity{cloud.nb(), 0.1 * kernel.h()};
  const sph::DensityDiffusion<true> diffusion{cloud.nb(), 0.1 * kernel.h() * 30.0, {0, -9.81, 0}};
  auto start = [&](Index i) { return start_of(cloud, i); };
  auto on_threads = [&](int threads) {
    omp_set_num_threads(threads);
    Rates r = zero_rates(cloud.x.size());
    r.visc_max = sph::mutual_pair_pass(grid, kernel, r.out(), cloud.x.size(), start,
                                       [](Index) {}, pressure, viscosity, diffusion)
                     .visc_max;
    return r;
  };
  const Rates one = on_threads(1), two = on_threads(2);
  for (std::size_t i = 0; i < cloud.x.size(); ++i) {
    ASSERT_EQ(one.acc[i], two.acc[i]) << i;
    ASSERT_EQ(one.drho[i], two.drho[i]) << i;
  }
  EXPECT_EQ(one.visc_max, two.visc_max);
}

// A fluid of one material and one mass: the terms on UniformNeighbourFields
// (which read neither field per pair) give the rates of the fields bit for
// bit, every term of the fluid-fluid pass.
TEST_P(MutualPass, OneMaterialAndMassGiveTheSameBitsWithoutReadingThem) {
  for (std::size_t i = 0; i < cloud.x.size(); ++i) {
    cloud.m[i] = cloud.m[0];
    cloud.mat[i] = 1;
  }
  use_material_viscosities();
  const sph::Neighbours fields = cloud.nb();
  sph::UniformNeighbourFields<double> uniform{fields};
  uniform.mass_of_all = cloud.m[0];
  uniform.material_of_all = 1;
  uniform.mass = nullptr;  // a read of either would crash
  uniform.material = nullptr;
  const double h = kernel.h(), eta2 = sph::laminar_eta2(h), delta_h_c0 = 0.1 * h * 30.0;
  const Vec3 g{0, -9.81, 0};
  auto same = [&](const auto& on_fields, const auto& on_uniform) {
    const Rates want = mutual(cloud, grid, kernel, on_fields);
    ASSERT_GT(largest(want.acc) + largest(want.drho), 0.0);
    const Rates got = mutual(cloud, grid, kernel, on_uniform);
    for (std::size_t i = 0; i < cloud.x.size(); ++i) {
      ASSERT_EQ(got.acc[i], want.acc[i]) << i;
      ASSERT_EQ(got.drho[i], want.drho[i]) << i;
    }
    EXPECT_EQ(got.visc_max, want.visc_max);
  };
  same(sph::PressureForce{fields}, sph::PressureForce{uniform});
  same(sph::ArtificialViscosity{fields, 0.1 * h}, sph::ArtificialViscosity{uniform, 0.1 * h});
  same(sph::LaminarViscosity<false>{fields, cloud.mu_of_material, eta2},
       sph::LaminarViscosity<false, decltype(uniform)>{uniform, cloud.mu_of_material, eta2});
  same(sph::Continuity{fields}, sph::Continuity{uniform});
  same(sph::DensityDiffusion<true>{fields, delta_h_c0, g},
       sph::DensityDiffusion<true, decltype(uniform)>{uniform, delta_h_c0, g});
}

// Mixed precision's fluid of one material and one mass: the terms on
// GatheredNeighbourFields read j's fields from the records, gathered eight
// at a time into the lanes, and give the rates of the float columns bit for
// bit, the dam break's terms and the laminar ones.
TEST_P(MutualPass, RecordsGiveTheBitsOfTheFloatColumns) {
  const std::size_t n = cloud.x.size();
  std::vector<Vec3f> v(n);
  std::vector<float> rho(n), p(n), c(n), inv_rho(n), m(n, static_cast<float>(cloud.m[0]));
  std::vector<std::int32_t> mat(n, 1);
  std::vector<sph::NeighbourRecord> records(n + 1);  // with the spare
  for (std::size_t i = 0; i < n; ++i) {
    v[i] = cloud.v[i];
    rho[i] = static_cast<float>(cloud.rho[i]);
    p[i] = static_cast<float>(cloud.p[i]);
    c[i] = static_cast<float>(cloud.c[i]);
    inv_rho[i] = static_cast<float>(1.0 / rho[i]);
    records[i] = {v[i].x, v[i].y, v[i].z, rho[i], p[i], c[i]};
    cloud.m[i] = m[i];
    cloud.mat[i] = 1;
  }
  use_material_viscosities();
  sph::UniformNeighbourFields<float> columns{{v.data(), rho.data(), p.data(), c.data(), m.data(), mat.data(),
                                              inv_rho.data(), nullptr}};
  columns.mass_of_all = m[0];
  columns.material_of_all = 1;
  sph::GatheredNeighbourFields<float> gathered{columns};
  gathered.record = records.data();
  gathered.velocity = nullptr;  // a read of any column would crash
  gathered.density = gathered.pressure = gathered.sound_speed = gathered.inv_density = nullptr;
  expect_records_match_columns(columns, gathered);
}

// The same in double: the records hold rho, p, c and 1/rho, v comes from
// its column, and the rates are those of the double columns bit for bit.
TEST_P(MutualPass, RecordsGiveTheBitsOfTheDoubleColumns) {
  const std::size_t n = cloud.x.size();
  std::vector<sph::NeighbourRecordDouble> records(n);
  for (std::size_t i = 0; i < n; ++i) {
    cloud.m[i] = cloud.m[0];
    cloud.mat[i] = 1;
    records[i] = {cloud.rho[i], cloud.p[i], cloud.c[i], cloud.inv_rho[i]};
  }
  use_material_viscosities();
  sph::UniformNeighbourFields<double> columns{cloud.nb()};
  columns.mass_of_all = cloud.m[0];
  columns.material_of_all = 1;
  sph::GatheredNeighbourFields<double> gathered{columns};
  gathered.record = records.data();
  gathered.density = gathered.pressure = gathered.sound_speed = gathered.inv_density = nullptr;  // a read would crash
  expect_records_match_columns(columns, gathered);
}

// On several MPI ranks the last rows are halo copies, whose rates are not
// wanted: the pass skips the pairs of two of them. The owned rows' rates are
// those of the whole pass bit for bit (every pair with an owned row is still
// evaluated, in the same order), and fewer pairs are counted. The time-step
// bound is the owned rows' own: the largest over their pairs, halo ones
// included, as a gather over the owned rows finds it.
TEST_P(MutualPass, SkipsPairsOfTwoHaloCopiesAndKeepsTheOwnedRates) {
  const sph::PressureForce pressure{cloud.nb()};
  const sph::ArtificialViscosity viscosity{cloud.nb(), 0.1 * kernel.h()};
  std::uint64_t all_pairs = 0, owned_pairs = 0;
  const Rates whole = mutual(cloud, grid, kernel, pressure, SIZE_MAX, &all_pairs);
  const std::size_t owned = 2 * cloud.x.size() / 3;
  const Rates part = mutual(cloud, grid, kernel, pressure, owned, &owned_pairs);
  for (std::size_t i = 0; i < owned; ++i) {
    ASSERT_EQ(part.acc[i], whole.acc[i]) << i;
    ASSERT_EQ(part.drho[i], whole.drho[i]) << i;
  }
  const double bound = gather(cloud, grid, kernel, viscosity, owned).visc_max;
  EXPECT_NEAR(mutual(cloud, grid, kernel, viscosity, owned).visc_max, bound, 1e-12 * bound);
  EXPECT_LT(owned_pairs, all_pairs);
  EXPECT_GT(owned_pairs, all_pairs / 2);
}

// Each lane gets its own record's fields, whatever the order of the rows and
// past a whole eight (the spare lanes of the last eight hold a real row).
TEST(NeighbourRecords, GatherEachLanesOwnFields) {
  std::vector<sph::NeighbourRecord> records(41);  // 40 rows and the spare
  for (std::size_t i = 0; i < records.size(); ++i) {
    const float f = static_cast<float>(i);
    records[i] = {f + 0.1f, f + 0.2f, f + 0.3f, 1000.0f + f, 50.0f * f, 30.0f + f};
  }
  const int n = 13;
  Index j[16] = {39, 0, 7, 7, 21, 3, 38, 12, 5, 30, 1, 16, 9, 39, 39, 39};
  sph::GatheredLanes<16> lanes{};
  sph::gather_records(records.data(), j, n, lanes);
  for (int k = 0; k < n; ++k) {
    const sph::NeighbourRecord& r = records[j[k]];
    EXPECT_EQ(lanes.vx[k], r.vx) << k;
    EXPECT_EQ(lanes.vy[k], r.vy) << k;
    EXPECT_EQ(lanes.vz[k], r.vz) << k;
    EXPECT_EQ(lanes.rho[k], r.rho) << k;
    EXPECT_EQ(lanes.p[k], r.p) << k;
    EXPECT_EQ(lanes.c[k], r.c) << k;
    EXPECT_EQ(lanes.inv_rho[k], static_cast<float>(1.0 / r.rho)) << k;  // as the stage's column
  }
}

// Records of doubles: each lane its own record's rho, p, c and 1/rho and
// its own row of the velocity column, past a whole four and eight, up to
// the column's last row.
TEST(NeighbourRecords, GatherEachLanesOwnFieldsInDouble) {
  std::vector<sph::NeighbourRecordDouble> records(40);
  std::vector<Vec3> velocity(40);
  for (std::size_t i = 0; i < records.size(); ++i) {
    const double f = static_cast<double>(i);
    records[i] = {1000.0 + f / 3.0, 50.0 * f, 30.0 + f, 1.0 / (1000.0 + f / 3.0)};
    velocity[i] = Vec3{f + 0.1, f + 0.2, f + 0.3};
  }
  const int n = 13;
  Index j[16] = {39, 0, 7, 7, 21, 3, 38, 12, 5, 30, 1, 16, 9, 39, 39, 39};
  sph::GatheredLanes<16> lanes{};
  sph::gather_records(records.data(), velocity.data(), j, n, lanes);
  for (int k = 0; k < n; ++k) {
    const sph::NeighbourRecordDouble& r = records[j[k]];
    EXPECT_EQ(lanes.vx[k], velocity[j[k]].x) << k;
    EXPECT_EQ(lanes.vy[k], velocity[j[k]].y) << k;
    EXPECT_EQ(lanes.vz[k], velocity[j[k]].z) << k;
    EXPECT_EQ(lanes.rho[k], r.rho) << k;
    EXPECT_EQ(lanes.p[k], r.p) << k;
    EXPECT_EQ(lanes.c[k], r.c) << k;
    EXPECT_EQ(lanes.inv_rho[k], r.inv_rho) << k;
  }
}

// The write blocks cover level 0 only: a grid that binned points on a
// higher level (per-point radii) is refused, not half evaluated.
TEST(MutualPassGrid, RefusesAGridWithPointsBeyondItsFirstLevel) {
  const Cloud c = make_cloud(3, 8, {false, false, false}, 5u);
  const ParamValues none;
  const kernels::CubicSpline spline(none);
  const KernelTable kernel(spline, 3, 1.3 * c.dp);
  std::vector<double> radius(c.x.size(), kernel.support_radius());
  radius[7] = 4.0 * kernel.support_radius();
  NeighbourGrid grid;
  grid.configure(3, c.lo, c.hi, kernel.support_radius());
  grid.build(c.x, radius);
  Rates r = zero_rates(c.x.size());
  auto start = [&](Index i) { return start_of(c, i); };
  EXPECT_THROW(sph::mutual_pair_pass(grid, kernel, r.out(), c.x.size(), start, [](Index) {},
                                     sph::PressureForce{c.nb()}),
               RunError);
  grid.build(c.x);
  EXPECT_GT(sph::mutual_pair_pass(grid, kernel, r.out(), c.x.size(), start, [](Index) {},
                                  sph::PressureForce{c.nb()})
                .evaluations,
            0u);
}

INSTANTIATE_TEST_SUITE_P(Layouts, MutualPass,
                         ::testing::Values(Layout{2, {false, false, false}, 1}, Layout{2, {true, false, false}, 2},
                                           Layout{3, {false, false, false}, 1}, Layout{3, {false, false, false}, 2},
                                           Layout{3, {true, true, false}, 2}));

}  // namespace
}  // namespace talus
