// json_file.h (private to layers::body) -- the MPFB2 asset files (rig,
// weights, vertex groups, T-pose) read with nlohmann_json, objects keeping
// their keys in file order, and typed access whose errors are InputErrors
// naming the file, the field, what was expected and what was found.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace layers::body::json {

using Value = nlohmann::ordered_json;

// A syntax error names the line and column.
Value parse_file(const std::string& path);

// Typed access; `file` and `what` only label the error.
const Value& member(const Value& object, const std::string& key, const std::string& file);
const Value& object(const Value& v, const std::string& file, const std::string& what);
const Value& array(const Value& v, const std::string& file, const std::string& what);
double number(const Value& v, const std::string& file, const std::string& what);
const std::string& string(const Value& v, const std::string& file, const std::string& what);

}  // namespace layers::body::json
