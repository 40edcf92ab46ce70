// Checkpoints are refused, with a message naming the file and the problem,
// when they are damaged (checksum, length, version) or intact but wrong for
// the scene (indices, counts, values): real checkpoints of small runs,
// corrupted byte by byte and field by field.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "checkpoint.hpp"
#include "crc32.hpp"
#include "plugin_registry.hpp"
#include "process.hpp"
#include "scene.hpp"
#include "simulation.hpp"
#include "talus/blocks.hpp"
#include "talus/error.hpp"
#include "talus/world.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using talus::test::read_file;
using talus::test::run_command;
using talus::test::write_file;

namespace {

constexpr std::size_t header = 20;  // magic and version (8), payload length (8), CRC-32 (4)

// One folder per test process: ctest runs the tests of a suite side by side,
// each in its own process, and each sets the suite up again.
std::string scratch(const std::string& name) {
  const fs::path dir =
      fs::path(TALUS_BINARY_DIR) / "tests" / "checkpoint_scratch" / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

// A scene edited to a few steps without outputs, written beside its checkpoints.
std::string short_scene(const std::string& source, const std::string& dir, double end) {
  std::ifstream in(source);
  json scene = json::parse(in);
  scene["time"]["end"] = end;
  scene.erase("checkpoint");
  scene["outputs"] = json::array();
  const std::string path = dir + "/scene.json";
  write_file(path, scene.dump(1));
  return path;
}

struct Loaded {
  talus::PluginRegistry registry;
  std::unique_ptr<talus::Simulation> sim;
  explicit Loaded(const std::string& scene) {
    registry.add_default_locations();
    sim = std::make_unique<talus::Simulation>(registry, talus::load_scene(scene, registry));
  }
  talus::World& world() { return sim->world(); }
};

// Runs the scene to its end and writes the checkpoint of that state.
std::string make_checkpoint(const std::string& scene, const std::string& dir) {
  Loaded run(scene);
  talus::RunOptions o;
  o.output_directory = dir + "/out";
  o.quiet = true;
  EXPECT_EQ(run.sim->run(o), 0);
  const std::string path = dir + "/state.checkpoint";
  run.sim->write_checkpoint(path);
  return path;
}

// The message a fresh simulation of the scene refuses the checkpoint with;
// empty if it accepts it.
std::string refusal(const std::string& scene, const std::string& checkpoint) {
  Loaded run(scene);
  try {
    run.sim->read_checkpoint(checkpoint);
  } catch (const talus::InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("not an InputError: ") + e.what();
  }
  return "";
}

template <class T>
T get(const std::string& bytes, std::size_t at) {
  T v{};
  std::memcpy(&v, bytes.data() + at, sizeof v);
  return v;
}

template <class T>
void put(std::string& bytes, std::size_t at, T v) {
  std::memcpy(bytes.data() + at, &v, sizeof v);
}

// Writes a new length and checksum, so that only the field checks can object.
void reseal(std::string& bytes) {
  put<std::uint64_t>(bytes, 8, bytes.size() - header);
  put<std::uint32_t>(bytes, 16, talus::crc32(bytes.data() + header, bytes.size() - header));
}

// Where the stage and boundary model states and the fluid store start in the payload.
struct Layout {
  std::vector<std::size_t> stage_state;  // first byte of each stage's state
  std::size_t boundary_count = 0;        // the number of boundary model states
  std::size_t fluid_count = 0;           // the fluid particle count
};

Layout layout(const std::string& bytes) {
  Layout l;
  std::size_t at = header + 5 * 8;                     // scene hash, time, step, removed, last output time
  for (int k = 0; k < 2; ++k) at += 8 + get<std::uint64_t>(bytes, at);  // output times, output steps
  const auto stages = get<std::uint64_t>(bytes, at);
  at += 8;
  for (std::uint64_t s = 0; s < stages; ++s) {
    l.stage_state.push_back(at + 8);
    at += 8 + get<std::uint64_t>(bytes, at);
  }
  l.boundary_count = at;
  const auto boundaries = get<std::uint64_t>(bytes, at);
  at += 8;
  for (std::uint64_t s = 0; s < boundaries; ++s) at += 8 + get<std::uint64_t>(bytes, at);
  l.fluid_count = at;
  return l;
}

class CheckpointTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string dir = scratch("wcsph");
    scene_ = short_scene(std::string(TALUS_SOURCE_DIR) + "/tests/verification/water_drop_2d.json", dir, 0.004);
    good_ = make_checkpoint(scene_, dir);
    bytes_ = read_file(good_);
    bad_ = dir + "/bad.checkpoint";
  }
  static void TearDownTestSuite() { fs::remove_all(fs::path(scene_).parent_path()); }
  std::string refused(const std::string& bytes) {
    write_file(bad_, bytes);
    return refusal(scene_, bad_);
  }
  // The message starts as every checkpoint refusal does, naming the file.
  void expect_refused(const std::string& message, const std::string& what) {
    EXPECT_EQ(message.rfind("error: checkpoint " + bad_ + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << "expected '" << what << "' in: " << message;
  }
  static std::string scene_, good_, bad_, bytes_;
};

std::string CheckpointTest::scene_, CheckpointTest::good_, CheckpointTest::bad_, CheckpointTest::bytes_;

// A field kept in float (mixed precision) is saved and loaded in float, bit for bit; a store
// that keeps it in double refuses the file and names both types.
TEST(Checkpoint, KeepsAFieldInTheFloatItWasSavedIn) {
  const std::string dir = scratch("float_field");
  talus::FieldInfo density{"density", talus::FieldType::scalar, "kg/m^3", true, true};
  density.single_when_mixed = true;
  talus::FieldInfo velocity{"velocity", talus::FieldType::vector, "m/s", true, true};
  velocity.single_when_mixed = true;
  auto make = [&](talus::World& w, bool mixed) {
    w.lo = {-1, -1, -1};
    w.hi = {1, 1, 1};
    w.dp = 0.1;
    talus::Body body;
    body.name = "water";
    body.kind = talus::BodyKind::fluid;
    body.material = 0;
    w.bodies.push_back(body);
    talus::Material water;
    water.name = "water";
    water.density = 1000.0;
    w.materials.push_back(water);
    w.fluid.set_mixed_precision(mixed);
    w.fluid.require(density);
    w.fluid.require(velocity);
  };
  talus::World saved;
  make(saved, true);
  saved.fluid.append(5);
  for (std::size_t i = 0; i < 5; ++i) {
    saved.fluid.position()[i] = {0.1 * static_cast<double>(i), 0.0, 0.0};
    saved.fluid.scalar_f32("density")[i] = 1000.0f + 0.1f * static_cast<float>(i);
    saved.fluid.vector_f32("velocity")[i] = talus::Vec3{1.0 / 3.0, -static_cast<double>(i), 2.5};
  }
  const std::string path = dir + "/float.ckpt";
  talus::save_checkpoint(path, saved, talus::RunState{});

  talus::World loaded;
  make(loaded, true);
  talus::load_checkpoint(path, loaded, 0);
  ASSERT_EQ(loaded.fluid.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(loaded.fluid.scalar_f32("density")[i], saved.fluid.scalar_f32("density")[i]);
    EXPECT_EQ(talus::Vec3(loaded.fluid.vector_f32("velocity")[i]),
              talus::Vec3(saved.fluid.vector_f32("velocity")[i]));
  }

  talus::World in_double;
  make(in_double, false);
  try {
    talus::load_checkpoint(path, in_double, 0);
    FAIL() << "a float field was loaded into a double one";
  } catch (const talus::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("is scalar_f32, this scene's is scalar"), std::string::npos) << what;
  }
}

TEST(Crc32, MatchesTheStandardCheckValue) {
  EXPECT_EQ(talus::crc32("123456789", 9), 0xCBF43926u);
  EXPECT_EQ(talus::crc32("12345", 5, talus::crc32("", 0)), talus::crc32("12345", 5));
  EXPECT_EQ(talus::crc32("6789", 4, talus::crc32("12345", 5)), 0xCBF43926u);  // incremental
}

TEST(Crc32, CombinesTheChecksumsOfTwoParts) {
  EXPECT_EQ(talus::crc32_combine(talus::crc32("12345", 5), talus::crc32("6789", 4), 4), 0xCBF43926u);
  EXPECT_EQ(talus::crc32_combine(0, talus::crc32("123456789", 9), 9), 0xCBF43926u);  // empty first part
  EXPECT_EQ(talus::crc32_combine(talus::crc32("123456789", 9), 0, 0), 0xCBF43926u);  // empty second part
  // Parts of every length from 0 to 3000 bytes of pseudo-random data.
  std::vector<unsigned char> bytes(3000);
  std::uint32_t state = 12345;
  for (auto& b : bytes) b = static_cast<unsigned char>((state = state * 1103515245u + 12345u) >> 16);
  const std::uint32_t whole = talus::crc32(bytes.data(), bytes.size());
  for (std::size_t cut = 0; cut <= bytes.size(); cut += 97) {
    const std::size_t rest = bytes.size() - cut;
    EXPECT_EQ(talus::crc32_combine(talus::crc32(bytes.data(), cut), talus::crc32(bytes.data() + cut, rest), rest),
              whole)
        << "cut at " << cut;
  }
}

TEST_F(CheckpointTest, AnIntactCheckpointIsAccepted) {
  EXPECT_EQ(refusal(scene_, good_), "");
  ASSERT_GT(bytes_.size(), 1000u);
  EXPECT_EQ(bytes_.substr(0, 8), "TALUSCK3");
}

TEST_F(CheckpointTest, EveryFlippedByteIsRefused) {
  std::vector<std::size_t> offsets;
  for (std::size_t i = 0; i < header; ++i) offsets.push_back(i);
  for (std::size_t i = header; i < bytes_.size(); i += bytes_.size() / 150) offsets.push_back(i);
  offsets.push_back(bytes_.size() - 1);
  for (std::size_t at : offsets) {
    std::string bytes = bytes_;
    bytes[at] = static_cast<char>(bytes[at] ^ 0x5A);
    const std::string m = refused(bytes);
    SCOPED_TRACE("byte " + std::to_string(at));
    if (at < 7) expect_refused(m, "not a Talus checkpoint");
    else if (at == 7) expect_refused(m, "format version");
    else if (at < 16) expect_refused(m, "the header promises");
    else expect_refused(m, "checksum mismatch");
  }
}

TEST_F(CheckpointTest, ATruncatedOrExtendedFileIsRefused) {
  expect_refused(refused(""), "not a Talus checkpoint");
  expect_refused(refused(bytes_.substr(0, 12)), "truncated");
  for (std::size_t size : {header, header + 1, bytes_.size() / 2, bytes_.size() - 1})
    expect_refused(refused(bytes_.substr(0, size)), "the header promises");
  expect_refused(refused(bytes_ + "x"), "the header promises");
}

TEST_F(CheckpointTest, AnOlderFormatVersionIsRefusedByName) {
  std::string bytes = bytes_;
  bytes[7] = '1';
  const std::string m = refused(bytes);
  expect_refused(m, "format version 1; this talus reads version 3");
}

// The checksum is recomputed: only the field checks stand between these and the solver.
TEST_F(CheckpointTest, AMaterialIndexOutOfRangeIsRefused) {
  for (int bad : {1, 7, -1, 1 << 30}) {
    Loaded run(scene_);
    run.sim->read_checkpoint(good_);
    run.world().fluid.material()[3] = bad;
    run.sim->write_checkpoint(bad_);
    SCOPED_TRACE(bad);
    expect_refused(refusal(scene_, bad_), "fluid particle 3 has material index " + std::to_string(bad));
  }
}

TEST_F(CheckpointTest, ABodyIndexOutOfRangeOrOfTheWrongKindIsRefused) {
  {
    Loaded run(scene_);
    run.sim->read_checkpoint(good_);
    run.world().fluid.body()[5] = 9;
    run.sim->write_checkpoint(bad_);
    expect_refused(refusal(scene_, bad_), "fluid particle 5 has body index 9; the scene has 2 bodies");
  }
  {
    Loaded run(scene_);
    run.sim->read_checkpoint(good_);
    run.world().fluid.body()[5] = 1;  // the tank
    run.sim->write_checkpoint(bad_);
    expect_refused(refusal(scene_, bad_), "belongs to body 'tank', which is a wall, not a fluid");
  }
  {
    Loaded run(scene_);
    run.sim->read_checkpoint(good_);
    run.world().boundary.body()[2] = 0;  // the water has no wall particles
    run.sim->write_checkpoint(bad_);
    expect_refused(refusal(scene_, bad_), "boundary particle 2 belongs to body 'water', which has no boundary particles");
  }
}

TEST_F(CheckpointTest, NonFiniteOrFarAwayValuesAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto with = [&](auto&& edit, const std::string& what) {
    Loaded run(scene_);
    run.sim->read_checkpoint(good_);
    edit(run.world());
    run.sim->write_checkpoint(bad_);
    SCOPED_TRACE(what);
    expect_refused(refusal(scene_, bad_), what);
  };
  with([&](talus::World& w) { w.fluid.position()[4].x = nan; }, "fluid particle 4 has a non-finite position");
  with([&](talus::World& w) { w.fluid.position()[4].y = 1e300; }, "fluid particle 4 at (");
  with([&](talus::World& w) { w.boundary.position()[0].x = -1e6; }, "boundary particle 0 at (");
  with([&](talus::World& w) { w.fluid.scalar("density")[8] = -1.0; }, "fluid particle 8 has density -1, not > 0");
  with([&](talus::World& w) { w.fluid.vector("velocity")[8].y = INFINITY; }, "non-finite velocity");
  with([&](talus::World& w) { w.time = 1e9; }, "time 1e+09 s is outside the run");
  with([&](talus::World& w) { w.fluid.ids()[0] = 1ull << 62; }, "fluid particle 0 has id");
}

TEST_F(CheckpointTest, AChangedParticleCountIsRefused) {
  const Layout l = layout(bytes_);
  const auto n = get<std::uint64_t>(bytes_, l.fluid_count);
  ASSERT_GT(n, 10u);
  ASSERT_LT(n, 10000u);
  for (std::uint64_t count : {n + 1, n - 1, std::uint64_t{1} << 60}) {
    std::string bytes = bytes_;
    put<std::uint64_t>(bytes, l.fluid_count, count);
    reseal(bytes);
    SCOPED_TRACE(count);
    const std::string m = refused(bytes);
    if (count > n + 1) expect_refused(m, "the fluid store claims " + std::to_string(count) + " particles");
    else expect_refused(m, "fluid field '");
  }
}

TEST_F(CheckpointTest, AnUnreadableStageStateIsRefusedNamingTheStage) {
  const Layout l = layout(bytes_);
  ASSERT_EQ(l.stage_state.size(), 1u);
  std::string bytes = bytes_;
  bytes[l.stage_state[0]] = 'x';  // the wcsph step counter
  reseal(bytes);
  expect_refused(refused(bytes), "stage 1 (wcsph): the wcsph stage's state");
}

// A boundary model's state that this scene has no model for (the water drop has one, its walls').
TEST_F(CheckpointTest, ABoundaryModelStateTheSceneLacksIsRefused) {
  const Layout l = layout(bytes_);
  ASSERT_EQ(get<std::uint64_t>(bytes_, l.boundary_count), 1u);
  std::string bytes = bytes_;
  put<std::uint64_t>(bytes, l.boundary_count, 2);
  bytes.insert(l.boundary_count + 8, 8, '\0');  // one more, empty, state
  reseal(bytes);
  expect_refused(refused(bytes), "it has the state of 2 boundary models, this scene has 1");
}

TEST_F(CheckpointTest, TalusRunRefusesWithExitTwoAndWritesNothing) {
  std::string bytes = bytes_;
  bytes[bytes.size() / 2] ^= 1;
  write_file(bad_, bytes);
  const std::string out = fs::path(bad_).parent_path().string() + "/never";
  const auto r = run_command(std::string(TALUS_EXE) + " run " + scene_ + " --quiet --out " + out + " --restart " + bad_);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.rfind("error: checkpoint " + bad_ + ": checksum mismatch", 0), 0u) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// Blocks: counts must match the scene, contact keys must name its blocks.
class BlockCheckpointTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string dir = scratch("dda");
    scene_ = short_scene(std::string(TALUS_SHARE_DIR) + "/scenes/block_on_incline.json", dir, 0.02);
    good_ = make_checkpoint(scene_, dir);
    bad_ = dir + "/bad.checkpoint";
  }
  static void TearDownTestSuite() { fs::remove_all(fs::path(scene_).parent_path()); }
  static std::string scene_, good_, bad_;
};

std::string BlockCheckpointTest::scene_, BlockCheckpointTest::good_, BlockCheckpointTest::bad_;

TEST_F(BlockCheckpointTest, AnExtraBlockIsRefused) {
  EXPECT_EQ(refusal(scene_, good_), "");
  Loaded run(scene_);
  run.sim->read_checkpoint(good_);
  run.world().blocks->position.push_back({});
  run.sim->write_checkpoint(bad_);
  const std::string m = refusal(scene_, bad_);
  EXPECT_EQ(m.rfind("error: checkpoint " + bad_ + ": ", 0), 0u) << m;
  EXPECT_NE(m.find("it has 3 block positions, this scene has 2 blocks"), std::string::npos) << m;
}

TEST_F(BlockCheckpointTest, AnUnnormalisedOrientationIsRefused) {
  Loaded run(scene_);
  run.sim->read_checkpoint(good_);
  run.world().blocks->orientation[1].w = 3.0;
  run.sim->write_checkpoint(bad_);
  const std::string m = refusal(scene_, bad_);
  EXPECT_NE(m.find("block 'cube' has an orientation that is not a unit quaternion"), std::string::npos) << m;
}

TEST_F(BlockCheckpointTest, AContactNamingAMissingBlockIsRefused) {
  std::string bytes = read_file(good_);
  const Layout l = layout(bytes);
  ASSERT_EQ(l.stage_state.size(), 1u);
  // The dda state: started (1), dt (8), slipping (8), energies (5 x 8), momenta (8 + 2 x 24), then the contact keys.
  const std::size_t keys = l.stage_state[0] + 1 + 8 + 8 + 40 + 8 + 2 * 24;
  ASSERT_GT(get<std::uint64_t>(bytes, keys), 0u) << "the cube should rest on the slope";
  put<std::uint32_t>(bytes, keys + 8 + 4, 5);  // block a of the first contact
  reseal(bytes);
  write_file(bad_, bytes);
  const std::string m = refusal(scene_, bad_);
  EXPECT_EQ(m.rfind("error: checkpoint " + bad_ + ": stage 1 (dda): ", 0), 0u) << m;
  EXPECT_NE(m.find("contact 0 joins blocks 5 and"), std::string::npos) << m;
}

}  // namespace
