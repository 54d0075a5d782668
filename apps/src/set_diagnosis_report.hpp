#pragma once
// The single-set diagnosis's report (measure_diagnose.cpp): diagnose.md and diagnose.json rendered
// from shard/measure/set_diagnosis.hpp's result.
#include <cstddef>
#include <filesystem>
#include <string>

#include "shard/io/json.hpp"
#include "shard/measure/comparison.hpp"
#include "shard/measure/set_diagnosis.hpp"

namespace shard {

// What the diagnosis is rendered from: its result and what the command was asked.
struct SetDiagnosisReport {
  const measure::SetDiagnosisResult& result;
  std::filesystem::path measurements, scene, library;
  int seeds = 0;
  measure::DataCoverage coverage;  // what the data span (loading rates, specimen sizes)
  int max_effects = 0;
  measure::Scoring scoring = measure::Scoring::Own;
  measure::ScoreReference score_reference = measure::ScoreReference::Normal;
};

std::string set_diagnosis_markdown(const SetDiagnosisReport& r);
io::Json set_diagnosis_json(const SetDiagnosisReport& r);

}  // namespace shard
