#include "shard/io/json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>

#include "shard/io/atomic_file.hpp"

namespace shard::io {
namespace {

// nlohmann's message without its "[json.exception.parse_error.101] parse error at line 1, column 5: "
// prefix (the position is given again, relative to the file, by the caller).
std::string parse_reason(const std::string& what) {
  const auto column = what.find("column ");
  const auto colon = column == std::string::npos ? what.find(": ") : what.find(": ", column);
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

const char* type_name(const Json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "true/false";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "text";
  if (j.is_array()) return "an array";
  return "an object";
}

}  // namespace

const char* shard_version() { return SHARD_VERSION; }

Json json_document(int format_version) {
  Json document = Json::object();
  document["format_version"] = format_version;
  document["shard_version"] = shard_version();
  return document;
}

std::string json_text(const Json& document) {
  // dump() writes NaN and infinities as null, the one spelling a strict parser accepts.
  return document.dump(2) + "\n";
}

std::string json_line(const Json& value) {
  // dump() without indent escapes every newline inside strings, so the record stays on one line.
  return value.dump() + "\n";
}

void write_json(const std::filesystem::path& file, const Json& document) {
  try {
    write_file_atomically(file, json_text(document));
  } catch (const std::runtime_error& e) {
    throw JsonError(e.what());
  }
}

Json parse_json(const std::string& text, const std::string& origin, std::size_t first_line) {
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    // e.byte counts the characters read, the offending one included.
    const std::size_t at = std::min(e.byte > 0 ? e.byte - 1 : 0, text.size());
    const auto before = std::string_view(text).substr(0, at);
    const std::size_t line = first_line + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
    const auto newline = before.rfind('\n');
    const std::size_t column = newline == std::string_view::npos ? at + 1 : at - newline;
    throw JsonError(fmt::format("{}:{}:{}: not valid JSON: {} (non-finite numbers are written as null; "
                                "check quotes, commas and brackets)",
                                origin, line, column, parse_reason(e.what())));
  }
}

Json read_json(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw JsonError(fmt::format("{}: cannot be opened for reading (check the path{})", file.string(),
                                std::filesystem::is_directory(file) ? "; it is a folder" : ""));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_json(text.str(), file.string());
}

Json read_json_document(const std::filesystem::path& file, const std::string& kind, int newest_version) {
  Json document = read_json(file);
  if (!document.is_object())
    throw JsonError(fmt::format("{}: a {} is a JSON object {{...}}, this file holds {}", file.string(), kind,
                                type_name(document)));
  const JsonFields fields(document, file.string());
  const long long version = fields.integer("format_version");
  if (version < 1 || version > newest_version)
    throw JsonError(fmt::format("{}: key 'format_version' is {}, but this Shard ({}) reads {} files of format "
                                "version 1 to {}: {}",
                                file.string(), version, shard_version(), kind, newest_version,
                                version > newest_version ? "read it with the newer Shard that wrote it"
                                                         : "the file is damaged; write it again"));
  return document;
}

JsonFields::JsonFields(const Json& object, std::string origin, std::string path)
    : object_(object), origin_(std::move(origin)), path_(std::move(path)) {
  if (!object_.is_object())
    throw JsonError(fmt::format("{}: {} is {}, expected an object {{...}}", origin_,
                                path_.empty() ? std::string("the document") : "key '" + path_ + "'",
                                type_name(object_)));
}

std::string JsonFields::key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

void JsonFields::mistyped(const std::string& key, const char* expected) const {
  throw JsonError(fmt::format("{}: key '{}' is {}, expected {}", origin_, key_path(key), type_name(object_.at(key)),
                              expected));
}

const Json& JsonFields::field(const std::string& key, const char* expected) const {
  const auto it = object_.find(key);
  if (it == object_.end())
    throw JsonError(fmt::format("{}: key '{}' ({}) is missing; add it to {}", origin_, key_path(key), expected,
                                path_.empty() ? std::string("the document") : "'" + path_ + "'"));
  return *it;
}

bool JsonFields::has(const std::string& key) const { return object_.contains(key); }

double JsonFields::number(const std::string& key) const {
  const Json& j = field(key, "a number");
  if (j.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!j.is_number()) mistyped(key, "a number");
  return j.get<double>();
}

std::optional<double> JsonFields::optional_number(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return number(key);
}

long long JsonFields::integer(const std::string& key) const {
  const Json& j = field(key, "an integer");
  if (!j.is_number_integer()) mistyped(key, "an integer");
  return j.get<long long>();
}

bool JsonFields::boolean(const std::string& key) const {
  const Json& j = field(key, "true or false");
  if (!j.is_boolean()) mistyped(key, "true or false");
  return j.get<bool>();
}

std::string JsonFields::text(const std::string& key) const {
  const Json& j = field(key, "text");
  if (!j.is_string()) mistyped(key, "text");
  return j.get<std::string>();
}

JsonFields JsonFields::object(const std::string& key) const {
  return JsonFields(field(key, "an object"), origin_, key_path(key));
}

std::vector<JsonFields> JsonFields::objects(const std::string& key) const {
  const Json& j = field(key, "an array of objects");
  if (!j.is_array()) mistyped(key, "an array of objects");
  std::vector<JsonFields> out;
  for (std::size_t k = 0; k < j.size(); ++k)
    out.emplace_back(j[k], origin_, fmt::format("{}[{}]", key_path(key), k));
  return out;
}

std::vector<double> JsonFields::numbers(const std::string& key) const {
  const Json& j = field(key, "an array of numbers");
  if (!j.is_array()) mistyped(key, "an array of numbers");
  std::vector<double> out;
  for (std::size_t k = 0; k < j.size(); ++k) {
    if (j[k].is_null()) out.push_back(std::numeric_limits<double>::quiet_NaN());
    else if (j[k].is_number()) out.push_back(j[k].get<double>());
    else
      throw JsonError(fmt::format("{}: key '{}[{}]' is {}, expected a number", origin_, key_path(key), k,
                                  type_name(j[k])));
  }
  return out;
}

}  // namespace shard::io
