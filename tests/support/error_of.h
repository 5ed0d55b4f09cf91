#pragma once
// The message of the exception of type E that `f` throws, or "" when it throws none: for tests that
// assert the exact one-line error a user would see.
#include <string>
#include <utility>

namespace tallow::test {

template <class E, class F>
std::string errorOf(F&& f) {
  try {
    std::forward<F>(f)();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

}  // namespace tallow::test
