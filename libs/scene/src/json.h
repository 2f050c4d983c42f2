// json.h (private to layers::scene) -- a small JSON reader for the MPFB2
// asset files (rig, weights, vertex groups, T-pose). Numbers are doubles,
// objects keep their keys in file order. Errors are layers::InputError
// naming the file and line.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace layers::scene::json {

struct Value {
  enum class Kind { Null, Bool, Number, String, Array, Object };
  Kind kind = Kind::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Value> array;
  std::vector<std::pair<std::string, Value>> object;

  // Object member or nullptr.
  const Value* find(const std::string& key) const;
};

// Parses `text`; `name` (a file path) is used in error messages.
Value parse(const std::string& text, const std::string& name);
Value parse_file(const std::string& path);

// Typed access that throws InputError("<file>", "<what>", ...) on a kind
// mismatch; `file` and `what` only label the error.
const Value& member(const Value& object, const std::string& key, const std::string& file);
double number(const Value& v, const std::string& file, const std::string& what);
const std::string& string(const Value& v, const std::string& file, const std::string& what);
const std::vector<Value>& array(const Value& v, const std::string& file, const std::string& what);

}  // namespace layers::scene::json
