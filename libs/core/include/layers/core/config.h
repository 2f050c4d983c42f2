// layers/core/config.h -- typed configuration structs.
//
// A config struct lists its fields once, in a visit() member:
//
//   struct Optim {
//     double lr = 1e-3;
//     int epochs = 10;
//     std::string kind = "adam";
//     template <class V> void visit(V& v) {
//       v("lr", lr, cfg::opt().range(0, 1).help("learning rate"));
//       v("epochs", epochs, cfg::opt().min(1));
//       v("kind", kind, cfg::opt().choices({"adam", "sgd"}));
//     }
//   };
//
// cfg::read<Optim>(node, "optim") fills it from a config tree, rejecting
// unknown keys, wrong types, missing required keys and out-of-range values
// with errors naming file, line, key path, expected and got;
// cfg::to_node(value) turns it back into a tree (the resolved config that
// every run prints and saves). Field types: bool, integers, float, double,
// std::string, std::vector<T>, std::map<std::string, T>, nested structs
// with visit(), enums (below), cfg::Node (kept raw, e.g. a plugin's own
// parameters) and std::optional<T> (an optional section: empty when the
// key is absent, and then left out of to_node(), so adding one does not
// change the resolved config of files without it).
//
// An enum field is written and read by name. Its names are listed once,
// next to the enum, by a function found through argument-dependent lookup:
//
//   enum class Kind { adam, sgd };
//   inline const cfg::EnumNames<Kind>& enum_names(Kind) {
//     static const cfg::EnumNames<Kind> names{{Kind::adam, "adam"}, {Kind::sgd, "sgd"}};
//     return names;
//   }
//
// A value outside the names is refused like a string outside choices().
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "layers/core/config_node.h"

namespace layers::cfg {

// Constraints of one field.
struct Opt {
  bool is_required = false;
  std::optional<double> lo, hi;
  std::vector<std::string> allowed;
  std::string text;

  Opt& required() {
    is_required = true;
    return *this;
  }
  Opt& range(double l, double h) {
    lo = l;
    hi = h;
    return *this;
  }
  Opt& min(double l) {
    lo = l;
    return *this;
  }
  Opt& max(double h) {
    hi = h;
    return *this;
  }
  Opt& choices(std::vector<std::string> c) {
    allowed = std::move(c);
    return *this;
  }
  Opt& help(std::string h) {
    text = std::move(h);
    return *this;
  }
};
inline Opt opt() { return {}; }

// The names of an enum's values, in the order they are listed in errors.
template <class E>
using EnumNames = std::vector<std::pair<E, const char*>>;

namespace detail {
template <class T, class = void>
struct has_visit : std::false_type {};
template <class T>
struct has_visit<T, std::void_t<decltype(std::declval<T&>().template visit<int>(std::declval<int&>()))>>
    : std::true_type {};
template <class T>
struct is_vector : std::false_type {};
template <class T>
struct is_vector<std::vector<T>> : std::true_type {};
template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};
template <class T>
struct is_map : std::false_type {};
template <class T>
struct is_map<std::map<std::string, T>> : std::true_type {};

std::string join_path(const std::string& parent, const std::string& key);
[[noreturn]] void fail(const Node& at, const std::string& path, const std::string& expected, const std::string& got);
void check_range(const Node& at, const std::string& path, double value, const Opt& o, const char* what);
void check_choice(const Node& at, const std::string& path, const std::string& value, const Opt& o);
void check_kind(const Node& at, const std::string& path, Node::Kind kind, const char* expected);

void parse_scalar(const Node& n, const std::string& path, bool& out);
void parse_scalar(const Node& n, const std::string& path, std::int64_t& out);
void parse_scalar(const Node& n, const std::string& path, std::uint64_t& out);
void parse_scalar(const Node& n, const std::string& path, double& out);
void parse_scalar(const Node& n, const std::string& path, std::string& out);

std::string format_double(double v);
}  // namespace detail

// Fills a struct from a mapping node, field by field (see file comment).
class Reader {
 public:
  Reader(const Node& node, std::string path);

  template <class T>
  void operator()(const char* key, T& out, const Opt& o = Opt()) {
    seen_.push_back(key);
    const Node* child = node_.find(key);
    std::string path = detail::join_path(path_, key);
    if (!child || child->kind == Node::Kind::Null) {
      if (o.is_required) detail::fail(node_, path, "a value (the key is required)", "nothing");
      return;
    }
    read_value(*child, path, out, o);
  }

  // Rejects keys that no field claimed, listing the valid ones.
  void finish() const;

  template <class T>
  static void read_value(const Node& n, const std::string& path, T& out, const Opt& o) {
    if constexpr (std::is_same_v<T, Node>) {
      out = n;
    } else if constexpr (detail::is_optional<T>::value) {
      typename T::value_type value{};
      read_value(n, path, value, o);
      out = std::move(value);
    } else if constexpr (std::is_enum_v<T>) {
      std::string name;
      detail::parse_scalar(n, path, name);
      Opt named = o;
      named.allowed.clear();
      for (const auto& [value, text] : enum_names(T{})) named.allowed.emplace_back(text);
      detail::check_choice(n, path, name, named);
      for (const auto& [value, text] : enum_names(T{}))
        if (name == text) out = value;
    } else if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::string>) {
      detail::parse_scalar(n, path, out);
      if constexpr (std::is_same_v<T, std::string>) detail::check_choice(n, path, out, o);
    } else if constexpr (std::is_integral_v<T>) {
      if constexpr (std::is_signed_v<T>) {
        std::int64_t v = 0;
        detail::parse_scalar(n, path, v);
        detail::check_range(n, path, static_cast<double>(v), o, "an integer");
        out = static_cast<T>(v);
      } else {
        std::uint64_t v = 0;
        detail::parse_scalar(n, path, v);
        detail::check_range(n, path, static_cast<double>(v), o, "a non-negative integer");
        out = static_cast<T>(v);
      }
    } else if constexpr (std::is_floating_point_v<T>) {
      double v = 0;
      detail::parse_scalar(n, path, v);
      detail::check_range(n, path, v, o, "a number");
      out = static_cast<T>(v);
    } else if constexpr (detail::is_vector<T>::value) {
      detail::check_kind(n, path, Node::Kind::Seq, "a list");
      T result;
      for (std::size_t i = 0; i < n.seq.size(); ++i) {
        typename T::value_type item{};
        read_value(n.seq[i], path + "[" + std::to_string(i) + "]", item, o);
        result.push_back(std::move(item));
      }
      out = std::move(result);
    } else if constexpr (detail::is_map<T>::value) {
      detail::check_kind(n, path, Node::Kind::Map, "a mapping");
      T result;
      for (const auto& [k, v] : n.map) {
        typename T::mapped_type item{};
        read_value(v, detail::join_path(path, k), item, o);
        result.emplace(k, std::move(item));
      }
      out = std::move(result);
    } else {
      static_assert(detail::has_visit<T>::value, "config field type needs a visit() member");
      detail::check_kind(n, path, Node::Kind::Map, "a mapping");
      Reader sub(n, path);
      out.visit(sub);
      sub.finish();
    }
  }

 private:
  const Node& node_;
  std::string path_;
  std::vector<std::string> seen_;
};

// Turns a struct back into a tree (defaults included).
class Writer {
 public:
  explicit Writer(Node& node) : node_(node) { node_.kind = Node::Kind::Map; }

  template <class T>
  void operator()(const char* key, const T& value, const Opt& = Opt()) {
    if constexpr (detail::is_optional<T>::value) {
      if (!value) return;  // an absent optional section stays absent
      node_.map.emplace_back(key, write_value(*value));
    } else {
      node_.map.emplace_back(key, write_value(value));
    }
  }

  template <class T>
  static Node write_value(const T& value) {
    Node n;
    if constexpr (std::is_same_v<T, Node>) {
      n = value;
    } else if constexpr (detail::is_optional<T>::value) {
      if (value) n = write_value(*value);
    } else if constexpr (std::is_same_v<T, bool>) {
      n.kind = Node::Kind::Scalar;
      n.scalar = value ? "true" : "false";
    } else if constexpr (std::is_same_v<T, std::string>) {
      n.kind = Node::Kind::Scalar;
      n.scalar = value;
    } else if constexpr (std::is_enum_v<T>) {
      n.kind = Node::Kind::Scalar;
      for (const auto& [v, text] : enum_names(T{}))
        if (v == value) n.scalar = text;
    } else if constexpr (std::is_integral_v<T>) {
      n.kind = Node::Kind::Scalar;
      n.scalar = std::to_string(value);
    } else if constexpr (std::is_floating_point_v<T>) {
      n.kind = Node::Kind::Scalar;
      n.scalar = detail::format_double(static_cast<double>(value));
    } else if constexpr (detail::is_vector<T>::value) {
      n.kind = Node::Kind::Seq;
      for (const auto& item : value) n.seq.push_back(write_value(item));
    } else if constexpr (detail::is_map<T>::value) {
      n.kind = Node::Kind::Map;
      for (const auto& [k, v] : value) n.map.emplace_back(k, write_value(v));
    } else {
      Writer sub(n);
      const_cast<T&>(value).visit(sub);
    }
    return n;
  }

 private:
  Node& node_;
};

// Reads a typed struct from `node` (a mapping); `path` prefixes key paths
// in error messages (e.g. "model").
template <class T>
T read(const Node& node, const std::string& path = "") {
  T out{};
  Reader::read_value(node, path, out, Opt());
  return out;
}

template <class T>
Node to_node(const T& value) {
  return Writer::write_value(value);
}

}  // namespace layers::cfg
