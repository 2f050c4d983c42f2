// layers/train/compute_threads.h -- the thread count of a run's numeric
// work: torch's intra-op pool and, when the BLAS loaded is OpenBLAS, its
// own pool, which torch's setting does not reach.
#pragma once

namespace layers::train {

// Sets torch's intra-op threads and OpenBLAS's threads to `threads` (> 0).
// OpenBLAS's pthread build otherwise keeps one thread per core, and on a
// machine that other processes share its idle threads spin on
// sched_yield: a 1-thread training beside another job ran 20x slower.
void set_compute_threads(int threads);

// OpenBLAS's current thread count; -1 when the loaded BLAS is not OpenBLAS.
int blas_threads();

}  // namespace layers::train
