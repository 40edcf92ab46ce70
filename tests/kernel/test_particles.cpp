#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "cell_order.hpp"
#include "store_rows.hpp"
#include "talus/particles.hpp"

namespace talus {
namespace {

TEST(ParticleStore, FieldsAreAllocatedOnlyWhenRequested) {
  ParticleStore s;
  EXPECT_FALSE(s.has("mu_eff"));
  s.append(3);
  s.require({"mu_eff", FieldType::scalar, "Pa s", true, false});
  ASSERT_TRUE(s.has("mu_eff"));
  EXPECT_EQ(s.scalar("mu_eff").size(), 3u);
  EXPECT_THROW(s.require({"mu_eff", FieldType::vector, "", true, false}), std::logic_error);
  EXPECT_THROW(s.scalar("strain_rate"), std::logic_error);
}

// Mixed precision: a field whose metadata allows it is stored in float, moves with the
// particles like any other, and is widened to double, exactly, as soon as code that reads it in
// double requires it; a field that does not allow it, and the position, stay in double.
TEST(ParticleStore, MixedPrecisionKeepsAllowedFieldsInFloat) {
  ParticleStore s;
  s.set_mixed_precision(true);
  FieldInfo rho{"density", FieldType::scalar, "kg/m^3", true, true};
  rho.single_when_mixed = true;
  FieldInfo v{"velocity", FieldType::vector, "m/s", true, true};
  v.single_when_mixed = true;
  s.require(rho);
  s.require(v);
  s.require({"pressure", FieldType::scalar, "Pa", true, false});
  s.append(3);
  EXPECT_EQ(s.info("density").type, FieldType::scalar_f32);
  EXPECT_EQ(s.info("velocity").type, FieldType::vector_f32);
  EXPECT_EQ(s.info("pressure").type, FieldType::scalar);
  EXPECT_EQ(s.info("position").type, FieldType::vector);
  EXPECT_EQ(ParticleStore::element_bytes(FieldType::scalar_f32), 4u);
  EXPECT_EQ(ParticleStore::element_bytes(FieldType::vector_f32), 12u);
  EXPECT_EQ(s.bytes("velocity").size(), 36u);
  EXPECT_THROW(s.scalar("density"), std::logic_error);  // not readable as double
  EXPECT_THROW(s.vector("velocity"), std::logic_error);
  EXPECT_THROW(s.set_mixed_precision(false), std::logic_error);  // too late: a float field exists

  // Stored in float: rounded once, to the nearest float.
  const double value = 1000.0 + 1.0 / 3.0;
  s.column<float>("density")[1] = static_cast<float>(value);
  s.column<Vec3f>("velocity")[2] = Vec3{0.1, -0.2, 0.3};
  EXPECT_EQ(s.scalar_f32("density")[1], static_cast<float>(value));
  EXPECT_NE(static_cast<double>(s.scalar_f32("density")[1]), value);
  EXPECT_EQ(Vec3(s.vector_f32("velocity")[2]).y, static_cast<double>(-0.2f));
  double seen = 0.0;
  s.visit_scalar("density", [&](auto c) { seen = c[1]; });
  EXPECT_EQ(seen, static_cast<double>(static_cast<float>(value)));

  // Reordered and removed with the other fields.
  const std::vector<Index> order{2, 1, 0};
  s.reorder(order);
  EXPECT_EQ(Vec3(s.vector_f32("velocity")[0]).z, static_cast<double>(0.3f));
  s.remove_if(std::vector<std::uint8_t>{1, 0, 0});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.scalar_f32("density")[0], static_cast<float>(value));

  // A second registration that allows float keeps it; one that does not widens the field.
  s.require(rho);
  EXPECT_EQ(s.info("density").type, FieldType::scalar_f32);
  s.require({"density", FieldType::scalar, "kg/m^3", true, true});
  EXPECT_EQ(s.info("density").type, FieldType::scalar);
  EXPECT_FALSE(s.info("density").single_when_mixed);
  EXPECT_EQ(s.scalar("density")[0], static_cast<double>(static_cast<float>(value)));
  s.require(rho);  // widened for good
  EXPECT_EQ(s.info("density").type, FieldType::scalar);
  EXPECT_THROW(s.require({"velocity", FieldType::scalar, "", true, true}), std::logic_error);

  // Without mixed precision the same metadata gives double.
  ParticleStore d;
  d.require(rho);
  EXPECT_EQ(d.info("density").type, FieldType::scalar);
  FieldInfo count{"count", FieldType::integer, "", false, true};
  count.single_when_mixed = true;
  ParticleStore m;
  m.set_mixed_precision(true);
  EXPECT_THROW(m.require(count), std::logic_error);  // only reals can be kept in float
}

// The re-sort's order: by cell (z, then y, then x), stable within a cell, points outside the box in
// its edge cells, and a box far larger than the points costs a bounded grid, not one cell per spacing.
TEST(CellOrder, SortsByCellAndBoundsTheGrid) {
  const std::vector<Vec3> x{{0.5, 0.5, 1.5}, {1.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {-7, 0.2, 0.1}, {0.6, 0.4, 0.3}};
  const std::vector<Index> order = cell_order(x, {0, 0, 0}, {2, 2, 2}, 1.0, 3);
  EXPECT_EQ(order, (std::vector<Index>{2, 3, 4, 1, 0}));
  const std::vector<Vec3> far{{0, 0, 0}, {1e7, 1e7, 1e7}, {5e6, 0, 0}};
  const std::vector<Index> sparse = cell_order(far, {0, 0, 0}, {1e7, 1e7, 1e7}, 0.01, 3);  // 1e27 cells asked
  EXPECT_EQ(sparse, (std::vector<Index>{0, 2, 1}));
}

// The two counting sorts (by row of cells, then by column) give the order of one stable sort by
// cell, on points spread over many rows, some of them empty, and outside the box.
TEST(CellOrder, EqualsAStableSortByCell) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  std::vector<Vec3> x(5000);
  for (Vec3& p : x) p = {u(rng), u(rng), 0.5 * u(rng)};  // the upper half of the box is empty
  const Vec3 lo{0, 0, 0}, hi{1, 1, 1};
  const double cell = 0.07;  // 14 cells along each axis
  auto axis = [](double v) { return std::clamp(static_cast<int>(std::floor(v * 14)), 0, 13); };
  auto key = [&](Index i) { return (axis(x[i].z) * 14 + axis(x[i].y)) * 14 + axis(x[i].x); };
  std::vector<Index> expected(x.size());
  std::iota(expected.begin(), expected.end(), Index{0});
  std::stable_sort(expected.begin(), expected.end(), [&](Index a, Index b) { return key(a) < key(b); });
  EXPECT_EQ(cell_order(x, lo, hi, cell, 3), expected);
}

// Reordering works cycle by cycle in place: many cycles of every length, fixed points included,
// across the 64-particle words of its bookkeeping.
TEST(ParticleStore, ReorderAppliesAnyPermutationInPlace) {
  ParticleStore s;
  s.require({"rho", FieldType::scalar, "kg/m^3", true, true});
  const std::size_t n = 1000;
  s.append(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.scalar("rho")[i] = static_cast<double>(i);
    s.position()[i] = {0, static_cast<double>(i), 0};
    s.material()[i] = static_cast<std::int32_t>(i);
  }
  std::vector<Index> order(n);
  for (std::size_t i = 0; i < 100; ++i) order[i] = static_cast<Index>(i);        // fixed points
  for (std::size_t i = 100; i < 200; ++i) order[i] = static_cast<Index>(299 - i);  // cycles of two
  for (std::size_t i = 200; i < n; ++i) order[i] = static_cast<Index>(200 + (i * 7919 + 13) % 800);  // long ones
  s.reorder(order);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(s.ids()[i], order[i]);
    EXPECT_EQ(s.scalar("rho")[i], static_cast<double>(order[i]));
    EXPECT_EQ(s.position()[i].y, static_cast<double>(order[i]));
    EXPECT_EQ(s.material()[i], static_cast<std::int32_t>(order[i]));
  }
  std::vector<Index> twice(n, 0);  // not a permutation: refused, never a loop without end
  EXPECT_THROW(s.reorder(twice), std::logic_error);
}

TEST(ParticleStore, ReorderAndRemoveKeepEveryFieldAndId) {
  ParticleStore s;
  s.require({"rho", FieldType::scalar, "kg/m^3", true, true});
  s.append(5);
  auto rho = s.scalar("rho");
  auto x = s.position();
  for (std::size_t i = 0; i < 5; ++i) {
    rho[i] = 1000.0 + static_cast<double>(i);
    x[i] = {static_cast<double>(i), 0, 0};
  }
  const std::vector<Index> order{4, 2, 0, 1, 3};
  s.reorder(order);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(s.ids()[i], order[i]);
    EXPECT_EQ(s.scalar("rho")[i], 1000.0 + order[i]);
    EXPECT_EQ(s.position()[i].x, static_cast<double>(order[i]));
  }
  const std::vector<std::uint8_t> drop{0, 1, 0, 0, 1};  // ids 2 and 3
  EXPECT_EQ(s.remove_if(drop), 2u);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.ids()[0], 4u);
  EXPECT_EQ(s.ids()[1], 0u);
  EXPECT_EQ(s.ids()[2], 1u);
  EXPECT_EQ(s.scalar("rho")[2], 1001.0);
  // New particles get fresh global ids, never reused ones.
  EXPECT_EQ(s.append(1), 3u);
  EXPECT_EQ(s.ids()[3], 5u);
}

TEST(ParticleStore, HaloRowsStayBehindTheOwnedOnes) {
  ParticleStore s;
  s.append(3);
  EXPECT_EQ(s.append_halo(2), 3u);
  EXPECT_EQ(s.size(), 5u);
  EXPECT_EQ(s.owned_size(), 3u);
  EXPECT_EQ(s.halo_size(), 2u);
  EXPECT_EQ(s.next_id(), 3u);  // halo rows carry their owners' ids, not new ones
  // Appending, re-sorting and removing would mix owned and halo rows.
  EXPECT_THROW(s.append(1), std::logic_error);
  const std::vector<Index> order{0, 1, 2, 3, 4};
  EXPECT_THROW(s.reorder(order), std::logic_error);
  const std::vector<std::uint8_t> none(5, 0);
  EXPECT_THROW(s.remove_if(none), std::logic_error);
  s.drop_halo();
  EXPECT_EQ(s.size(), 3u);
  EXPECT_EQ(s.halo_size(), 0u);
  EXPECT_EQ(s.position().size(), 3u);
  EXPECT_EQ(s.append(1), 3u);
}

TEST(StoreRows, PackedRowsUnpackIntoAnotherStoreFieldByField) {
  ParticleStore a, b;
  for (ParticleStore* s : {&a, &b}) {
    s->require({"rho", FieldType::scalar, "kg/m^3", true, true});
    s->require({"flag", FieldType::integer, "", true, true});
  }
  a.append(4);
  for (std::size_t i = 0; i < 4; ++i) {
    a.scalar("rho")[i] = 1000.0 + static_cast<double>(i);
    a.integer("flag")[i] = static_cast<std::int32_t>(10 * i);
    a.position()[i] = {0.5 * static_cast<double>(i), -1.0, 2.0};
  }
  const auto fields = all_fields(a);
  EXPECT_EQ(row_bytes(a, fields), 8u + 4u + 4u + 24u + 8u + 4u);  // id body material position rho flag
  std::vector<std::byte> packet;
  const std::vector<Index> rows{3, 1};
  pack_rows(a, fields, rows, packet);
  ASSERT_EQ(packet.size(), 2 * row_bytes(a, fields));
  b.append(1);
  b.append_halo(2);
  unpack_rows(b, fields, packet, 1, 2);
  EXPECT_EQ(b.ids()[1], 3u);
  EXPECT_EQ(b.ids()[2], 1u);
  EXPECT_EQ(b.scalar("rho")[1], 1003.0);
  EXPECT_EQ(b.integer("flag")[2], 10);
  EXPECT_EQ(b.position()[1].x, 1.5);
  // A subset of fields: only those are overwritten.
  const std::vector<std::string> rho_only{"rho"};
  std::vector<std::byte> small;
  a.scalar("rho")[1] = -7.0;
  pack_rows(a, rho_only, std::vector<Index>{1}, small);
  unpack_rows(b, rho_only, small, 2, 1);
  EXPECT_EQ(b.scalar("rho")[2], -7.0);
  EXPECT_EQ(b.integer("flag")[2], 10);
  EXPECT_THROW(unpack_rows(b, rho_only, small, 2, 2), std::logic_error);
}

}  // namespace
}  // namespace talus
