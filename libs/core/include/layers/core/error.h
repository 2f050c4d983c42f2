// layers/core/error.h -- the toolkit's error types.
//
// Every failure a user can cause (bad file, bad config, bad plugin) is an
// InputError that names where the problem is (file, field or key path),
// what was expected and what was found. Programming errors are plain
// layers::Error. The CLI maps InputError/Error to exit code 1 and
// UsageError (bad command line) to 2.
#pragma once

#include <stdexcept>
#include <string>

namespace layers {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Bad user input: "<file>: <field>: expected <expected>, got <got>".
class InputError : public Error {
 public:
  InputError(std::string file, std::string field, std::string expected, std::string got);
  // A free-form message about a file/field when expected/got do not fit.
  static InputError message(std::string file, std::string field, std::string text);

  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& expected() const { return expected_; }
  const std::string& got() const { return got_; }

 private:
  struct Raw {};
  InputError(Raw, std::string file, std::string field, std::string text);
  std::string file_, field_, expected_, got_;
};

// Bad command-line usage (unknown verb, missing argument): exit code 2.
class UsageError : public Error {
 public:
  explicit UsageError(const std::string& message) : Error(message) {}
};

}  // namespace layers
