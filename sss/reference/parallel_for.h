#pragma once
// tbb::parallel_for for the reference integrator, with its fork and join made visible to
// ThreadSanitizer. TBB's scheduler lives in libtbb.so, which is not instrumented, so TSan cannot see
// that what the calling thread wrote before the loop happens before every body, and every body
// before the loop returns; it reported each read of such data (the image size, the scene) as a race.
// Under TSan the loop body is wrapped in TsanOrderedBody, which declares the edges TBB guarantees
// with __tsan_release/__tsan_acquire on the addresses of the copies TBB makes of it (in its task
// objects): constructing a copy happens before the task that holds it runs, destroying one before
// its memory is reused for the next copy, and every body before the loop returns. The wrapper reads
// nothing of its own copy before acquiring it (the address is `this`), which the earlier lambda
// wrapper did (its captures, read from TBB's task memory before its acquire). Bodies get no edge
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

#ifdef TALLOW_TSAN
template <class Range, class Body>
class TsanOrderedBody {
 public:
  TsanOrderedBody(const Body& body, char* join) {
    __tsan_acquire(this);  // after the previous object that lived at this address
    body_ = &body;
    join_ = join;
    __tsan_release(this);  // before the task that holds this copy runs
  }
  TsanOrderedBody(const TsanOrderedBody& other) {
    __tsan_acquire(const_cast<TsanOrderedBody*>(&other));
    __tsan_acquire(this);
    body_ = other.body_;
    join_ = other.join_;
    __tsan_release(this);
  }
  TsanOrderedBody& operator=(const TsanOrderedBody&) = delete;
  ~TsanOrderedBody() { __tsan_release(this); }  // before TBB reuses the memory

  void operator()(const Range& r) const {
    __tsan_acquire(const_cast<TsanOrderedBody*>(this));
    (*body_)(r);
    __tsan_release(join_);  // before the loop returns
  }

 private:
  const Body* body_;  // no initialisers: every write follows the acquire above
  char* join_;
};
#endif

template <class Range, class Body>
void parallelFor(const Range& range, const Body& body) {
#ifdef TALLOW_TSAN
  char join = 0;  // its address names the join edge
  tbb::parallel_for(range, TsanOrderedBody<Range, Body>(body, &join));
  __tsan_acquire(&join);
#else
  tbb::parallel_for(range, body);
#endif
}

}  // namespace tallow::sss
