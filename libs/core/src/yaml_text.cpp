// Bounded YAML parsing (see yaml_text.h).
#include "layers/core/yaml_text.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cstring>
#include <sstream>

#include "layers/core/error.h"

namespace layers {
namespace {

// Counts the parser's events; throws at the first value over a bound.
class Counter : public YAML::EventHandler {
 public:
  explicit Counter(const std::string& name) : name_(name) {}
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { value(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { value(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
    value(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    open(mark);
  }
  void OnSequenceEnd() override { --depth_; }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    open(mark);
  }
  void OnMapEnd() override { --depth_; }

 private:
  std::string where(const YAML::Mark& mark) const {
    return mark.line >= 0 ? name_ + ":" + std::to_string(mark.line + 1) : name_;
  }
  void value(const YAML::Mark& mark) {
    if (++values_ > kMaxYamlValues)
      throw InputError(where(mark), "", "YAML of at most " + std::to_string(kMaxYamlValues) + " values",
                       "more (counted up to this line)");
  }
  void open(const YAML::Mark& mark) {
    value(mark);
    if (++depth_ > kMaxYamlDepth)
      throw InputError(where(mark), "", "values nested at most " + std::to_string(kMaxYamlDepth) + " levels deep",
                       "deeper nesting");
  }
  const std::string& name_;
  std::int64_t values_ = 0;
  int depth_ = 0;
};

[[noreturn]] void malformed(const std::string& name, const YAML::Exception& e) {
  const std::string where = e.mark.line >= 0 ? name + ":" + std::to_string(e.mark.line + 1) : name;
  const std::string column = e.mark.column >= 0 ? " (column " + std::to_string(e.mark.column + 1) + ")" : "";
  throw InputError::message(where, "", "malformed YAML" + column + ": " + e.msg);
}

}  // namespace

YAML::Node parse_yaml(const std::string& text, const std::string& name) {
  if (const void* nul = std::memchr(text.data(), '\0', text.size())) {
    const auto at = static_cast<std::size_t>(static_cast<const char*>(nul) - text.data());
    std::size_t line = 1;
    for (std::size_t k = 0; k < at; ++k) line += text[k] == '\n';
    throw InputError(name + ":" + std::to_string(line), "", "YAML text",
                     "a NUL byte (a binary file?) at byte " + std::to_string(at));
  }
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    Counter counter(name);
    while (parser.HandleNextDocument(counter)) {
    }
    return YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw InputError(e.mark.line >= 0 ? name + ":" + std::to_string(e.mark.line + 1) : name, "",
                     "YAML nested less deeply", "nesting beyond the parser's limit");
  } catch (const YAML::Exception& e) {
    malformed(name, e);
  }
}

}  // namespace layers
