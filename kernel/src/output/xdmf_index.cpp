#include "xdmf_index.hpp"

#include <fmt/format.h>

#include <fstream>
#include <system_error>

#include "shard/output.hpp"

namespace shard {

namespace {

// One HDF DataItem: dims "N 3", number type Float/Int, precision in bytes.
std::string data_item(const std::string& dims, const char* number_type, int precision,
                      const std::string& h5_name, const std::string& dataset,
                      const char* indent) {
  return fmt::format(
      "{}<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}:{}"
      "</DataItem>\n",
      indent, dims, number_type, precision, h5_name, dataset);
}

std::string attribute(const char* name, bool vector, const char* number_type, int precision,
                      std::size_t n, const std::string& h5_name, const std::string& dataset) {
  const std::string dims = vector ? fmt::format("{} 3", n) : fmt::format("{}", n);
  return fmt::format(
      "          <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n{}"
      "          </Attribute>\n",
      name, vector ? "Vector" : "Scalar",
      data_item(dims, number_type, precision, h5_name, dataset, "            "));
}

std::string render_frame(const XdmfFrame& frame, const std::string& h5_name) {
  const std::string& g = frame.group;
  const std::size_t n = frame.particles;
  const std::string geometry = fmt::format(
      "          <Geometry GeometryType=\"XYZ\">\n{}          </Geometry>\n",
      data_item(fmt::format("{} 3", n), "Float", 8, h5_name, g + "/position", "            "));
  std::string xml = fmt::format(
      "      <Grid Name=\"{}\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
      "        <Time Value=\"{:.17g}\"/>\n"
      "        <Grid Name=\"particles\" GridType=\"Uniform\">\n"
      "          <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" "
      "NodesPerElement=\"1\"/>\n",
      g.substr(g.rfind('/') + 1), frame.time, n);
  xml += geometry;
  xml += attribute("radius", false, "Float", 8, n, h5_name, g + "/radius");
  xml += attribute("velocity", true, "Float", 8, n, h5_name, g + "/velocity");
  xml += attribute("omega", true, "Float", 8, n, h5_name, g + "/omega");
  xml += attribute("id", false, "Int", 4, n, h5_name, g + "/id");
  xml += attribute("material", false, "Int", 4, n, h5_name, g + "/material");
  xml += attribute("body", false, "Int", 4, n, h5_name, g + "/body");
  if (frame.fragments) xml += attribute("fragment", false, "Int", 4, n, h5_name, g + "/fragment");
  xml += "        </Grid>\n";
  // ParaView rejects a Polyline topology with no elements, so a frame without surviving bonds
  // has only the particle grid.
  if (frame.bonds > 0) {
    xml += fmt::format(
        "        <Grid Name=\"bonds\" GridType=\"Uniform\">\n"
        "          <Topology TopologyType=\"Polyline\" NumberOfElements=\"{}\" "
        "NodesPerElement=\"2\">\n{}"
        "          </Topology>\n",
        frame.bonds,
        data_item(fmt::format("{} 2", frame.bonds), "Int", 4, h5_name, g + "/bonds",
                  "            "));
    xml += geometry;
    xml += "        </Grid>\n";
  }
  xml += "      </Grid>\n";
  return xml;
}

}  // namespace

XdmfIndex::XdmfIndex(std::filesystem::path xmf_path, std::string h5_name)
    : path_(std::move(xmf_path)), h5_name_(std::move(h5_name)) {
  // Replaces a previous run's index at once, so it never points into the new file.
  write();
}

void XdmfIndex::add(const XdmfFrame& frame) {
  frames_xml_ += render_frame(frame, h5_name_);
  write();
}

void XdmfIndex::write() const {
  std::filesystem::path temp = path_;
  temp += ".tmp";
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out << "<?xml version=\"1.0\" ?>\n"
           "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
           "<Xdmf Version=\"2.0\">\n"
           "  <Domain>\n"
           "    <Grid Name=\"run\" GridType=\"Collection\" CollectionType=\"Temporal\">\n"
        << frames_xml_
        << "    </Grid>\n"
           "  </Domain>\n"
           "</Xdmf>\n";
    out.flush();
    if (!out)
      throw OutputError("cannot write the XDMF index '" + temp.string() +
                        "': check that the folder is writable and the disk not full");
  }
  std::error_code error;
  std::filesystem::rename(temp, path_, error);
  if (error)
    throw OutputError("cannot replace the XDMF index '" + path_.string() + "' with '" +
                      temp.string() + "': " + error.message());
}

}  // namespace shard
