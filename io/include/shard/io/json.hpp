#pragma once
// Every JSON file Shard writes or reads goes through here, over nlohmann-json.
//
// A document Shard writes is one object whose first two keys say what wrote it:
//     {"format_version": 1, "shard_version": "0.1.0", ...the document's own keys...}
// `format_version` is an integer owned by each kind of document (a bending report, a calibration,
// ...): raise it when a key changes meaning or disappears, so a reader can refuse a file newer than
// it understands instead of misreading it. Keys keep the order they were added in (ordered_json),
// which is the order a person reading the file expects.
//
// Numbers that are not finite (NaN, +-inf) are written as null: JSON has no literal for them and a
// strict parser refuses `nan`. Files are written to a temporary file beside the target, flushed to
// disk and renamed over it, so a reader never sees half a document.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shard::io {

using Json = nlohmann::ordered_json;

// Any JSON file that cannot be read, parsed or understood. what() names the file, the line and
// column of a syntax error or the key of a bad field, and the fix.
class JsonError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The Shard version that writes documents ("0.1.0").
const char* shard_version();

// {"format_version": format_version, "shard_version": shard_version()}; add the document's keys.
Json json_document(int format_version);

// The document as text: indented by two spaces, one key a line, ending in a newline.
std::string json_text(const Json& document);

// The value as one line of a JSON Lines file: compact, no newline inside, one newline at the end.
std::string json_line(const Json& value);

// Writes json_text(document) to `file` atomically (temp file + flush + rename). Throws JsonError
// naming the file when it cannot be written.
void write_json(const std::filesystem::path& file, const Json& document);

// Parses `text`, which came from `origin` (a file name) starting at line `first_line` (a line of a
// JSON Lines file is parsed with its own line number). Throws JsonError "origin:line:column: ...".
Json parse_json(const std::string& text, const std::string& origin, std::size_t first_line = 1);

// Reads and parses a whole file; throws JsonError when it is missing, unreadable or not JSON.
Json read_json(const std::filesystem::path& file);

// The fields of one JSON object read with errors that name the file and the key's path
// ("runs[2].force_max_N") and say what was expected.
class JsonFields {
 public:
  JsonFields(const Json& object, std::string origin, std::string path = "");

  bool has(const std::string& key) const;
  // A number; null (how a non-finite value is written) reads as NaN.
  double number(const std::string& key) const;
  std::optional<double> optional_number(const std::string& key) const;  // nullopt when absent
  long long integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  std::string text(const std::string& key) const;
  JsonFields object(const std::string& key) const;
  // The elements of an array of objects, each with its index in the path.
  std::vector<JsonFields> objects(const std::string& key) const;
  std::vector<double> numbers(const std::string& key) const;
  const Json& json() const { return object_; }

 private:
  const Json& field(const std::string& key, const char* expected) const;
  [[noreturn]] void mistyped(const std::string& key, const char* expected) const;
  std::string key_path(const std::string& key) const;

  const Json& object_;
  std::string origin_;
  std::string path_;
};

// Reads a document written by write_json: its format_version must be an integer in
// 1 .. newest_version (a newer file is refused, naming both versions and the fix). `kind` names the
// document in messages ("bending report"). The returned Json owns the fields; read them with
// JsonFields(document, file.string()).
Json read_json_document(const std::filesystem::path& file, const std::string& kind, int newest_version);

}  // namespace shard::io
