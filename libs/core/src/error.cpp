// Formatting of the toolkit's error messages (see error.h).
#include "layers/core/error.h"

namespace layers {
namespace {
std::string prefix(const std::string& file, const std::string& field) {
  std::string out = file.empty() ? std::string("<input>") : file;
  if (!field.empty()) out += ": " + field;
  return out;
}
}  // namespace

InputError::InputError(std::string file, std::string field, std::string expected, std::string got)
    : Error(prefix(file, field) + ": expected " + expected + ", got " + got),
      file_(std::move(file)),
      field_(std::move(field)),
      expected_(std::move(expected)),
      got_(std::move(got)) {}

InputError::InputError(Raw, std::string file, std::string field, std::string text)
    : Error(prefix(file, field) + ": " + text), file_(std::move(file)), field_(std::move(field)) {}

InputError InputError::message(std::string file, std::string field, std::string text) {
  return InputError(Raw{}, std::move(file), std::move(field), std::move(text));
}

}  // namespace layers
