#include "shard/analysis/column_table.hpp"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

#include "column_table_h5.hpp"
#include "hdf5_writer.hpp"
#include "shard/hdf5_quiet.hpp"

namespace shard::analysis {
namespace {

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string cell(const Column& c, std::size_t row) {
  return std::visit(
      [row](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::vector<double>>) return fmt::format("{:.17g}", v[row]);
        else if constexpr (std::is_same_v<T, std::vector<std::int64_t>>) return fmt::format("{}", v[row]);
        else return csv_text(v[row]);
      },
      c.values);
}

void write_string_attribute(hid_t object, const std::string& name, const std::string& text, const std::string& what) {
  h5::Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), text.empty() ? 1 : text.size());
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  h5::Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  h5::Handle attr(H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.valid() || H5Awrite(attr.get(), type.get(), text.c_str()) < 0)
    throw std::runtime_error(fmt::format("HDF5: cannot write attribute {} of {}", name, what));
}

void write_strings(hid_t group, const std::string& name, const std::vector<std::string>& values,
                   const std::string& what) {
  h5::Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  std::vector<const char*> pointers;
  for (const std::string& s : values) pointers.push_back(s.c_str());
  const hsize_t n = values.size();
  h5::Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  h5::Handle set(H5Dcreate2(group, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose);
  if (!set.valid() || (n > 0 && H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()) < 0))
    throw std::runtime_error("HDF5: cannot write " + what);
}

}  // namespace

std::size_t Column::size() const {
  return std::visit([](const auto& v) { return v.size(); }, values);
}

ColumnTable& ColumnTable::add(std::string name, std::vector<double> values) {
  columns.push_back({std::move(name), std::move(values)});
  return *this;
}
ColumnTable& ColumnTable::add(std::string name, std::vector<std::int64_t> values) {
  columns.push_back({std::move(name), std::move(values)});
  return *this;
}
ColumnTable& ColumnTable::add(std::string name, std::vector<std::string> values) {
  columns.push_back({std::move(name), std::move(values)});
  return *this;
}
ColumnTable& ColumnTable::note(std::string name, std::string text) {
  notes.emplace_back(std::move(name), std::move(text));
  return *this;
}

std::size_t ColumnTable::rows() const {
  if (columns.empty()) return 0;
  const std::size_t n = columns.front().size();
  for (const Column& c : columns)
    if (c.size() != n)
      throw std::invalid_argument(fmt::format("table column {} has {} rows, {} has {}", c.name, c.size(),
                                              columns.front().name, n));
  return n;
}

void write_csv(const ColumnTable& table, const std::filesystem::path& file) {
  const std::size_t rows = table.rows();
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  for (std::size_t c = 0; c < table.columns.size(); ++c) out << (c ? "," : "") << csv_text(table.columns[c].name);
  out << "\n";
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) out << (c ? "," : "") << cell(table.columns[c], r);
    out << "\n";
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

void h5::write_table(hid_t file, const std::string& file_name, const std::string& group, const ColumnTable& table) {
  const std::size_t rows = table.rows();
  const std::string what = fmt::format("{} in {}", group, file_name);
  if (group.empty() || group.front() != '/') throw std::runtime_error("HDF5 table group must be absolute: " + group);
  // Parents first, then the group itself replaced.
  for (std::size_t at = group.find('/', 1); at != std::string::npos; at = group.find('/', at + 1)) {
    const std::string parent = group.substr(0, at);
    if (!h5::has_link(file, parent)) h5::create_group(file, parent, fmt::format("{} in {}", parent, file_name));
  }
  if (h5::has_link(file, group) && H5Ldelete(file, group.c_str(), H5P_DEFAULT) < 0)
    throw std::runtime_error("HDF5: cannot replace " + what);
  const h5::Handle g = h5::create_group(file, group, what);
  for (const Column& c : table.columns) {
    const std::string where = fmt::format("{}/{} in {}", group, c.name, file_name);
    if (const auto* d = std::get_if<std::vector<double>>(&c.values))
      h5::write_dataset(g.get(), c.name, H5T_NATIVE_DOUBLE, {rows}, d->data(), where);
    else if (const auto* i = std::get_if<std::vector<std::int64_t>>(&c.values))
      h5::write_dataset(g.get(), c.name, H5T_NATIVE_INT64, {rows}, i->data(), where);
    else
      write_strings(g.get(), c.name, std::get<std::vector<std::string>>(c.values), where);
  }
  h5::write_int_attribute(g.get(), "rows", static_cast<std::int64_t>(rows), what);
  for (const auto& [name, text] : table.notes) write_string_attribute(g.get(), name, text, what);
  H5Fflush(file, H5F_SCOPE_GLOBAL);
}

void write_hdf5_table(const std::filesystem::path& file, const std::string& group, const ColumnTable& table) {
  const QuietHdf5Errors quiet;
  std::error_code ec;
  const bool exists = std::filesystem::exists(file, ec);
  h5::Handle f(exists ? H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)
                      : H5Fcreate(file.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT),
               H5Fclose);
  if (!f.valid())
    throw std::runtime_error(fmt::format("HDF5: cannot {} {}", exists ? "open for writing" : "create", file.string()));
  h5::write_table(f.get(), file.string(), group, table);
}

}  // namespace shard::analysis
