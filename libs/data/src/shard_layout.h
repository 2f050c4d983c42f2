// shard_layout.h (private) -- the structure of a shard: root attributes,
// the list of sequences and, per sequence, its attributes and the
// presence, dtype and shape of every array (no array data is read).
//
// Shared by the reader's index (which throws on the first problem) and the
// validator (which collects them all and then checks values of the arrays
// found well-formed). Problems go to a ProblemSink.
#pragma once

#include <H5Cpp.h>

#include <set>
#include <string>
#include <vector>

#include "layers/data/sequence.h"
#include "layers/data/validate.h"

namespace layers::data {

class ProblemSink {
 public:
  virtual ~ProblemSink() = default;
  virtual void report(Problem problem) = 0;
};

// Throws InputError(file, object, message) on the first problem.
class ThrowOnProblem : public ProblemSink {
 public:
  void report(Problem problem) override;
};

class CollectProblems : public ProblemSink {
 public:
  explicit CollectProblems(std::vector<Problem>& out) : out_(out) {}
  void report(Problem problem) override { out_.push_back(std::move(problem)); }

 private:
  std::vector<Problem>& out_;
};

// Root attributes format, format_version, fps, units, up.
void check_root(const std::string& file, const H5::H5File& h5, ProblemSink& sink);

// Names of the groups under /seq (a problem if /seq is missing).
std::vector<std::string> sequence_ids(const std::string& file, const H5::H5File& h5, ProblemSink& sink);

struct SequenceLayout {
  SequenceInfo info;
  // Arrays (paths relative to the sequence group, e.g. "body/positions",
  // "garments/0/rest") present with the right dtype and shape.
  std::set<std::string> well_formed;
};

SequenceLayout inspect_sequence(const std::string& file, const H5::Group& seq, const std::string& id,
                                ProblemSink& sink);

}  // namespace layers::data
