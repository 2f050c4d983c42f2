// Reading JSON asset files with nlohmann_json (see json_file.h).
#include "json_file.h"

#include "layers/core/error.h"
#include "layers/core/text_file.h"

namespace layers::body::json {
namespace {

std::string kind_name(const Value& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  return v.type_name();
}

}  // namespace

Value parse_file(const std::string& path) {
  const std::string text = read_text_file(path);
  try {
    return Value::parse(text);
  } catch (const Value::parse_error& e) {
    // e.what(): "[json.exception.parse_error.N] parse error at line L, column C: <reason>"
    std::string where, reason = e.what();
    const std::size_t at = reason.find(" at line ");
    const std::size_t colon = at == std::string::npos ? at : reason.find(": ", at);
    if (colon != std::string::npos) {
      where = reason.substr(at + 4, colon - at - 4);
      reason = reason.substr(colon + 2);
    }
    throw InputError(path, where, "valid JSON", reason);
  }
}

const Value& member(const Value& object, const std::string& key, const std::string& file) {
  if (!object.is_object()) throw InputError(file, key, "an object holding it", kind_name(object));
  const auto it = object.find(key);
  if (it == object.end()) throw InputError(file, key, "this key", "nothing");
  return *it;
}

const Value& object(const Value& v, const std::string& file, const std::string& what) {
  if (!v.is_object()) throw InputError(file, what, "an object", kind_name(v));
  return v;
}

const Value& array(const Value& v, const std::string& file, const std::string& what) {
  if (!v.is_array()) throw InputError(file, what, "an array", kind_name(v));
  return v;
}

double number(const Value& v, const std::string& file, const std::string& what) {
  if (!v.is_number()) throw InputError(file, what, "a number", kind_name(v));
  return v.get<double>();
}

const std::string& string(const Value& v, const std::string& file, const std::string& what) {
  if (!v.is_string()) throw InputError(file, what, "a string", kind_name(v));
  return v.get_ref<const std::string&>();
}

}  // namespace layers::body::json
