// Regenerates the contact laws' reference files (contact_reference.hpp) after a deliberate
// physics change:  write_contact_reference SOURCE_DIR   (plugins/contact/README.md).
// The configuration is the fixed one of random_configuration(); the results are those of the
// plugins in this build's plugin folder.
#include <cstdio>
#include <exception>

#include "contact_reference.hpp"

int main(int argc, char** argv) {
  using namespace shard;
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_contact_reference SOURCE_DIR\n");
    return 2;
  }
  try {
    PluginHost host;
    host.load_directories({SHARD_BUILD_DIR "/plugins"});
    for (const auto& c : test::reference_cases()) {
      const auto file = test::reference_file(argv[1], c);
      test::write_reference(file, c, test::run_case(host, c, test::random_configuration(48), 1e-6, 4));
      std::printf("wrote %s\n", file.string().c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "write_contact_reference: %s\n", e.what());
    return 1;
  }
  return 0;
}
