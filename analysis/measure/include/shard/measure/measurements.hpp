#pragma once
// The measurement folder (docs/how-to/bring-lab-data.md):
//   metadata.toml    name, load-cell and displacement uncertainty, how the test was run ([test]),
//                    free-form [notes]
//   specimens.csv    one row per specimen: id, geometry, loading rate, optional crack position and
//                    fragment count, optional curve / fragments file names
//   curves/<id>.csv  time, displacement, force [, u_displacement, u_force]
//   fragments/<id>.csv (optional) size [, mass]
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "shard/measure/curve.hpp"
#include "shard/measure/test_conditions.hpp"

namespace shard::measure {

struct Metadata {
  std::string name;
  double load_cell_uncertainty = 0;     // N, standard uncertainty of one force reading
  double displacement_uncertainty = 0;  // m, standard uncertainty of one displacement reading
  double crack_position_uncertainty = 0;  // m
  TestConditions test;                    // [test]
  std::string notes;  // top-level `notes` (text) or [notes] (any keys, kept as TOML text); never interpreted
};

struct Specimen {
  std::string id;
  double length = 0, width = 0, height = 0;  // m: L, b, h
  double span = 0;                           // m, support distance
  double pin_distance = 0;                   // m, loading-pin distance d
  double loading_rate = 0;                   // m/s
  std::optional<double> crack_position;      // m, from the specimen centre along the length
  std::optional<double> fragment_count;
  Curve curve;
  std::vector<double> fragment_sizes;  // m, equivalent diameters; empty when not measured
  std::vector<double> fragment_masses; // kg, same length as sizes, or empty (then volume ~ size^3)
};

struct MeasurementSet {
  std::filesystem::path folder;
  Metadata metadata;
  std::vector<Specimen> specimens;
  // Distinct loading rates, ascending: specimens at one rate are replicates of each other.
  std::vector<double> loading_rates() const;
};

MeasurementSet read_measurements(const std::filesystem::path& folder);
Metadata read_metadata(const std::filesystem::path& file);
// Reads one curve file; missing uncertainty columns are filled from the metadata, and the known
// zero offset ([test] zero_offset) is subtracted from every force.
Curve read_curve(const std::filesystem::path& file, const Metadata& metadata);
void read_fragments(const std::filesystem::path& file, Specimen& specimen);

// Writers for the same format (used by `shard synth`).
void write_curve(const std::filesystem::path& file, const Curve& curve);
void write_measurements(const MeasurementSet& set, const std::filesystem::path& folder);

}  // namespace shard::measure
