// set_compute_threads (see compute_threads.h). OpenBLAS is found at run
// time (dlsym), so that a build against another BLAS works unchanged.
#include "layers/train/compute_threads.h"

#include <ATen/Parallel.h>
#include <dlfcn.h>

#include <algorithm>
#include <thread>

namespace layers::train {
namespace {

template <class F>
F blas_symbol(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_DEFAULT, name));
}

}  // namespace

void set_compute_threads(int threads) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  auto set_blas = blas_symbol<void (*)(int)>("openblas_set_num_threads");
  if (!set_blas) {
    at::set_num_threads(threads);
    return;
  }
  // The matrix products (OpenBLAS) get the threads, torch's own operators
  // one: with both pools at two threads on two cores a model step ran 3-5x
  // slower than on one thread (docs/benchmarks.md, "Threads").
  set_blas(threads);
  at::set_num_threads(1);
}

int blas_threads() {
  auto get = blas_symbol<int (*)()>("openblas_get_num_threads");
  return get != nullptr ? get() : -1;
}

}  // namespace layers::train
