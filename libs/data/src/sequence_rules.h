// sequence_rules.h (private) -- value rules shared by the writer's
// in-memory checks and the validator's file checks: index ranges, joint
// parents, sequence ids, garment types and layers. Each returns the
// problem ("expected ..., got ...") or nullopt.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace layers::data {

// Every value in [lo, hi); rows of `width` values for the message.
std::optional<std::string> check_index_range(const std::vector<std::int32_t>& values, std::int64_t lo, std::int64_t hi,
                                             std::size_t width);
// Each parent in [-1, J) and not the joint itself.
std::optional<std::string> check_joint_parents(const std::vector<std::int32_t>& parents);
std::optional<std::string> check_sequence_id(const std::string& id);
std::optional<std::string> check_garment_type(const std::string& type);
std::optional<std::string> check_garment_layer(std::int64_t layer);
bool is_reserved(const std::string& name, const std::vector<std::string>& reserved);

}  // namespace layers::data
