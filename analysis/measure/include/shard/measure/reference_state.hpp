#pragma once
// Where the reference's model stands on each library effect. An effect describes how a batch
// differs from the reference, so it moves the model from the reference's state (the scene's
// value, a --set, or a base parameter fitted on the reference), not from the library's neutral:
// a scene with lubricated rollers is the reference, and more or less friction than that, none
// included, are the effect's two sides.
#include <iosfwd>
#include <optional>
#include <vector>

#include "shard/measure/effect_library.hpp"
#include "shard/measure/model_plan.hpp"

namespace shard::measure {

// The value `model` gives `effect`'s parameter: its last override, else the scene file; for a
// value_format such as "[0.0, 0.0, {}]" the component the effect moves. None when neither sets it
// (the plugin's default, which the library's neutral is).
std::optional<double> effect_state(const ModelPlan& model, const CandidateEffect& effect);

// The effects re-centred on `reference`'s state (a machine compliance, which adds to the
// model's own, already starts there): an effect whose parameter the reference sets
// away from neutral gets that value as its neutral and keeps its trial step (turned the other way
// where the step would leave [min, max]). Throws, naming the effect's [[effect]] table, when the
// reference's value lies outside the effect's [min, max]: no size of the effect gives back the
// reference, so every contrast it was fitted to would be measured from a model it cannot reach.
std::vector<CandidateEffect> centred_on_reference(std::vector<CandidateEffect> effects, const ModelPlan& reference,
                                                  std::ostream& log);

// The same check alone, on the model before its base fit: a scene whose own state is out of an
// effect's reach is refused before a single run.
void check_effects_reach(const std::vector<CandidateEffect>& effects, const ModelPlan& reference);

}  // namespace shard::measure
