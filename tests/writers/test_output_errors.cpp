// Failures are for people: an output folder that cannot take files, or a
// full disk, is a RunError naming the path and the system's reason, and no
// truncated file is left under a final name.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>

#include "../common/process.hpp"
#include "hdf5_writer.hpp"
#include "probes_writer.hpp"
#include "talus/error.hpp"
#include "vtu_writer.hpp"
#include "world_fixture.hpp"

namespace talus {
namespace {

using test::TempDir;

std::vector<std::unique_ptr<Writer>> all_writers() {
  std::vector<std::unique_ptr<Writer>> out;
  out.push_back(std::make_unique<writers::Hdf5Writer>(params_from_json(writers::Hdf5Writer::describe(), "{}")));
  out.push_back(std::make_unique<writers::VtuWriter>(params_from_json(writers::VtuWriter::describe(), "{}")));
  out.push_back(std::make_unique<writers::ProbesWriter>(params_from_json(writers::ProbesWriter::describe(), "{}")));
  return out;
}

std::string open_error(Writer& writer, const std::string& directory, const World& w) {
  try {
    writer.open(test::context_for(directory), w);
  } catch (const RunError& e) {
    return e.what();
  }
  return {};
}

// Output names stay inside the output folder: refused at validation, with
// the JSON pointer, before anything is written.
TEST(OutputErrors, FileNamesOutsideTheOutputFolderAreRefusedAtValidation) {
  auto message = [](const ParamSet& set, const std::string& json) {
    try {
      params_from_json(set, json);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const ParamSet h5 = writers::Hdf5Writer::describe();
  for (const char* bad : {"../x.h5part", "/tmp/x.h5part", "sub/x.h5part", "..", ""})
    EXPECT_NE(message(h5, std::string(R"({"file": ")") + bad + "\"}").find("/file: "), std::string::npos) << bad;
  EXPECT_NE(message(h5, R"({"file": "../x.h5part"})").find("a path, not a file name"), std::string::npos);
  EXPECT_NE(message(h5, "{\"file\": \"" + std::string(300, 'a') + "\"}").find("300 characters"), std::string::npos);
  EXPECT_NE(message(h5, R"({"file": "a\u0000b"})").find("control character"), std::string::npos);
  EXPECT_EQ(message(h5, R"({"file": "run.h5part"})"), "accepted");
  EXPECT_NE(message(writers::ProbesWriter::describe(), R"({"file": "../p.csv", "points": [[0, 0, 0]]})").find("/file: "),
            std::string::npos);
  EXPECT_NE(message(writers::VtuWriter::describe(), R"({"prefix": "../v"})").find("/prefix: "), std::string::npos);
}

TEST(OutputErrors, FolderThatIsAFileNamesThePathAndTheReason) {
  TempDir dir("errors-notdir");
  World w;
  test::fill_lattice(w, 2, {0, 0, 0}, 2, 2, 1, 0.1);
  const std::string not_a_folder = dir.file("plain-file");
  std::ofstream(not_a_folder) << "x";
  for (auto& writer : all_writers()) {
    const std::string m = open_error(*writer, not_a_folder, w);
    EXPECT_NE(m.find("'" + not_a_folder + "'"), std::string::npos) << m;
    EXPECT_NE(m.find("Not a directory"), std::string::npos) << m;
  }
}

TEST(OutputErrors, MissingFolderNamesThePathAndTheReason) {
  TempDir dir("errors-missing");
  World w;
  test::fill_lattice(w, 2, {0, 0, 0}, 2, 2, 1, 0.1);
  const std::string missing = dir.file("no/such/folder");
  for (auto& writer : all_writers()) {
    const std::string m = open_error(*writer, missing, w);
    EXPECT_NE(m.find(missing), std::string::npos) << m;
    EXPECT_NE(m.find("No such file or directory"), std::string::npos) << m;
  }
}

TEST(OutputErrors, ReadOnlyFolderNamesThePathAndTheReason) {
  if (::geteuid() == 0)
    GTEST_SKIP() << "root ignores folder permissions; covered by the not-a-folder and disk-full tests";
  TempDir dir("errors-readonly");
  World w;
  test::fill_lattice(w, 2, {0, 0, 0}, 2, 2, 1, 0.1);
  std::filesystem::permissions(dir.str(), std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  for (auto& writer : all_writers()) {
    const std::string m = open_error(*writer, dir.str(), w);
    EXPECT_NE(m.find(dir.str()), std::string::npos) << m;
    EXPECT_NE(m.find("Permission denied"), std::string::npos) << m;
  }
}

// /dev/full accepts opens and fails every write with ENOSPC: a symbolic link
// to it in place of a writer's temporary file is a disk that just filled up.
bool link_to_dev_full(const std::string& path) {
  return ::access("/dev/full", W_OK) == 0 && ::symlink("/dev/full", path.c_str()) == 0;
}

TEST(OutputErrors, DiskFullWhileWritingAFrame) {
  TempDir dir("errors-full");
  World w;
  test::fill_lattice(w, 3, {0, 0, 0}, 4, 4, 4, 0.1);
  auto expect_disk_full = [](const std::function<void()>& write, const std::string& path) {
    try {
      write();
      ADD_FAILURE() << "no error writing " << path;
    } catch (const RunError& e) {
      const std::string m = e.what();
      RecordProperty("message", m);
      std::cerr << "[message] " << m << "\n";
      EXPECT_NE(m.find(path), std::string::npos) << m;
      EXPECT_NE(m.find("No space left on device"), std::string::npos) << m;
    }
  };

  // VTU: frame 0 is written, frame 1 hits the full disk.
  writers::VtuWriter vtu(params_from_json(writers::VtuWriter::describe(), "{}"));
  vtu.open(test::context_for(dir.str()), w);
  vtu.write(w);
  const std::string pvd_before = test::read_file(dir.file("scene.pvd"));
  if (!link_to_dev_full(dir.file("scene_000001.vtu.tmp"))) GTEST_SKIP() << "no /dev/full";
  w.step = 1;
  w.time = 0.1;
  expect_disk_full([&] { vtu.write(w); }, dir.file("scene_000001.vtu.tmp"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("scene_000001.vtu")));
  EXPECT_EQ(test::read_file(dir.file("scene.pvd")), pvd_before);  // still lists frame 0 only

  // HDF5: frame 0 is written, frame 1 hits the full disk; the published file
  // keeps frame 0 and stays readable; once space is back frame 1 goes in.
  w.step = 0;
  w.time = 0.0;
  writers::Hdf5Writer h5(params_from_json(writers::Hdf5Writer::describe(), "{}"));
  h5.open(test::context_for(dir.str()), w);
  h5.write(w);
  ASSERT_TRUE(link_to_dev_full(dir.file("scene.h5part.tmp")));
  w.step = 1;
  w.time = 0.1;
  expect_disk_full([&] { h5.write(w); }, dir.file("scene.h5part.tmp"));
  auto steps_in_file = [&] {
    hid_t f = H5Fopen(dir.file("scene.h5part").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    EXPECT_GE(f, 0);
    int n = 0;
    while (H5Lexists(f, ("Step#" + std::to_string(n)).c_str(), H5P_DEFAULT) > 0) ++n;
    H5Fclose(f);
    return n;
  };
  EXPECT_EQ(steps_in_file(), 1);
  EXPECT_FALSE(std::filesystem::exists(dir.file("scene.h5part.tmp")));  // the failed copy is gone
  h5.write(w);
  h5.close(w);
  EXPECT_EQ(steps_in_file(), 2);

  writers::ProbesWriter probes(params_from_json(writers::ProbesWriter::describe(), R"({"file": "p.csv"})"));
  ASSERT_TRUE(link_to_dev_full(dir.file("p.csv")));
  expect_disk_full([&] { probes.open(test::context_for(dir.str()), w); }, dir.file("p.csv"));
}

}  // namespace
}  // namespace talus
