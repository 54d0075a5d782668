#include "h5_handle.hpp"

#include "shard/output.hpp"

namespace shard::h5 {

namespace {

herr_t collect_message(unsigned depth, const H5E_error2_t* error, void* client) {
  auto& text = *static_cast<std::string*>(client);
  // The outermost two frames ("unable to open file" ...) repeat the context Shard already
  // gives; the deeper ones carry the cause (permission denied, no such file, ...).
  if (depth > 0 && error->desc != nullptr && error->desc[0] != '\0') {
    if (!text.empty()) text += "; ";
    text += error->desc;
  }
  return 0;
}

}  // namespace

std::string take_error_stack() {
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_message, &text);
  H5Eclear2(H5E_DEFAULT);
  return text;
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
