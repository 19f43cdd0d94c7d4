#pragma once
/// BlockValues: one number per block of a stack, bottom first (angles, rates). A vector of
/// doubles the size of a std::vector that holds up to kInline values in place, so that the
/// samples and events of one- and two-block stacks (the thesis's) allocate nothing; more values
/// go to the heap.
#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <vector>

namespace rockbench {

class BlockValues {
 public:
  /// Values kept in place.
  static constexpr size_t kInline = 2;

  BlockValues() = default;
  /// `n` values equal to `value`.
  explicit BlockValues(size_t n, double value = 0.0) { assign(n, value); }
  BlockValues(std::initializer_list<double> values) { CopyFrom(values.begin(), values.size()); }
  BlockValues(const std::vector<double>& values) { CopyFrom(values.data(), values.size()); }
  BlockValues(const BlockValues& other) { CopyFrom(other.data(), other.size_); }
  BlockValues(BlockValues&& other) noexcept { Steal(other); }
  BlockValues& operator=(const BlockValues& other) {
    if (this != &other) CopyFrom(other.data(), other.size_);
    return *this;
  }
  BlockValues& operator=(BlockValues&& other) noexcept {
    if (this != &other) {
      Release();
      Steal(other);
    }
    return *this;
  }
  BlockValues& operator=(std::initializer_list<double> values) {
    CopyFrom(values.begin(), values.size());
    return *this;
  }
  ~BlockValues() { Release(); }

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  double* data() { return size_ > kInline ? heap_ : inline_; }
  const double* data() const { return size_ > kInline ? heap_ : inline_; }
  double& operator[](size_t i) { return data()[i]; }
  double operator[](size_t i) const { return data()[i]; }
  double* begin() { return data(); }
  double* end() { return data() + size_; }
  const double* begin() const { return data(); }
  const double* end() const { return data() + size_; }

  /// Makes it `n` values equal to `value`.
  void assign(size_t n, double value) {
    Reserve(n);
    std::fill_n(data(), n, value);
  }
  /// Keeps the first min(n, size()) values; new ones are `value`.
  void resize(size_t n, double value = 0.0) {
    BlockValues out(n, value);
    std::copy_n(data(), std::min(n, size_), out.data());
    *this = std::move(out);
  }
  std::vector<double> vector() const { return {begin(), end()}; }

  friend bool operator==(const BlockValues& a, const BlockValues& b) {
    return a.size_ == b.size_ && std::equal(a.begin(), a.end(), b.begin());
  }
  friend bool operator!=(const BlockValues& a, const BlockValues& b) { return !(a == b); }

 private:
  // Sets size() to n with storage for it (the values unspecified).
  void Reserve(size_t n) {
    if (n > kInline && (size_ <= kInline || n > size_)) {
      Release();
      heap_ = new double[n];
    } else if (n <= kInline) {
      Release();
    }
    size_ = n;
  }
  void CopyFrom(const double* values, size_t n) {
    if (values == data() && n == size_) return;
    if (n > kInline && size_ > kInline && n <= size_) {
      // reuse the heap block (values may not alias it: they are another object's)
      std::copy_n(values, n, heap_);
      size_ = n;
      return;
    }
    BlockValues out;
    out.Reserve(n);
    std::copy_n(values, n, out.data());
    *this = std::move(out);
  }
  void Steal(BlockValues& other) {
    size_ = other.size_;
    if (size_ > kInline) {
      heap_ = other.heap_;
    } else {
      std::copy_n(other.inline_, kInline, inline_);
    }
    other.size_ = 0;
  }
  void Release() {
    if (size_ > kInline) delete[] heap_;
    size_ = 0;
  }

  size_t size_ = 0;
  union {
    double inline_[kInline] = {0.0, 0.0};
    double* heap_;
  };
};

}  // namespace rockbench
