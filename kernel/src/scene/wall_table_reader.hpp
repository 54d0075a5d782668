#pragma once
// Reads a [[wall]] motion_table: a CSV file with a header naming `time` and either `displacement`
// or `velocity` (SI units; '#' lines are comments), one row per instant; a rotation_table names
// `angle` [rad] or `angular_velocity` [rad/s] instead.
#include <filesystem>

#include "shard/wall_motion.hpp"

namespace shard {

// Throws SceneError with the table's file:line:column for an unknown or missing column, a cell
// that is no number, a row with the wrong number of cells, or a time that does not increase.
enum class WallTableKind { Translation, Rotation };
WallTable read_wall_table(const std::filesystem::path& file, WallTableKind kind = WallTableKind::Translation);

}  // namespace shard
