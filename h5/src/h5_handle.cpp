#include "h5_handle.hpp"

#include <algorithm>
#include <vector>

#include "shard/io/output_error.hpp"

namespace shard::h5 {

namespace {

herr_t collect_message(unsigned depth, const H5E_error2_t* error, void* client) {
  auto& frames = *static_cast<std::vector<std::string>*>(client);
  // The outermost frame ("unable to open file" ...) repeats the context Shard already gives;
  // the deeper ones carry the cause (permission denied, no such file, ...).
  if (depth > 0 && error->desc != nullptr && error->desc[0] != '\0') frames.emplace_back(error->desc);
  return 0;
}

// The quoted value of `key = '...'` in a file driver's message, or "".
std::string quoted_field(const std::string& text, const std::string& key) {
  const std::string tag = key + " = '";
  const auto start = text.find(tag);
  if (start == std::string::npos) return {};
  const auto end = text.find('\'', start + tag.size());
  return end == std::string::npos ? std::string() : text.substr(start + tag.size(), end - start - tag.size());
}

// The file driver's message spans lines and lists time, descriptor and buffer address; the file
// name and its "error message" (e.g. 'File too large') are what a user needs.
std::string tidy(std::string text) {
  const std::string cause = quoted_field(text, "error message");
  const auto colon = text.find(':');
  if (!cause.empty() && colon != std::string::npos) {
    const std::string file = quoted_field(text, "filename");
    text = text.substr(0, colon) + (file.empty() ? "" : " on '" + file + "'") + ": " + cause;
  }
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

}  // namespace

std::string take_error_stack() {
  std::vector<std::string> frames;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_message, &frames);
  H5Eclear2(H5E_DEFAULT);
  if (frames.empty()) return {};
  // The first frame says what failed, the innermost why; the two dozen between are HDF5's call path.
  const std::string cause = tidy(frames.back());
  if (frames.size() == 1) return cause;
  return tidy(frames.front()) + (frames.size() > 2 ? "; ...; " : "; ") + cause;
}

void fail(const std::string& context) {
  const std::string cause = take_error_stack();
  throw OutputError(cause.empty() ? context : context + ": " + cause);
}

Handle check(hid_t id, Handle::Closer closer, const std::string& context) {
  if (id < 0) fail(context);
  return Handle(id, closer);
}

void check(herr_t status, const std::string& context) {
  if (status < 0) fail(context);
}

Handle file_handle(hid_t id, const std::string& context) { return check(id, H5Fclose, context); }
Handle group_handle(hid_t id, const std::string& context) { return check(id, H5Gclose, context); }
Handle dataset_handle(hid_t id, const std::string& context) { return check(id, H5Dclose, context); }
Handle space_handle(hid_t id, const std::string& context) { return check(id, H5Sclose, context); }
Handle type_handle(hid_t id, const std::string& context) { return check(id, H5Tclose, context); }
Handle plist_handle(hid_t id, const std::string& context) { return check(id, H5Pclose, context); }
Handle attribute_handle(hid_t id, const std::string& context) {
  return check(id, H5Aclose, context);
}

}  // namespace shard::h5
