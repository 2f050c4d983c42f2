// layers/core/parallel.h -- runs a function on every index of a range over
// a few threads (the caller's one among them), for work whose items are
// independent and whose results the caller puts in order afterwards.
#pragma once

#include <cstddef>
#include <functional>

namespace layers {

// Calls f(i) for every i in [0, n), on up to `threads` threads (at least
// the calling one). Each index runs once; which thread runs it is not
// fixed, so f must write its result to a place of its own (e.g. slot i).
// If f throws, no new index starts, and once every thread has stopped the
// exception of the lowest failing index is rethrown (the one a single
// thread would have met).
void parallel_indices(std::size_t n, int threads, const std::function<void(std::size_t)>& f);

}  // namespace layers
