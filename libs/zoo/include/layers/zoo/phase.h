// layers/zoo/phase.h -- a named phase of a model step, for profiles
// (`layers bench --profile`): the operators run while a Phase lives are
// counted under its name (the innermost one when phases nest). Costs
// nothing when no profiler runs.
#pragma once

#include <ATen/record_function.h>

namespace layers::zoo {

class Phase {
 public:
  // `name`: "phase:<what>", a string literal.
  explicit Phase(const char* name) : guard_(at::RecordScope::USER_SCOPE) {
    if (guard_.isActive()) guard_.before(name);
  }
  Phase(const Phase&) = delete;
  Phase& operator=(const Phase&) = delete;

 private:
  at::RecordFunction guard_;
};

}  // namespace layers::zoo
