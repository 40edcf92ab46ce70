#include "xdmf_sidecar.hpp"

#include "vtu_format.hpp"  // format_real

namespace talus::writers {

namespace {
struct NumberType {
  const char* type;
  int precision;
};

void data_item(std::string& out, const std::string& indent, const std::string& path, std::uint64_t n, NumberType t) {
  out += indent + "<DataItem Dimensions=\"" + std::to_string(n) + "\" NumberType=\"" + t.type + "\" Precision=\"" +
         std::to_string(t.precision) + "\" Format=\"HDF\">" + path + "</DataItem>\n";
}
}  // namespace

std::string build_xdmf(const std::string& h5_file, const std::vector<XdmfFrame>& frames,
                       const std::vector<FieldInfo>& fields, bool single) {
  const NumberType real{"Float", single ? 4 : 8};
  std::string out;
  out += "<?xml version=\"1.0\" ?>\n";
  out += "<Xdmf Version=\"2.0\">\n";
  out += "  <Domain>\n";
  out += "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::string group = h5_file + ":/Step#" + std::to_string(k) + "/";
    const std::uint64_t n = frames[k].particles;
    const std::string N = std::to_string(n);
    out += "      <Grid Name=\"Step#" + std::to_string(k) + "\" GridType=\"Uniform\">\n";
    out += "        <Time Value=\"" + format_real(frames[k].time) + "\"/>\n";
    out += "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + N + "\" NodesPerElement=\"1\"/>\n";
    out += "        <Geometry GeometryType=\"X_Y_Z\">\n";
    for (const char* c : {"x", "y", "z"}) data_item(out, "          ", group + c, n, real);
    out += "        </Geometry>\n";
    for (const auto& f : fields) {
      switch (f.type) {
        case FieldType::scalar:
        case FieldType::scalar_f32:  // written in the file's real type, as every real field
        case FieldType::integer:
        case FieldType::id: {
          const NumberType t = f.type == FieldType::integer ? NumberType{"Int", 4}
                               : f.type == FieldType::id    ? NumberType{"UInt", 8}
                                                            : real;
          out += "        <Attribute Name=\"" + f.name + "\" AttributeType=\"Scalar\" Center=\"Node\">\n";
          data_item(out, "          ", group + f.name, n, t);
          out += "        </Attribute>\n";
          break;
        }
        case FieldType::vector:
        case FieldType::vector_f32:
          // The components are separate datasets NAME_0/1/2: joined into one vector.
          out += "        <Attribute Name=\"" + f.name + "\" AttributeType=\"Vector\" Center=\"Node\">\n";
          out +=
              "          <DataItem ItemType=\"Function\" Function=\"JOIN($0, $1, $2)\" Dimensions=\"" + N + " 3\">\n";
          for (int c = 0; c < 3; ++c) data_item(out, "            ", group + f.name + "_" + std::to_string(c), n, real);
          out += "          </DataItem>\n";
          out += "        </Attribute>\n";
          break;
      }
    }
    out += "      </Grid>\n";
  }
  out += "    </Grid>\n";
  out += "  </Domain>\n";
  out += "</Xdmf>\n";
  return out;
}

}  // namespace talus::writers
