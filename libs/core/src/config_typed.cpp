// Scalar parsing, constraint checks and unknown-key detection for typed
// configs (see config.h).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "layers/core/config.h"
#include "layers/core/error.h"

namespace layers::cfg {
namespace detail {

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

void fail(const Node& at, const std::string& path, const std::string& expected, const std::string& got) {
  throw InputError(at.where(), path.empty() ? "<top level>" : path, expected, got);
}

namespace {
std::string quoted(const Node& n) {
  if (n.kind == Node::Kind::Scalar) return "'" + n.scalar + "'";
  return n.kind_name();
}
std::string describe_range(const Opt& o, const char* what) {
  std::string out = what;
  if (o.lo && o.hi)
    out += " in [" + format_double(*o.lo) + ", " + format_double(*o.hi) + "]";
  else if (o.lo)
    out += " >= " + format_double(*o.lo);
  else if (o.hi)
    out += " <= " + format_double(*o.hi);
  return out;
}
}  // namespace

std::string format_double(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

void check_kind(const Node& at, const std::string& path, Node::Kind kind, const char* expected) {
  if (at.kind != kind) fail(at, path, expected, quoted(at));
}

void check_range(const Node& at, const std::string& path, double value, const Opt& o, const char* what) {
  if ((o.lo && value < *o.lo) || (o.hi && value > *o.hi)) fail(at, path, describe_range(o, what), quoted(at));
}

void check_choice(const Node& at, const std::string& path, const std::string& value, const Opt& o) {
  if (o.allowed.empty()) return;
  if (std::find(o.allowed.begin(), o.allowed.end(), value) != o.allowed.end()) return;
  std::string list;
  for (const auto& a : o.allowed) list += (list.empty() ? "" : ", ") + a;
  fail(at, path, "one of " + list, quoted(at));
}

void parse_scalar(const Node& n, const std::string& path, bool& out) {
  check_kind(n, path, Node::Kind::Scalar, "true or false");
  const std::string& s = n.scalar;
  if (s == "true" || s == "True" || s == "yes" || s == "on") {
    out = true;
  } else if (s == "false" || s == "False" || s == "no" || s == "off") {
    out = false;
  } else {
    fail(n, path, "true or false", quoted(n));
  }
}

void parse_scalar(const Node& n, const std::string& path, std::int64_t& out) {
  check_kind(n, path, Node::Kind::Scalar, "an integer");
  const char* begin = n.scalar.c_str();
  char* end = nullptr;
  errno = 0;
  long long v = std::strtoll(begin, &end, 10);
  if (n.scalar.empty() || *end != '\0' || errno == ERANGE) fail(n, path, "an integer", quoted(n));
  out = v;
}

void parse_scalar(const Node& n, const std::string& path, std::uint64_t& out) {
  check_kind(n, path, Node::Kind::Scalar, "a non-negative integer");
  const char* begin = n.scalar.c_str();
  char* end = nullptr;
  errno = 0;
  unsigned long long v = std::strtoull(begin, &end, 10);
  if (n.scalar.empty() || n.scalar[0] == '-' || *end != '\0' || errno == ERANGE)
    fail(n, path, "a non-negative integer", quoted(n));
  out = v;
}

void parse_scalar(const Node& n, const std::string& path, double& out) {
  check_kind(n, path, Node::Kind::Scalar, "a number");
  const char* begin = n.scalar.c_str();
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(begin, &end);
  if (n.scalar.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    fail(n, path, "a (finite) number", quoted(n));
  out = v;
}

void parse_scalar(const Node& n, const std::string& path, std::string& out) {
  check_kind(n, path, Node::Kind::Scalar, "a string");
  out = n.scalar;
}

}  // namespace detail

Reader::Reader(const Node& node, std::string path) : node_(node), path_(std::move(path)) {}

void Reader::finish() const {
  for (const auto& [key, value] : node_.map) {
    if (std::find(seen_.begin(), seen_.end(), key) != seen_.end()) continue;
    std::string valid;
    for (const auto& s : seen_) valid += (valid.empty() ? "" : ", ") + s;
    throw InputError(value.where(), detail::join_path(path_, key),
                     "one of the keys " + (valid.empty() ? std::string("(none)") : valid), "unknown key '" + key + "'");
  }
}

}  // namespace layers::cfg
