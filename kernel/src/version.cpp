#include "shard/version.hpp"

// Written at build time by cmake/ShardGitDescribe.cmake: SHARD_VERSION and SHARD_GIT_DESCRIBE, rewritten
// only when the checkout's description changes, so only this file recompiles after a commit.
#include "shard_git_describe.h"

namespace shard {

std::string_view version() { return SHARD_VERSION; }

std::string_view git_describe() { return SHARD_GIT_DESCRIBE; }

std::string version_line() {
  std::string line(version());
  if (!git_describe().empty()) line += " (git " + std::string(git_describe()) + ")";
  return line;
}

}  // namespace shard
