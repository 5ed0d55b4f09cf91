#pragma once
// tbb::parallel_for for the reference integrator, with its fork and join made visible to
// ThreadSanitizer. TBB's scheduler lives in libtbb.so, which is not instrumented, so TSan cannot see
// that what the calling thread wrote before the loop happens before every body, and every body
// before the loop returns; it reported each read of such data (the image size, the scene) as a race.
// Under TSan the two edges TBB guarantees are declared with __tsan_release/__tsan_acquire: one from
// the caller to each body, one from each body to the caller after the join. Bodies get no edge
// between each other, so two bodies touching the same data are still reported.
#include <tbb/parallel_for.h>

#if defined(__SANITIZE_THREAD__)
#define TALLOW_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define TALLOW_TSAN 1
#endif
#endif
#ifdef TALLOW_TSAN
#include <sanitizer/tsan_interface.h>
#endif

namespace tallow::sss {

template <class Range, class Body>
void parallelFor(const Range& range, const Body& body) {
#ifdef TALLOW_TSAN
  char fork = 0, join = 0;  // their addresses name the two edges
  __tsan_release(&fork);
  tbb::parallel_for(range, [&](const Range& r) {
    __tsan_acquire(&fork);
    body(r);
    __tsan_release(&join);
  });
  __tsan_acquire(&join);
#else
  tbb::parallel_for(range, body);
#endif
}

}  // namespace tallow::sss
