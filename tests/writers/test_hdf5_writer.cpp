// HDF5 (H5Part) writer: write a hand-built World, read it back with the HDF5
// C API and compare bit for bit; layout details ParaView's H5Part reader
// relies on (Step#N numbering, x/y/z, NAME_0/1/2, TimeValue as one double).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <regex>
#include <vector>

#include "../common/process.hpp"
#include "hdf5_writer.hpp"
#include "talus/error.hpp"
#include "world_fixture.hpp"

namespace talus {
namespace {

using test::TempDir;

// Deterministic, non-trivial values (not representable in float).
void set_frame_values(World& w, int frame) {
  auto v = w.fluid.vector("velocity");
  auto p = w.fluid.scalar("pressure");
  auto body = w.fluid.body();
  for (std::size_t i = 0; i < w.fluid.size(); ++i) {
    v[i] = {0.1 * i + frame / 3.0, -1.0 / (i + 1.0), std::sqrt(2.0) * frame};
    p[i] = 1000.0 * std::exp(-0.001 * i) + frame / 7.0;
    body[i] = static_cast<int>(i % 3);
  }
  w.time = 0.01 * frame + 1.0 / 3.0;
  w.step = 10u * frame + 5u;
}

struct File {
  hid_t id;
  explicit File(const std::string& path) : id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~File() {
    if (id >= 0) H5Fclose(id);
  }
};

template <class T>
std::vector<T> read_dataset(hid_t file, const std::string& name, hid_t mem_type) {
  hid_t set = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(set, 0) << name;
  if (set < 0) return {};
  hid_t space = H5Dget_space(set);
  std::vector<T> out(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  if (!out.empty()) EXPECT_GE(H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), 0);
  H5Sclose(space);
  H5Dclose(set);
  return out;
}

double read_double_attribute(hid_t object, const std::string& owner, const char* name) {
  hid_t o = H5Oopen(object, owner.c_str(), H5P_DEFAULT);
  hid_t a = H5Aopen(o, name, H5P_DEFAULT);
  double value = -1.0;
  // ParaView accepts TimeValue only as a native double with one element.
  hid_t type = H5Aget_type(a);
  EXPECT_GT(H5Tequal(type, H5T_IEEE_F64LE), 0);
  hid_t space = H5Aget_space(a);
  EXPECT_EQ(H5Sget_simple_extent_npoints(space), 1);
  H5Aread(a, H5T_NATIVE_DOUBLE, &value);
  H5Sclose(space);
  H5Tclose(type);
  H5Aclose(a);
  H5Oclose(o);
  return value;
}

std::string read_string_attribute(hid_t object, const std::string& owner, const char* name) {
  hid_t o = H5Oopen(object, owner.c_str(), H5P_DEFAULT);
  hid_t a = H5Aopen(o, name, H5P_DEFAULT);
  hid_t type = H5Aget_type(a);
  char* text = nullptr;
  H5Aread(a, type, &text);
  std::string out = text ? text : "";
  H5free_memory(text);
  H5Tclose(type);
  H5Aclose(a);
  H5Oclose(o);
  return out;
}

std::unique_ptr<writers::Hdf5Writer> make_writer(const std::string& json) {
  return std::make_unique<writers::Hdf5Writer>(params_from_json(writers::Hdf5Writer::describe(), json));
}

// Writes the world as the one frame of a series in `dir`; returns the file's path.
std::string write_one_frame(const TempDir& dir, World& w) {
  auto writer = make_writer("{}");
  writer->open(test::context_for(dir.str()), w);
  writer->write(w);
  writer->close(w);
  return dir.file("scene.h5part");
}

TEST(Hdf5Writer, RoundTripIsExact) {
  TempDir dir("h5-roundtrip");
  World w;
  test::fill_lattice(w, 3, {0, 0, 0}, 7, 5, 4, 0.02);
  test::add_blocks(w);
  auto writer = make_writer("{}");
  writer->open(test::context_for(dir.str()), w);
  const std::string path = dir.file("scene.h5part");

  std::vector<std::vector<Vec3>> velocities;
  std::vector<std::vector<double>> pressures;
  std::vector<std::vector<Vec3>> positions;
  std::vector<std::vector<std::uint64_t>> ids;
  for (int frame = 0; frame < 3; ++frame) {
    if (frame == 2) {  // particles leave the domain: fewer rows
      std::vector<std::uint8_t> flags(w.fluid.size(), 0);
      flags[3] = flags[50] = 1;
      w.fluid.remove_if(flags);
    }
    set_frame_values(w, frame);
    w.blocks->position[0].x = 0.5 * frame;
    writer->write(w);
    auto v = w.fluid.vector("velocity");
    velocities.emplace_back(v.begin(), v.end());
    auto p = w.fluid.scalar("pressure");
    pressures.emplace_back(p.begin(), p.end());
    auto x = w.fluid.position();
    positions.emplace_back(x.begin(), x.end());
    auto id = w.fluid.ids();
    ids.emplace_back(id.begin(), id.end());
    // The published file is complete after every frame.
    File f(path);
    ASSERT_GE(f.id, 0) << "frame " << frame;
    EXPECT_GT(H5Lexists(f.id, ("Step#" + std::to_string(frame)).c_str(), H5P_DEFAULT), 0);
  }
  writer->close(w);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  EXPECT_FALSE(std::filesystem::exists(path + ".prev"));
  ASSERT_EQ(writer->files(), (std::vector<std::string>{dir.file("scene.xmf"), path}));

  File f(path);
  ASSERT_GE(f.id, 0);
  EXPECT_EQ(read_string_attribute(f.id, "/", "scene"), test::context_for("").scene_text);
  EXPECT_EQ(read_string_attribute(f.id, "/", "talus_version"), "0.1.0-test");
  EXPECT_EQ(H5Lexists(f.id, "Step#3", H5P_DEFAULT), 0);
  for (int frame = 0; frame < 3; ++frame) {
    const std::string g = "Step#" + std::to_string(frame);
    EXPECT_EQ(read_double_attribute(f.id, g, "TimeValue"), 0.01 * frame + 1.0 / 3.0);
    const std::size_t n = positions[frame].size();
    const auto x = read_dataset<double>(f.id, g + "/x", H5T_NATIVE_DOUBLE);
    const auto y = read_dataset<double>(f.id, g + "/y", H5T_NATIVE_DOUBLE);
    const auto z = read_dataset<double>(f.id, g + "/z", H5T_NATIVE_DOUBLE);
    const auto vx = read_dataset<double>(f.id, g + "/velocity_0", H5T_NATIVE_DOUBLE);
    const auto vy = read_dataset<double>(f.id, g + "/velocity_1", H5T_NATIVE_DOUBLE);
    const auto vz = read_dataset<double>(f.id, g + "/velocity_2", H5T_NATIVE_DOUBLE);
    const auto p = read_dataset<double>(f.id, g + "/pressure", H5T_NATIVE_DOUBLE);
    const auto id = read_dataset<std::uint64_t>(f.id, g + "/id", H5T_NATIVE_UINT64);
    const auto body = read_dataset<std::int32_t>(f.id, g + "/body", H5T_NATIVE_INT32);
    ASSERT_EQ(x.size(), n);
    ASSERT_EQ(vz.size(), n);
    ASSERT_EQ(p.size(), n);
    ASSERT_EQ(id.size(), n);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_EQ(x[i], positions[frame][i].x);
      EXPECT_EQ(y[i], positions[frame][i].y);
      EXPECT_EQ(z[i], positions[frame][i].z);
      EXPECT_EQ(vx[i], velocities[frame][i].x);
      EXPECT_EQ(vy[i], velocities[frame][i].y);
      EXPECT_EQ(vz[i], velocities[frame][i].z);
      EXPECT_EQ(p[i], pressures[frame][i]);
      EXPECT_EQ(id[i], ids[frame][i]);
      EXPECT_EQ(body[i], static_cast<int>(i % 3));
    }
    EXPECT_EQ(read_string_attribute(f.id, g + "/pressure", "unit"), "Pa");
    EXPECT_EQ(read_string_attribute(f.id, g + "/velocity_1", "unit"), "m/s");
    // Blocks beside the particles.
    const auto bx = read_dataset<double>(f.id, "Blocks/" + g + "/position", H5T_NATIVE_DOUBLE);
    ASSERT_EQ(bx.size(), 6u);
    EXPECT_EQ(bx[0], 0.5 * frame);
    const auto q = read_dataset<double>(f.id, "Blocks/" + g + "/orientation", H5T_NATIVE_DOUBLE);
    ASSERT_EQ(q.size(), 8u);
    EXPECT_EQ(q[4], std::cos(0.1));
    EXPECT_EQ(read_dataset<double>(f.id, "Blocks/" + g + "/vertices", H5T_NATIVE_DOUBLE).size(), 2u * 8u * 3u);
    EXPECT_EQ(read_dataset<std::int32_t>(f.id, "Blocks/" + g + "/face_vertices", H5T_NATIVE_INT32).size(),
              2u * 6u * 4u);
  }
  EXPECT_EQ(positions[2].size(), positions[0].size() - 2);
}

// The XDMF sidecar lists every frame with its time and particle count, and
// every data path it names exists in the HDF5 file with that many values.
// A tessellated slope has thousands of blocks, all named in the root's
// "bodies" attribute: past 64 KiB, which only dense attribute storage holds.
// Fields kept in float (mixed precision) are written like every real field, in the file's real
// type, with the float values exactly.
TEST(Hdf5Writer, WritesFieldsKeptInFloat) {
  TempDir dir("h5-float-fields");
  World w;
  w.fluid.set_mixed_precision(true);
  test::fill_lattice(w, 3, {0, 0, 0}, 4, 3, 2, 0.02);
  FieldInfo speed{"speed", FieldType::scalar, "m/s", true, false};
  speed.single_when_mixed = true;
  FieldInfo drift{"drift", FieldType::vector, "m", true, false};
  drift.single_when_mixed = true;
  w.fluid.require(speed);
  w.fluid.require(drift);
  ASSERT_EQ(w.fluid.info("speed").type, FieldType::scalar_f32);
  const std::size_t n = w.fluid.size();
  for (std::size_t i = 0; i < n; ++i) {
    w.fluid.scalar_f32("speed")[i] = static_cast<float>(1.0 / (i + 3.0));
    w.fluid.vector_f32("drift")[i] = Vec3{0.1 * i, -1.0 / 3.0, 2.0 + i};
  }
  File f(write_one_frame(dir, w));
  ASSERT_GE(f.id, 0);
  const auto s = read_dataset<double>(f.id, "Step#0/speed", H5T_NATIVE_DOUBLE);
  ASSERT_EQ(s.size(), n);
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(s[i], static_cast<double>(w.fluid.scalar_f32("speed")[i]));
  for (int c = 0; c < 3; ++c) {
    const auto d = read_dataset<double>(f.id, "Step#0/drift_" + std::to_string(c), H5T_NATIVE_DOUBLE);
    ASSERT_EQ(d.size(), n);
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(d[i], Vec3(w.fluid.vector_f32("drift")[i])[c]) << i << " " << c;
  }
}

TEST(Hdf5Writer, NamesThousandsOfBodies) {
  TempDir dir("h5-bodies");
  World w;
  test::fill_lattice(w, 3, {0, 0, 0}, 2, 2, 2, 0.02);
  const std::size_t n = 6000;
  for (std::size_t i = 0; i < n; ++i) {
    Body b;
    b.name = "tetrahedron_" + std::to_string(i);
    w.bodies.push_back(b);
  }
  File f(write_one_frame(dir, w));
  ASSERT_GE(f.id, 0);
  hid_t a = H5Aopen(f.id, "bodies", H5P_DEFAULT);
  ASSERT_GE(a, 0);
  hid_t space = H5Aget_space(a);
  EXPECT_EQ(H5Sget_simple_extent_npoints(space), static_cast<hssize_t>(n));
  std::vector<char*> names(n, nullptr);
  hid_t type = H5Aget_type(a);
  ASSERT_GE(H5Aread(a, type, names.data()), 0);
  EXPECT_STREQ(names[0], "tetrahedron_0");
  EXPECT_STREQ(names[n - 1], "tetrahedron_5999");
  H5Dvlen_reclaim(type, space, H5P_DEFAULT, names.data());
  H5Tclose(type);
  H5Sclose(space);
  H5Aclose(a);
}

TEST(Hdf5Writer, XdmfSidecarDescribesTheFrames) {
  TempDir dir("h5-xdmf");
  World w;
  test::fill_lattice(w, 3, {0, 0, 0}, 4, 3, 2, 0.05);
  auto writer = make_writer("{}");
  writer->open(test::context_for(dir.str()), w);
  std::vector<std::size_t> counts;
  for (int frame = 0; frame < 3; ++frame) {
    if (frame == 2) {
      std::vector<std::uint8_t> flags(w.fluid.size(), 0);
      flags[0] = 1;
      w.fluid.remove_if(flags);
    }
    set_frame_values(w, frame);
    writer->write(w);
    counts.push_back(w.fluid.size());
  }
  writer->close(w);
  const std::string xmf = test::read_file(dir.file("scene.xmf"));
  EXPECT_NE(xmf.find("<Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">"),
            std::string::npos);

  const std::regex grid_re(R"re(<Grid Name="Step#(\d+)" GridType="Uniform">\s*<Time Value="([^"]+)"/>\s*)re"
                           R"re(<Topology TopologyType="Polyvertex" NumberOfElements="(\d+)" NodesPerElement="1"/>)re");
  std::vector<std::smatch> grids;
  for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), grid_re); it != std::sregex_iterator(); ++it)
    grids.push_back(*it);
  ASSERT_EQ(grids.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(std::stoi(grids[k][1]), k);
    EXPECT_EQ(std::stod(grids[k][2]), 0.01 * k + 1.0 / 3.0);
    EXPECT_EQ(std::stoul(grids[k][3]), counts[k]);
  }

  File f(dir.file("scene.h5part"));
  ASSERT_GE(f.id, 0);
  const std::regex item_re(R"re(<DataItem Dimensions="(\d+)" NumberType="(\w+)" Precision="(\d)" Format="HDF">)re"
                           R"re(scene\.h5part:(/Step#(\d+)/\w+)</DataItem>)re");
  int items = 0;
  for (auto it = std::sregex_iterator(xmf.begin(), xmf.end(), item_re); it != std::sregex_iterator(); ++it, ++items) {
    const std::string path = (*it)[4];
    ASSERT_GT(H5Lexists(f.id, path.c_str(), H5P_DEFAULT), 0) << path;
    hid_t set = H5Dopen2(f.id, path.c_str(), H5P_DEFAULT);
    hid_t space = H5Dget_space(set);
    EXPECT_EQ(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)), std::stoul((*it)[1])) << path;
    H5Sclose(space);
    H5Dclose(set);
  }
  // Per frame: x, y, z, velocity_0/1/2, density, pressure, mass, id, body.
  EXPECT_EQ(items, 3 * 11);
  EXPECT_NE(xmf.find(R"(<Attribute Name="velocity" AttributeType="Vector" Center="Node">)"), std::string::npos);
  EXPECT_NE(xmf.find(R"x(Function="JOIN($0, $1, $2)")x"), std::string::npos);
}

TEST(Hdf5Writer, ChosenFieldsSinglePrecisionAndBoundaryFile) {
  TempDir dir("h5-fields");
  World w;
  test::fill_lattice(w, 2, {0, 0, 0}, 6, 4, 1, 0.1);
  w.boundary.append(5);
  for (std::size_t i = 0; i < 5; ++i) w.boundary.position()[i] = {0.1 * i, -0.05, 0.0};
  set_frame_values(w, 1);
  auto writer = make_writer(R"({"fields": ["pressure"], "precision": "single", "boundary": true, "file": "out.h5"})");
  writer->open(test::context_for(dir.str()), w);
  writer->write(w);
  writer->close(w);
  EXPECT_EQ(writer->files(), (std::vector<std::string>{dir.file("out_boundary.xmf"), dir.file("out_boundary.h5"),
                                                       dir.file("out.xmf"), dir.file("out.h5")}));

  File f(dir.file("out.h5"));
  ASSERT_GE(f.id, 0);
  EXPECT_GT(H5Lexists(f.id, "Step#0/pressure", H5P_DEFAULT), 0);
  EXPECT_EQ(H5Lexists(f.id, "Step#0/velocity_0", H5P_DEFAULT), 0);
  // A field list keeps the identity fields: particles can still be followed and told apart.
  EXPECT_GT(H5Lexists(f.id, "Step#0/id", H5P_DEFAULT), 0);
  EXPECT_GT(H5Lexists(f.id, "Step#0/body", H5P_DEFAULT), 0);
  EXPECT_EQ(H5Lexists(f.id, "Blocks", H5P_DEFAULT), 0);  // no blocks in this world
  hid_t set = H5Dopen2(f.id, "Step#0/pressure", H5P_DEFAULT);
  hid_t type = H5Dget_type(set);
  EXPECT_GT(H5Tequal(type, H5T_IEEE_F32LE), 0);
  H5Tclose(type);
  H5Dclose(set);
  const auto p = read_dataset<float>(f.id, "Step#0/pressure", H5T_NATIVE_FLOAT);
  const auto ref = w.fluid.scalar("pressure");
  ASSERT_EQ(p.size(), ref.size());
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p[i], static_cast<float>(ref[i]));

  File wall(dir.file("out_boundary.h5"));
  ASSERT_GE(wall.id, 0);
  EXPECT_EQ(read_dataset<float>(wall.id, "Step#0/x", H5T_NATIVE_FLOAT).size(), 5u);
}

TEST(Hdf5Writer, UnknownFieldIsAnInputErrorAtItsPointer) {
  TempDir dir("h5-unknown");
  World w;
  test::fill_lattice(w, 2, {0, 0, 0}, 2, 2, 1, 0.1);
  auto writer = make_writer(R"({"fields": ["pressure", "vorticity"]})");
  try {
    writer->open(test::context_for(dir.str()), w);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("/fields"), std::string::npos) << m;
    EXPECT_NE(m.find("vorticity"), std::string::npos) << m;
    EXPECT_NE(m.find("pressure"), std::string::npos) << m;  // the known fields are listed
  }
}

TEST(Hdf5Writer, ResumeKeepsFramesUpToTheCheckpointAndAppends) {
  TempDir dir("h5-resume");
  World w;
  test::fill_lattice(w, 2, {0, 0, 0}, 3, 3, 1, 0.1);
  {
    auto writer = make_writer("{}");
    writer->open(test::context_for(dir.str()), w);
    for (int frame = 0; frame < 4; ++frame) {
      set_frame_values(w, frame);  // steps 5, 15, 25, 35
      writer->write(w);
    }
    // Interrupted: no close(), the working copy stays behind.
  }
  set_frame_values(w, 1);  // the checkpoint was at step 15
  auto writer = make_writer("{}");
  writer->open(test::context_for(dir.str(), true), w);
  writer->write(w);  // the host writes the checkpoint's state again: no duplicate
  // Two frames more: the dropped frames 2 and 3 of the interrupted run must not come back nor collide.
  w.step = 100;
  w.time = 9.0;
  writer->write(w);
  w.step = 110;
  w.time = 9.5;
  writer->write(w);
  writer->close(w);

  File f(dir.file("scene.h5part"));
  ASSERT_GE(f.id, 0);
  EXPECT_EQ(read_double_attribute(f.id, "Step#0", "TimeValue"), 1.0 / 3.0);
  EXPECT_EQ(read_double_attribute(f.id, "Step#1", "TimeValue"), 0.01 + 1.0 / 3.0);
  EXPECT_EQ(read_double_attribute(f.id, "Step#2", "TimeValue"), 9.0);
  EXPECT_EQ(read_double_attribute(f.id, "Step#3", "TimeValue"), 9.5);
  EXPECT_EQ(H5Lexists(f.id, "Step#4", H5P_DEFAULT), 0);
}

}  // namespace
}  // namespace talus
