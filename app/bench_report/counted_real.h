#pragma once
// A float that counts the arithmetic done on it, for counting the FLOPs of the shared shader code
// (shaders/bssrdf/*.glsl, shaders/maps/estimator.glsl): those files name their scalar type `real`
// (shaders/bssrdf/real.glsl), so compiling them with `real = CountedReal` runs the very lines the
// GPU runs, in float as the GPU does, and counts each operation as it executes, branches included.
//
// What counts as a FLOP: +, −, ×, ÷ of two operands (1 each), and each call of exp, log, sqrt,
// inversesqrt, sin, cos, sinh, cosh, asinh, pow (1 each, listed apart as `special`: the GPU's special-function units
// run them). Sign flips are free (folded into the next instruction), and comparisons, min, max,
// abs, clamp, floor, ceil (and fract's floor) are counted as `other`, not as FLOPs. GLM's vector functions (dot,
// cross, length, normalize) are counted through the scalar operations they are made of.
#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace tallow::flops {

/// Operations counted since the last reset(), per thread.
struct OpCounts {
  std::uint64_t add = 0, mul = 0, div = 0, special = 0, other = 0;
  std::uint64_t flops() const { return add + mul + div + special; }
};

inline OpCounts& counts() {
  thread_local OpCounts c;
  return c;
}
inline void reset() { counts() = OpCounts{}; }

class CountedReal {
 public:
  /// Trivial, like float's (GLM keeps the components in unions, which need it): uninitialised.
  CountedReal() = default;
  /// Implicit from any arithmetic type: the shared files write `const real X = 1.5;` and `real(n)`.
  template <class A, std::enable_if_t<std::is_arithmetic_v<A>, int> = 0>
  constexpr CountedReal(A a) : v_(static_cast<float>(a)) {}  // NOLINT(google-explicit-constructor)

  float value() const { return v_; }
  explicit operator float() const { return v_; }
  explicit operator double() const { return v_; }
  explicit operator int() const { return static_cast<int>(v_); }
  explicit operator std::uint32_t() const { return static_cast<std::uint32_t>(v_); }

  friend CountedReal operator+(CountedReal a, CountedReal b) { return ++counts().add, raw(a.v_ + b.v_); }
  friend CountedReal operator-(CountedReal a, CountedReal b) { return ++counts().add, raw(a.v_ - b.v_); }
  friend CountedReal operator*(CountedReal a, CountedReal b) { return ++counts().mul, raw(a.v_ * b.v_); }
  friend CountedReal operator/(CountedReal a, CountedReal b) { return ++counts().div, raw(a.v_ / b.v_); }
  friend CountedReal operator-(CountedReal a) { return raw(-a.v_); }
  friend CountedReal operator+(CountedReal a) { return a; }
  CountedReal& operator+=(CountedReal b) { return *this = *this + b; }
  CountedReal& operator-=(CountedReal b) { return *this = *this - b; }
  CountedReal& operator*=(CountedReal b) { return *this = *this * b; }
  CountedReal& operator/=(CountedReal b) { return *this = *this / b; }

  friend bool operator<(CountedReal a, CountedReal b) { return ++counts().other, a.v_ < b.v_; }
  friend bool operator>(CountedReal a, CountedReal b) { return ++counts().other, a.v_ > b.v_; }
  friend bool operator<=(CountedReal a, CountedReal b) { return ++counts().other, a.v_ <= b.v_; }
  friend bool operator>=(CountedReal a, CountedReal b) { return ++counts().other, a.v_ >= b.v_; }
  friend bool operator==(CountedReal a, CountedReal b) { return ++counts().other, a.v_ == b.v_; }
  friend bool operator!=(CountedReal a, CountedReal b) { return ++counts().other, a.v_ != b.v_; }

  // GLSL's built-ins on the scalar, found by argument-dependent lookup; as non-templates they win
  // over GLM's generic versions, inside GLM's own vector functions too.
  friend CountedReal exp(CountedReal a) { return ++counts().special, raw(std::exp(a.v_)); }
  friend CountedReal log(CountedReal a) { return ++counts().special, raw(std::log(a.v_)); }
  friend CountedReal sqrt(CountedReal a) { return ++counts().special, raw(std::sqrt(a.v_)); }
  friend CountedReal inversesqrt(CountedReal a) { return ++counts().special, raw(1.0f / std::sqrt(a.v_)); }
  friend CountedReal sin(CountedReal a) { return ++counts().special, raw(std::sin(a.v_)); }
  friend CountedReal cos(CountedReal a) { return ++counts().special, raw(std::cos(a.v_)); }
  friend CountedReal sinh(CountedReal a) { return ++counts().special, raw(std::sinh(a.v_)); }
  friend CountedReal cosh(CountedReal a) { return ++counts().special, raw(std::cosh(a.v_)); }
  friend CountedReal asinh(CountedReal a) { return ++counts().special, raw(std::asinh(a.v_)); }
  friend CountedReal pow(CountedReal a, CountedReal b) { return ++counts().special, raw(std::pow(a.v_, b.v_)); }
  friend CountedReal abs(CountedReal a) { return ++counts().other, raw(std::fabs(a.v_)); }
  friend CountedReal floor(CountedReal a) { return ++counts().other, raw(std::floor(a.v_)); }
  friend CountedReal ceil(CountedReal a) { return ++counts().other, raw(std::ceil(a.v_)); }
  /// GLSL's fract: x − floor(x) (one subtraction and a floor).
  friend CountedReal fract(CountedReal a) { return ++counts().add, ++counts().other, raw(a.v_ - std::floor(a.v_)); }
  friend CountedReal min(CountedReal a, CountedReal b) { return ++counts().other, raw(b.v_ < a.v_ ? b.v_ : a.v_); }
  friend CountedReal max(CountedReal a, CountedReal b) { return ++counts().other, raw(a.v_ < b.v_ ? b.v_ : a.v_); }
  friend CountedReal clamp(CountedReal x, CountedReal lo, CountedReal hi) { return min(max(x, lo), hi); }

 private:
  static CountedReal raw(float v) {
    CountedReal r;
    r.v_ = v;
    return r;
  }
  float v_;
};

}  // namespace tallow::flops

/// GLM's vector functions assert that their scalar is an IEEE floating-point type; CountedReal is
/// one (it computes in float).
template <>
class std::numeric_limits<tallow::flops::CountedReal> : public std::numeric_limits<float> {
 public:
  static constexpr tallow::flops::CountedReal min() noexcept { return std::numeric_limits<float>::min(); }
  static constexpr tallow::flops::CountedReal max() noexcept { return std::numeric_limits<float>::max(); }
  static constexpr tallow::flops::CountedReal lowest() noexcept { return std::numeric_limits<float>::lowest(); }
  static constexpr tallow::flops::CountedReal epsilon() noexcept { return std::numeric_limits<float>::epsilon(); }
  static constexpr tallow::flops::CountedReal infinity() noexcept { return std::numeric_limits<float>::infinity(); }
  static constexpr tallow::flops::CountedReal quiet_NaN() noexcept { return std::numeric_limits<float>::quiet_NaN(); }
};
