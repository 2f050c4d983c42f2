// layers/train/compute_threads.h -- the thread count of a run's numeric
// work: torch's intra-op pool and, when the BLAS loaded is OpenBLAS, its
// own pool, which torch's setting does not reach.
#pragma once

namespace layers::train {

// Gives a run `threads` threads (0: one per core). With OpenBLAS loaded,
// its matrix products get them and torch's intra-op pool one thread: the
// two pools at more than one thread each oversubscribe the cores (OpenBLAS
// threads spin while torch's wait), measured 3-5x slower than one thread
// on two cores, while OpenBLAS alone at two threads is as fast or faster
// (docs/benchmarks.md, "Threads"). OpenBLAS's pthread build otherwise
// keeps one thread per core, and on a machine other processes share its
// idle threads spin on sched_yield: a 1-thread training beside another job
// ran 20x slower. Without OpenBLAS, torch's pool gets the threads.
void set_compute_threads(int threads);

// OpenBLAS's current thread count; -1 when the loaded BLAS is not OpenBLAS.
int blas_threads();

}  // namespace layers::train
