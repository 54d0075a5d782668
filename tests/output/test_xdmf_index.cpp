// The .xmf index beside run.h5: well-formed XML, one time step per frame with the frame's time,
// and every DataItem names a dataset of run.h5 that exists with the dimensions it declares.
#include <doctest/doctest.h>
#include <hdf5.h>

#include <fstream>
#include <sstream>

#include "run_fixtures.hpp"

using namespace shard;
using namespace shard::test;

namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The tags of an XML text: name, closing ("</x>") and self-closing ("<x/>") flags; <?...?> and
// <!...> are skipped. (String scanning, not std::regex: GCC 12 warns inside <regex> under the
// sanitizers, and warnings are errors.)
struct Tag {
  std::string name, text;  // text: everything between '<' and '>'
  bool closing = false, self_closing = false;
};

std::vector<Tag> tags(const std::string& xml) {
  std::vector<Tag> out;
  for (auto open = xml.find('<'); open != std::string::npos; open = xml.find('<', open + 1)) {
    const auto close = xml.find('>', open);
    if (close == std::string::npos) break;
    Tag tag;
    tag.text = xml.substr(open + 1, close - open - 1);
    if (tag.text.empty() || tag.text[0] == '?' || tag.text[0] == '!') continue;
    tag.closing = tag.text[0] == '/';
    tag.self_closing = tag.text.back() == '/';
    const auto name_start = tag.closing ? 1u : 0u;
    tag.name = tag.text.substr(name_start, tag.text.find_first_of(" /", name_start) - name_start);
    out.push_back(tag);
  }
  return out;
}

bool tags_balanced(const std::string& xml) {
  std::vector<std::string> open;
  for (const Tag& tag : tags(xml)) {
    if (tag.self_closing) continue;
    if (tag.closing) {
      if (open.empty() || open.back() != tag.name) return false;
      open.pop_back();
    } else {
      open.push_back(tag.name);
    }
  }
  return open.empty();
}

// The value of attribute `name` in a tag's text.
std::string attribute_value(const std::string& tag_text, const std::string& name) {
  const auto start = tag_text.find(" " + name + "=\"");
  if (start == std::string::npos) return {};
  const auto value = start + name.size() + 3;
  return tag_text.substr(value, tag_text.find('"', value) - value);
}

struct DataItem {
  std::vector<hsize_t> dims;
  std::string file, dataset;
};

std::vector<DataItem> data_items(const std::string& xml) {
  std::vector<DataItem> items;
  for (auto pos = xml.find("<DataItem "); pos != std::string::npos;
       pos = xml.find("<DataItem ", pos + 1)) {
    const auto tag_end = xml.find('>', pos);
    const auto body_end = xml.find("</DataItem>", tag_end);
    const std::string tag = xml.substr(pos + 1, tag_end - pos - 1);
    if (attribute_value(tag, "Format") != "HDF") continue;
    const std::string body = xml.substr(tag_end + 1, body_end - tag_end - 1);
    DataItem d;
    std::istringstream dims(attribute_value(tag, "Dimensions"));
    for (hsize_t v; dims >> v;) d.dims.push_back(v);
    d.file = body.substr(0, body.find(':'));
    d.dataset = body.substr(body.find(':') + 1);
    items.push_back(d);
  }
  return items;
}

std::vector<double> times(const std::string& xml) {
  std::vector<double> out;
  for (const Tag& tag : tags(xml))
    if (tag.name == "Time") out.push_back(std::stod(attribute_value(tag.text, "Value")));
  return out;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

// The dataset's dimensions, or empty when it does not exist.
std::vector<hsize_t> dataset_dims(hid_t file, const std::string& path) {
  if (H5Oexists_by_name(file, path.c_str(), H5P_DEFAULT) <= 0) return {};
  const hid_t dataset = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (dataset < 0) return {};
  const hid_t space = H5Dget_space(dataset);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(dataset);
  return dims;
}

}  // namespace

TEST_CASE("the XDMF index references only datasets that exist, with their dimensions") {
  TempFolder folder("xdmf");
  const auto h5_path = folder.path() / "beam.h5";
  const auto xmf_path = folder.path() / "beam.xmf";
  const std::vector<double> frame_times{0.0, 1e-4 / 3.0, 2.5e-4};
  std::vector<Index> labels(7, 3);
  {
    RunWriter writer(h5_path, make_metadata(), {"pin"});
    REQUIRE(std::filesystem::exists(xmf_path));  // an index with no frames from the start
    CHECK(data_items(read_text(xmf_path)).empty());
    writer.write_frame(0, frame_times[0], make_particles(7, 0), make_chain(7, 99));
    writer.write_frame(5, frame_times[1], make_particles(7, 1), make_chain(7, 2), &labels);
    writer.write_frame(9, frame_times[2], make_particles(7, 2), Bonds{});  // no bonds left
    CHECK_FALSE(std::filesystem::exists(folder.path() / "beam.xmf.tmp"));
  }
  const std::string xml = read_text(xmf_path);
  CHECK(tags_balanced(xml));
  CHECK(times(xml) == frame_times);  // printed with 17 digits: exact
  CHECK(count(xml, "TopologyType=\"Polyvertex\"") == 3);
  CHECK(count(xml, "TopologyType=\"Polyline\"") == 2);  // the bond-less frame has none
  CHECK(count(xml, "Attribute Name=\"fragment\"") == 1);

  const auto items = data_items(xml);
  // Per frame: position (particles), radius, velocity, omega, id, material, body; with bonds:
  // bonds + position again; frame 1 has fragment.
  CHECK(items.size() == 9 + 10 + 7);
  CHECK(count(xml, "Attribute Name=\"body\"") == 3);
  const hid_t file = H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  for (const DataItem& item : items) {
    CAPTURE(item.dataset);
    CHECK(item.file == "beam.h5");  // relative to the .xmf's folder
    CHECK(dataset_dims(file, item.dataset) == item.dims);
  }
  H5Fclose(file);
}
