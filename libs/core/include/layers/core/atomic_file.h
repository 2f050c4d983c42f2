// layers/core/atomic_file.h -- write-then-rename, so that a file a user
// made is either the old one or the complete new one, never half-written.
#pragma once

#include <string>

namespace layers {

// A temporary name next to `target`; commit() renames it onto the target,
// and the destructor removes the temporary if commit() was never reached
// (e.g. an exception while writing).
class AtomicPath {
 public:
  explicit AtomicPath(std::string target);
  ~AtomicPath();
  AtomicPath(const AtomicPath&) = delete;
  AtomicPath& operator=(const AtomicPath&) = delete;

  const std::string& temp() const { return temp_; }
  const std::string& target() const { return target_; }
  void commit();
  // Moves the finished file into place only if the target does not exist
  // (else InputError naming the target with `exists_message`), so a file
  // someone made meanwhile is never replaced.
  void commit_new(const std::string& exists_message);

 private:
  std::string target_, temp_;
  bool committed_ = false;
};

// Writes `text` to `path` atomically; throws InputError on failure.
void write_text_atomic(const std::string& path, const std::string& text);
// The same for a file that must be new: InputError (`exists_message`) if
// `path` exists, checked when the complete file is moved into place.
void write_new_text_file(const std::string& path, const std::string& text, const std::string& exists_message);

}  // namespace layers
