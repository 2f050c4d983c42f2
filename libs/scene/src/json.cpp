// A recursive-descent JSON reader (see json.h).
#include "json.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "layers/core/error.h"
#include "layers/core/text_file.h"

namespace layers::scene::json {
namespace {

class Parser {
 public:
  Parser(const std::string& text, const std::string& name) : s_(text), name_(name) {}

  Value document() {
    Value v = value(0);
    skip_space();
    if (pos_ != s_.size()) fail("end of document", describe());
    return v;
  }

 private:
  const std::string& s_;
  const std::string& name_;
  std::size_t pos_ = 0;
  int line_ = 1;

  [[noreturn]] void fail(const std::string& expected, const std::string& got) const {
    throw InputError(name_, "line " + std::to_string(line_), expected, got);
  }
  std::string describe() const {
    if (pos_ >= s_.size()) return "end of file";
    return "'" + s_.substr(pos_, 12) + "'";
  }
  void skip_space() {
    while (pos_ < s_.size()) {
      char c = s_[pos_];
      if (c == '\n') ++line_;
      if (c != ' ' && c != '\n' && c != '\r' && c != '\t') break;
      ++pos_;
    }
  }
  bool consume(char c) {
    skip_space();
    if (pos_ < s_.size() && s_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!consume(c)) fail(std::string("'") + c + "'", describe());
  }
  bool literal(const char* word) {
    std::size_t n = std::char_traits<char>::length(word);
    if (s_.compare(pos_, n, word) == 0) {
      pos_ += n;
      return true;
    }
    return false;
  }

  Value value(int depth) {
    if (depth > 200) fail("nesting depth <= 200", "deeper nesting");
    skip_space();
    if (pos_ >= s_.size()) fail("a value", "end of file");
    Value v;
    char c = s_[pos_];
    if (c == '{') {
      ++pos_;
      v.kind = Value::Kind::Object;
      if (consume('}')) return v;
      do {
        skip_space();
        std::string key = quoted();
        expect(':');
        v.object.emplace_back(std::move(key), value(depth + 1));
      } while (consume(','));
      expect('}');
    } else if (c == '[') {
      ++pos_;
      v.kind = Value::Kind::Array;
      if (consume(']')) return v;
      do {
        v.array.push_back(value(depth + 1));
      } while (consume(','));
      expect(']');
    } else if (c == '"') {
      v.kind = Value::Kind::String;
      v.string = quoted();
    } else if (literal("true")) {
      v.kind = Value::Kind::Bool;
      v.boolean = true;
    } else if (literal("false")) {
      v.kind = Value::Kind::Bool;
    } else if (literal("null")) {
      v.kind = Value::Kind::Null;
    } else {
      const char* begin = s_.c_str() + pos_;
      char* end = nullptr;
      v.number = std::strtod(begin, &end);
      if (end == begin) fail("a JSON value", describe());
      v.kind = Value::Kind::Number;
      pos_ += static_cast<std::size_t>(end - begin);
    }
    return v;
  }

  std::string quoted() {
    if (pos_ >= s_.size() || s_[pos_] != '"') fail("a string", describe());
    ++pos_;
    std::string out;
    while (pos_ < s_.size() && s_[pos_] != '"') {
      char c = s_[pos_++];
      if (c == '\n') fail("a closing '\"'", "end of line");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= s_.size()) break;
      char e = s_[pos_++];
      switch (e) {
        case 'n': out += '\n'; break;
        case 't': out += '\t'; break;
        case 'r': out += '\r'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'u': {
          if (pos_ + 4 > s_.size()) fail("four hex digits", "end of file");
          unsigned code = static_cast<unsigned>(std::stoul(s_.substr(pos_, 4), nullptr, 16));
          pos_ += 4;
          // UTF-8 encoding of a BMP code point (surrogates are kept as is).
          if (code < 0x80) {
            out += static_cast<char>(code);
          } else if (code < 0x800) {
            out += static_cast<char>(0xC0 | (code >> 6));
            out += static_cast<char>(0x80 | (code & 0x3F));
          } else {
            out += static_cast<char>(0xE0 | (code >> 12));
            out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
            out += static_cast<char>(0x80 | (code & 0x3F));
          }
          break;
        }
        default: out += e;
      }
    }
    if (pos_ >= s_.size()) fail("a closing '\"'", "end of file");
    ++pos_;
    return out;
  }
};

const char* kind_name(Value::Kind k) {
  switch (k) {
    case Value::Kind::Null: return "null";
    case Value::Kind::Bool: return "a boolean";
    case Value::Kind::Number: return "a number";
    case Value::Kind::String: return "a string";
    case Value::Kind::Array: return "an array";
    case Value::Kind::Object: return "an object";
  }
  return "?";
}

}  // namespace

const Value* Value::find(const std::string& key) const {
  for (const auto& [k, v] : object)
    if (k == key) return &v;
  return nullptr;
}

Value parse(const std::string& text, const std::string& name) { return Parser(text, name).document(); }

Value parse_file(const std::string& path) {
  return parse(read_text_file(path), path);
}

const Value& member(const Value& object, const std::string& key, const std::string& file) {
  if (object.kind != Value::Kind::Object) throw InputError(file, key, "an object holding it", kind_name(object.kind));
  const Value* v = object.find(key);
  if (!v) throw InputError(file, key, "this key", "nothing");
  return *v;
}

double number(const Value& v, const std::string& file, const std::string& what) {
  if (v.kind != Value::Kind::Number) throw InputError(file, what, "a number", kind_name(v.kind));
  return v.number;
}

const std::string& string(const Value& v, const std::string& file, const std::string& what) {
  if (v.kind != Value::Kind::String) throw InputError(file, what, "a string", kind_name(v.kind));
  return v.string;
}

const std::vector<Value>& array(const Value& v, const std::string& file, const std::string& what) {
  if (v.kind != Value::Kind::Array) throw InputError(file, what, "an array", kind_name(v.kind));
  return v.array;
}

}  // namespace layers::scene::json
