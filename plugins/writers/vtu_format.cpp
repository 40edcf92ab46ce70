#include "vtu_format.hpp"

#include <charconv>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <type_traits>

#include "base64.hpp"

namespace talus::writers {

std::string format_real(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

namespace {

template <class T>
const char* vtk_type() {
  if constexpr (std::is_same_v<T, double>)
    return "Float64";
  else if constexpr (std::is_same_v<T, float>)
    return "Float32";
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return "Int32";
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return "Int64";
  else if constexpr (std::is_same_v<T, std::uint64_t>)
    return "UInt64";
  else if constexpr (std::is_same_v<T, std::uint8_t>)
    return "UInt8";
}

template <class T>
void append_number(std::string& out, T v) {
  char buf[32];
  if constexpr (std::is_same_v<T, std::uint8_t>) {
    const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<unsigned>(v));
    out.append(buf, r.ptr);
  } else {
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
  }
}

class Document {
 public:
  Document(std::string& out, const VtuOptions& o) : out_(out), options_(o) {}

  // One <DataArray> of `count` values (count = tuples * components).
  template <class T>
  void array(const std::string& name, int components, const T* data, std::size_t count, const std::string& unit,
             const char* indent) {
    out_ += indent;
    out_ += "<DataArray type=\"";
    out_ += vtk_type<T>();
    out_ += "\" Name=\"" + name + "\"";
    if (components > 1) out_ += " NumberOfComponents=\"" + std::to_string(components) + "\"";
    if (!unit.empty()) out_ += " unit=\"" + unit + "\"";
    out_ += options_.binary ? " format=\"binary\">\n" : " format=\"ascii\">\n";
    if (options_.binary) {
      const std::uint64_t bytes = count * sizeof(T);
      Base64Encoder enc(out_);
      enc.add(&bytes, sizeof bytes);
      if (count > 0) enc.add(data, bytes);
      enc.finish();
    } else {
      for (std::size_t i = 0; i < count; ++i) {
        append_number(out_, data[i]);
        out_ += ((i + 1) % static_cast<std::size_t>(components) == 0) ? '\n' : ' ';
      }
    }
    out_ += "\n";
    out_ += indent;
    out_ += "</DataArray>\n";
  }

  // Real data, converted to Float32 when asked.
  void reals(const std::string& name, int components, const double* data, std::size_t count, const std::string& unit,
             const char* indent, VtuScratch& s) {
    if (!options_.single) return array(name, components, data, count, unit, indent);
    s.reals.resize(count);
    for (std::size_t i = 0; i < count; ++i) s.reals[i] = static_cast<float>(data[i]);
    array(name, components, s.reals.data(), count, unit, indent);
  }

 private:
  std::string& out_;
  VtuOptions options_;
};

}  // namespace

void build_vtu(std::string& out, const ParticleStore& store, const std::vector<FieldInfo>& fields, double time,
               std::uint64_t step, const VtuOptions& options, VtuScratch& scratch) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");
  const std::size_t n = store.size();
  out.clear();
  Document doc(out, options);
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <FieldData>\n";
  const double t = time;
  const std::int64_t s = static_cast<std::int64_t>(step);
  out += "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">" +
         format_real(t) + "</DataArray>\n";
  out += "      <DataArray type=\"Int64\" Name=\"Step\" NumberOfTuples=\"1\" format=\"ascii\">" + std::to_string(s) +
         "</DataArray>\n";
  out += "    </FieldData>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfCells=\"" + std::to_string(n) + "\">\n";

  std::string scalars, vectors;
  for (const auto& f : fields) {
    const bool scalar = double_type(f.type) == FieldType::scalar;
    const bool vector = double_type(f.type) == FieldType::vector;
    if (scalar && scalars.empty()) scalars = f.name;
    if (vector && vectors.empty()) vectors = f.name;
  }
  out += "      <PointData";
  if (!scalars.empty()) out += " Scalars=\"" + scalars + "\"";
  if (!vectors.empty()) out += " Vectors=\"" + vectors + "\"";
  out += ">\n";
  const char* in = "        ";
  std::vector<double> widened;
  for (const auto& f : fields) {
    switch (f.type) {
      case FieldType::scalar:
        doc.reals(f.name, 1, store.scalar(f.name).data(), n, f.unit, in, scratch);
        break;
      case FieldType::vector:
        doc.reals(f.name, 3, reinterpret_cast<const double*>(store.vector(f.name).data()), 3 * n, f.unit, in, scratch);
        break;
      case FieldType::integer:
        doc.array(f.name, 1, store.integer(f.name).data(), n, f.unit, in);
        break;
      case FieldType::id:
        doc.array(f.name, 1, store.ids().data(), n, f.unit, in);
        break;
      case FieldType::scalar_f32: {  // written as every real field, from a copy in double
        const auto v = store.scalar_f32(f.name);
        widened.assign(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
        doc.reals(f.name, 1, widened.data(), n, f.unit, in, scratch);
        break;
      }
      case FieldType::vector_f32: {
        const auto v = store.vector_f32(f.name);
        widened.resize(3 * n);
        for (std::size_t i = 0; i < n; ++i)
          for (int c = 0; c < 3; ++c) widened[3 * i + c] = Vec3(v[i])[c];
        doc.reals(f.name, 3, widened.data(), 3 * n, f.unit, in, scratch);
        break;
      }
    }
  }
  out += "      </PointData>\n";

  out += "      <Points>\n";
  doc.reals("position", 3, reinterpret_cast<const double*>(store.position().data()), 3 * n, "m", in, scratch);
  out += "      </Points>\n";

  // One vertex cell per particle: connectivity i, offset i+1, type 1; Int32
  // while the indices fit (half the bytes), Int64 beyond.
  out += "      <Cells>\n";
  auto cells = [&](auto& indices) {
    using I = typename std::decay_t<decltype(indices)>::value_type;
    indices.resize(n);
    for (std::size_t i = 0; i < n; ++i) indices[i] = static_cast<I>(i);
    doc.array("connectivity", 1, indices.data(), n, "", in);
    for (std::size_t i = 0; i < n; ++i) indices[i] = static_cast<I>(i + 1);
    doc.array("offsets", 1, indices.data(), n, "", in);
  };
  if (n < static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    cells(scratch.indices32);
  else
    cells(scratch.indices);
  scratch.types.assign(n, std::uint8_t{1});  // VTK_VERTEX
  doc.array("types", 1, scratch.types.data(), n, "", in);
  out += "      </Cells>\n";
  out += "    </Piece>\n";
  out += "  </UnstructuredGrid>\n";
  out += "</VTKFile>\n";
}

std::string build_pvd(const std::vector<PvdEntry>& entries) {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += "  <Collection>\n";
  for (const auto& e : entries)
    out += "    <DataSet timestep=\"" + format_real(e.time) + "\" group=\"\" part=\"0\" file=\"" + e.file + "\"/>\n";
  out += "  </Collection>\n";
  out += "</VTKFile>\n";
  return out;
}

std::vector<PvdEntry> parse_pvd(const std::string& text) {
  std::vector<PvdEntry> out;
  auto attribute = [](const std::string& line, const std::string& key, std::string& value) {
    const auto at = line.find(" " + key + "=\"");
    if (at == std::string::npos) return false;
    const auto begin = at + key.size() + 3;
    const auto end = line.find('"', begin);
    if (end == std::string::npos) return false;
    value = line.substr(begin, end - begin);
    return true;
  };
  std::size_t pos = 0;
  while ((pos = text.find("<DataSet ", pos)) != std::string::npos) {
    const auto end = text.find("/>", pos);
    if (end == std::string::npos) return {};
    const std::string element = text.substr(pos, end - pos);
    PvdEntry e;
    std::string t;
    if (!attribute(element, "timestep", t) || !attribute(element, "file", e.file)) return {};
    char* stop = nullptr;
    e.time = std::strtod(t.c_str(), &stop);
    if (stop == t.c_str()) return {};
    out.push_back(std::move(e));
    pos = end;
  }
  return out;
}

}  // namespace talus::writers
