// set_compute_threads (see compute_threads.h). OpenBLAS is found at run
// time (dlsym), so that a build against another BLAS works unchanged.
#include "layers/train/compute_threads.h"

#include <ATen/Parallel.h>
#include <dlfcn.h>

namespace layers::train {
namespace {

template <class F>
F blas_symbol(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_DEFAULT, name));
}

}  // namespace

void set_compute_threads(int threads) {
  if (threads <= 0) return;
  at::set_num_threads(threads);
  if (auto set = blas_symbol<void (*)(int)>("openblas_set_num_threads")) set(threads);
}

int blas_threads() {
  auto get = blas_symbol<int (*)()>("openblas_get_num_threads");
  return get != nullptr ? get() : -1;
}

}  // namespace layers::train
