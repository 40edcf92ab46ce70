// VTK XML writer: the .pvd lists every frame with its time, each .vtu has
// the right counts and cells, and a field decodes back exactly (binary and
// ascii encodings).
#include <gtest/gtest.h>

#include <charconv>
#include <cstring>
#include <filesystem>
#include <regex>

#include "../common/process.hpp"
#include "base64.hpp"
#include "vtu_writer.hpp"
#include "world_fixture.hpp"

namespace talus {
namespace {

using test::TempDir;

std::unique_ptr<writers::VtuWriter> make_writer(const std::string& json) {
  return std::make_unique<writers::VtuWriter>(params_from_json(writers::VtuWriter::describe(), json));
}

// The text of <DataArray ... Name="NAME" ...>TEXT</DataArray> and its opening tag.
bool find_array(const std::string& doc, const std::string& name, std::string& tag, std::string& body) {
  const auto at = doc.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return false;
  const auto open = doc.rfind("<DataArray", at);
  const auto close_tag = doc.find('>', at);
  const auto end = doc.find("</DataArray>", close_tag);
  tag = doc.substr(open, close_tag - open + 1);
  body = doc.substr(close_tag + 1, end - close_tag - 1);
  return true;
}

std::string attribute(const std::string& tag, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(tag, m, std::regex(" " + key + "=\"([^\"]*)\""))) return {};
  return m[1];
}

template <class T>
std::vector<T> decode_binary(const std::string& body) {
  const std::string bytes = writers::base64_decode(body);
  std::uint64_t header = 0;
  EXPECT_GE(bytes.size(), sizeof header);
  std::memcpy(&header, bytes.data(), sizeof header);
  EXPECT_EQ(header, bytes.size() - sizeof header);  // UInt64 byte count, then the data
  std::vector<T> out((bytes.size() - sizeof header) / sizeof(T));
  std::memcpy(out.data(), bytes.data() + sizeof header, out.size() * sizeof(T));
  return out;
}

std::vector<double> decode_ascii(const std::string& body) {
  std::vector<double> out;
  const char* p = body.data();
  const char* end = p + body.size();
  while (p < end) {
    while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
    if (p == end) break;
    double v = 0;
    auto r = std::from_chars(p, end, v);
    EXPECT_EQ(r.ec, std::errc());
    out.push_back(v);
    p = r.ptr;
  }
  return out;
}

void prepare(World& w, int frame) {
  auto p = w.fluid.scalar("pressure");
  auto v = w.fluid.vector("velocity");
  for (std::size_t i = 0; i < w.fluid.size(); ++i) {
    p[i] = 1.0 / (i + 3.0) + frame;
    v[i] = {0.1 * i, -0.2 * frame, 1.0 / 7.0};
  }
  w.time = 0.125 * frame + 1e-3 / 3.0;
  w.step = 100u * frame;
}

TEST(VtuWriter, SeriesStructureAndExactBinaryData) {
  TempDir dir("vtu");
  World w;
  test::fill_lattice(w, 3, {0, 0, 0}, 4, 3, 2, 0.05);
  auto writer = make_writer("{}");
  writer->open(test::context_for(dir.str()), w);
  for (int frame = 0; frame < 2; ++frame) {
    prepare(w, frame);
    writer->write(w);
  }
  writer->write(w);  // the same step again: no new frame
  writer->close(w);
  ASSERT_EQ(writer->files(), std::vector<std::string>{dir.file("scene.pvd")});

  const std::string pvd = test::read_file(dir.file("scene.pvd"));
  const std::regex dataset("<DataSet timestep=\"([^\"]+)\" group=\"\" part=\"0\" file=\"([^\"]+)\"/>");
  std::vector<std::pair<double, std::string>> entries;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), dataset); it != std::sregex_iterator(); ++it)
    entries.emplace_back(std::stod((*it)[1]), (*it)[2]);
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].second, "scene_000000.vtu");
  EXPECT_EQ(entries[1].first, 0.125 + 1e-3 / 3.0);  // shortest round-trip text: exact
  for (const auto& e : entries) EXPECT_TRUE(std::filesystem::exists(dir.file(e.second)));
  for (const auto& f : std::filesystem::directory_iterator(dir.str()))
    EXPECT_NE(f.path().extension(), ".tmp") << f.path();

  const std::string doc = test::read_file(dir.file("scene_000001.vtu"));
  const std::size_t n = w.fluid.size();
  EXPECT_NE(doc.find("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                     "header_type=\"UInt64\">"),
            std::string::npos);
  EXPECT_NE(
      doc.find("<Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" + std::to_string(n) + "\">"),
      std::string::npos);
  std::string tag, body;
  ASSERT_TRUE(find_array(doc, "pressure", tag, body));
  EXPECT_EQ(attribute(tag, "type"), "Float64");
  EXPECT_EQ(attribute(tag, "format"), "binary");
  const auto p = decode_binary<double>(body);
  ASSERT_EQ(p.size(), n);
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(p[i], w.fluid.scalar("pressure")[i]);

  ASSERT_TRUE(find_array(doc, "velocity", tag, body));
  EXPECT_EQ(attribute(tag, "NumberOfComponents"), "3");
  const auto v = decode_binary<double>(body);
  ASSERT_EQ(v.size(), 3 * n);
  EXPECT_EQ(v[3 * 5 + 2], 1.0 / 7.0);

  ASSERT_TRUE(find_array(doc, "position", tag, body));
  const auto x = decode_binary<double>(body);
  ASSERT_EQ(x.size(), 3 * n);
  EXPECT_EQ(x[3 * 7 + 1], w.fluid.position()[7].y);

  ASSERT_TRUE(find_array(doc, "connectivity", tag, body));
  EXPECT_EQ(attribute(tag, "type"), "Int32");
  const auto conn = decode_binary<std::int32_t>(body);
  ASSERT_TRUE(find_array(doc, "offsets", tag, body));
  const auto offsets = decode_binary<std::int32_t>(body);
  ASSERT_TRUE(find_array(doc, "types", tag, body));
  const auto types = decode_binary<std::uint8_t>(body);
  ASSERT_EQ(conn.size(), n);
  ASSERT_EQ(offsets.size(), n);
  ASSERT_EQ(types.size(), n);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(conn[i], static_cast<std::int32_t>(i));
    EXPECT_EQ(offsets[i], static_cast<std::int32_t>(i + 1));
    EXPECT_EQ(types[i], 1);  // VTK_VERTEX
  }
  ASSERT_TRUE(find_array(doc, "id", tag, body));
  EXPECT_EQ(attribute(tag, "type"), "UInt64");
}

TEST(VtuWriter, AsciiSinglePrecisionAndChosenFields) {
  TempDir dir("vtu-ascii");
  World w;
  test::fill_lattice(w, 2, {0, 0, 0}, 5, 2, 1, 0.1);
  prepare(w, 1);
  auto writer = make_writer(R"({"fields": ["pressure"], "encoding": "ascii", "precision": "single", "prefix": "dam"})");
  writer->open(test::context_for(dir.str()), w);
  writer->write(w);
  const std::string doc = test::read_file(dir.file("dam_000000.vtu"));
  std::string tag, body;
  ASSERT_TRUE(find_array(doc, "pressure", tag, body));
  EXPECT_EQ(attribute(tag, "type"), "Float32");
  const auto p = decode_ascii(body);
  ASSERT_EQ(p.size(), w.fluid.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    EXPECT_EQ(static_cast<float>(p[i]), static_cast<float>(w.fluid.scalar("pressure")[i]));
  EXPECT_FALSE(find_array(doc, "velocity", tag, body));
  EXPECT_TRUE(std::filesystem::exists(dir.file("dam.pvd")));
}

TEST(VtuWriter, ResumeKeepsTheFramesUpToTheCheckpoint) {
  TempDir dir("vtu-resume");
  World w;
  test::fill_lattice(w, 2, {0, 0, 0}, 2, 2, 1, 0.1);
  {
    auto writer = make_writer("{}");
    writer->open(test::context_for(dir.str()), w);
    for (int frame = 0; frame < 3; ++frame) {
      prepare(w, frame);
      writer->write(w);
    }
  }
  prepare(w, 1);
  auto writer = make_writer("{}");
  writer->open(test::context_for(dir.str(), true), w);
  writer->write(w);  // the checkpoint's state again: skipped
  prepare(w, 5);
  writer->write(w);
  const std::string pvd = test::read_file(dir.file("scene.pvd"));
  const auto entries = writers::parse_pvd(pvd);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[1].time, 0.125 + 1e-3 / 3.0);
  EXPECT_EQ(entries[2].time, 0.125 * 5 + 1e-3 / 3.0);
  EXPECT_EQ(entries[2].file, "scene_000002.vtu");
}

TEST(Base64, MatchesRfc4648Vectors) {
  auto encode = [](const std::string& s) {
    std::string out;
    writers::Base64Encoder e(out);
    // Feed byte by byte to exercise the carry between calls.
    for (char c : s) e.add(&c, 1);
    e.finish();
    return out;
  };
  EXPECT_EQ(encode(""), "");
  EXPECT_EQ(encode("f"), "Zg==");
  EXPECT_EQ(encode("fo"), "Zm8=");
  EXPECT_EQ(encode("foo"), "Zm9v");
  EXPECT_EQ(encode("foob"), "Zm9vYg==");
  EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(writers::base64_decode("Zm9vYmE="), "fooba");
}

}  // namespace
}  // namespace talus
