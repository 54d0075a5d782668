#pragma once
// Which Shard this is: the release (CMake's PROJECT_VERSION, semantic versioning, tags vX.Y.Z) and,
// when built from a git checkout, `git describe` of the tree it was built from. `shard --version`
// prints version_line(); run.h5 stores version() and git_describe() as attributes; every JSON
// report should carry them too, so a figure can be traced to the code that made it.
#include <string>
#include <string_view>

namespace shard {

// "0.1.0": the release this build belongs to.
std::string_view version();

// "v0.1.0-12-g1a2b3c4-dirty" (or a bare abbreviated commit when no release tag is reachable);
// empty when the build did not come from a git checkout, e.g. a source tarball.
std::string_view git_describe();

// "0.1.0" or "0.1.0 (git v0.1.0-12-g1a2b3c4-dirty)": one line for humans.
std::string version_line();

}  // namespace shard
