// The released part of a block system: blocks joined to the fixed base only
// through sticking joints are held; a group held by slipping or open joints
// alone is released, with its share of the free mass.
#include <gtest/gtest.h>

#include "slip_path.hpp"

using namespace talus;
using namespace talus::dda;
using talus::strength_reduction::released_blocks;

namespace {

// Block 0 fixed (base), blocks 1..n free with masses 1, 2, 4, ...
BlockSet stack(int free_blocks) {
  BlockSet b;
  for (int i = 0; i <= free_blocks; ++i) {
    b.name.push_back("b" + std::to_string(i));
    b.fixed.push_back(i == 0);
    b.kinematic.push_back(false);
    b.mass.push_back(i == 0 ? 1e6 : double(1 << (i - 1)));
  }
  return b;
}

// Every block its own rigid body.
std::vector<std::uint32_t> singles(const BlockSet& b) {
  std::vector<std::uint32_t> r(b.size());
  for (std::uint32_t i = 0; i < r.size(); ++i) r[i] = i;
  return r;
}

void add(ContactSet& c, std::uint32_t a, std::uint32_t b, std::uint8_t state) {
  c.resize(c.size() + 1);
  c.key.back() = {0, a, b, 0};
  c.state.back() = state;
}

}  // namespace

TEST(SlipPath, StickingJointsHoldAndSlippingOnesRelease) {
  const BlockSet b = stack(3);
  ContactSet c;
  add(c, 0, 1, contact_stick | contact_bonded);
  add(c, 1, 2, contact_slip);
  add(c, 2, 3, contact_stick);
  auto r = released_blocks(b, c, singles(b));
  EXPECT_EQ(r.blocks, (std::vector<std::uint32_t>{2, 3}));  // 2 and 3 ride on a slipping joint together
  EXPECT_DOUBLE_EQ(r.mass_fraction, 6.0 / 7.0);

  c.state[1] = contact_stick;  // everything sticks: nothing released
  EXPECT_TRUE(released_blocks(b, c, singles(b)).blocks.empty());

  c.state[0] = contact_open;  // the whole column lifted off the base
  r = released_blocks(b, c, singles(b));
  EXPECT_EQ(r.blocks.size(), 3u);
  EXPECT_DOUBLE_EQ(r.mass_fraction, 1.0);
}

TEST(SlipPath, ABlockTouchingNothingIsReleased) {
  const BlockSet b = stack(2);
  ContactSet c;
  add(c, 0, 1, contact_stick);
  const auto r = released_blocks(b, c, singles(b));
  EXPECT_EQ(r.blocks, (std::vector<std::uint32_t>{2}));
}

TEST(SlipPath, TheBlocksOfAClumpAreHeldTogether) {
  const BlockSet b = stack(3);
  ContactSet c;
  add(c, 0, 1, contact_stick);
  add(c, 1, 2, contact_slip);
  add(c, 0, 3, contact_slip);
  EXPECT_EQ(released_blocks(b, c, singles(b)).blocks, (std::vector<std::uint32_t>{2, 3}));
  // Blocks 2 and 3 one clump led by 2, block 1 its own: the clump has no sticking joint.
  EXPECT_EQ(released_blocks(b, c, {0, 1, 2, 2}).blocks, (std::vector<std::uint32_t>{2, 3}));
  // Blocks 1 and 3 one clump: block 1 sticks to the base, so the clump holds; 2 slides off it.
  EXPECT_EQ(released_blocks(b, c, {0, 1, 2, 1}).blocks, (std::vector<std::uint32_t>{2}));
}
