// plugins/skinned/src/spec.h -- the "skinned" reference model: each
// garment vertex follows its nearest body vertex through the body's linear
// blend skinning,
//   p(t+1) = sum_j w_j [R_j(t+1) R_j(t)^T (p(t) - p_j(t)) + p_j(t+1)],
// with the joint transforms [R|p] of StepInput::joints (t) and joints_next
// (t+1) and the weights w_j (top 4, renormalised to sum 1) of that body
// vertex (SequenceStatic::skin_index / skin_weight). No parameters, nothing
// to train: the anchor "a garment glued to the skin" for accuracy charts.
//
// Binding: nothing body-dependent is known when a sequence is prepared, so
// each garment vertex is bound to the body vertex nearest to it (k-d tree,
// garment at t against the body at t) on the first step after prepare()
// made the sequence current without a cached binding -- that is, once per
// prepare() of an id the model has not cached (or whose cache entry was
// evicted; see Model::set_cache_capacity). Later steps of that id, also
// after preparing other sequences in between, reuse the binding. It is
// deterministic for a given first step: the same sequence prepared and
// stepped the same way binds the same way.
//
// Errors: a sequence without skin_index / skin_weight is a
// layers::InputError at prepare(); a step without joints or joints_next,
// or with fewer joints than the skinning weights name, is a layers::Error.
// Torch-free declaration.
#pragma once

#include "layers/zoo/registry.h"

namespace layers::reference {

// `params` must be empty (or absent); any key is a layers::InputError.
std::shared_ptr<zoo::Model> make_skinned_model(const cfg::Node& params);
inline constexpr zoo::ModelSpec kSkinned{
    "skinned", "reference: garment vertices follow their nearest body vertex's skinning (no parameters)",
    make_skinned_model};

}  // namespace layers::reference
