// tests/support/grid_tensor.h -- the grid faces of grid.h as the zoo holds
// them: an [F,3] tensor of the given integer dtype.
#pragma once

#include <ATen/ATen.h>

#include "grid.h"

namespace layers::test {

inline at::Tensor grid_faces_tensor(int rows, int cols, at::ScalarType dtype = at::kLong, bool closed = false) {
  return at::tensor(grid_faces<std::int64_t>(rows, cols, closed), at::kLong).reshape({-1, 3}).to(dtype);
}

}  // namespace layers::test
