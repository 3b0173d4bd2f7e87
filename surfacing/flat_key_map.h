#pragma once
// A hash map from 64-bit keys to small values with open addressing: one flat array, no node per
// entry. Grid-keyed lookups (a polygonisation's field values and edge vertices, the proxy's memo
// of field values) run millions of times a proxy; a node-based std::unordered_map spends most of
// that time on allocation and pointer chasing.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace sketchsurf {

/// Keys are any uint64 but kEmpty (all bits set). Iteration order is not offered: callers that
/// need an order keep their own.
template <class Value>
class FlatKeyMap {
 public:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  explicit FlatKeyMap(std::size_t expected = 0) { rehash(capacity_for(expected)); }

  std::size_t size() const { return size_; }

  /// The value of `key`, or nullptr when it has none.
  const Value* find(std::uint64_t key) const {
    for (std::size_t i = slot(key);; i = (i + 1) & mask_) {
      if (keys_[i] == key) return &values_[i];
      if (keys_[i] == kEmpty) return nullptr;
    }
  }
  bool contains(std::uint64_t key) const { return find(key) != nullptr; }

  /// The value of `key`, inserted as `value` when absent; second: whether it was inserted.
  std::pair<Value*, bool> try_emplace(std::uint64_t key, const Value& value) {
    if (2 * (size_ + 1) > keys_.size()) rehash(2 * keys_.size());
    std::size_t i = slot(key);
    for (; keys_[i] != kEmpty; i = (i + 1) & mask_)
      if (keys_[i] == key) return {&values_[i], false};
    keys_[i] = key;
    values_[i] = value;
    ++size_;
    return {&values_[i], true};
  }

  /// Sets the value of `key`, inserting it when absent.
  void set(std::uint64_t key, const Value& value) {
    auto [v, inserted] = try_emplace(key, value);
    if (!inserted) *v = value;
  }

 private:
  static std::size_t capacity_for(std::size_t expected) {
    std::size_t c = 16;
    while (c < 2 * expected) c *= 2;
    return c;
  }

  // Fibonacci hashing: the top bits of key * 2^64 / phi, which spreads grid keys that differ by
  // small strides.
  std::size_t slot(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }

  void rehash(std::size_t capacity) {
    std::vector<std::uint64_t> keys(capacity, kEmpty);
    std::vector<Value> values(capacity);
    keys.swap(keys_);
    values.swap(values_);
    mask_ = capacity - 1;
    shift_ = 64;
    for (std::size_t c = capacity; c > 1; c >>= 1) --shift_;
    size_ = 0;
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) try_emplace(keys[i], values[i]);
  }

  std::vector<std::uint64_t> keys_;
  std::vector<Value> values_;
  std::size_t mask_ = 0;
  int shift_ = 64;
  std::size_t size_ = 0;
};

}  // namespace sketchsurf
