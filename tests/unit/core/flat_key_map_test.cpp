// FlatKeyMap against std::unordered_map on the same operations: grid-like keys (small strides,
// which a poor hash would pile into one run of slots) and random keys, through many rehashes.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <unordered_map>

#include "surfacing/flat_key_map.h"

namespace sketchsurf {
namespace {

TEST(FlatKeyMap, FindsWhatWasInsertedAndNothingElse) {
  FlatKeyMap<int> map;
  std::unordered_map<std::uint64_t, int> reference;
  std::mt19937_64 rng(7);
  // Grid keys i + 101 (j + 101 k) of a band, then random 64-bit keys.
  for (std::uint64_t k = 0; k < 40; ++k)
    for (std::uint64_t j = 0; j < 40; ++j)
      for (std::uint64_t i = 10; i < 14; ++i) {
        const std::uint64_t key = i + 101 * (j + 101 * k);
        const int value = static_cast<int>(reference.size());
        const auto [v, inserted] = map.try_emplace(key, value);
        ASSERT_TRUE(inserted);
        ASSERT_EQ(*v, value);
        reference.emplace(key, value);
      }
  for (int n = 0; n < 20000; ++n) {
    const std::uint64_t key = rng() >> 1;
    const int value = n;
    const bool fresh = reference.emplace(key, value).second;
    EXPECT_EQ(map.try_emplace(key, value).second, fresh);
  }
  EXPECT_EQ(map.size(), reference.size());
  for (const auto& [key, value] : reference) {
    const int* found = map.find(key);
    ASSERT_NE(found, nullptr) << key;
    EXPECT_EQ(*found, value);
  }
  for (std::uint64_t key = 0; key < 10; ++key) EXPECT_FALSE(map.contains(key));  // i < 10: none
}

TEST(FlatKeyMap, AnInsertedKeyKeepsItsFirstValueAndSetReplacesIt) {
  FlatKeyMap<double> map(3);
  EXPECT_TRUE(map.try_emplace(42, 1.5).second);
  const auto [v, inserted] = map.try_emplace(42, 2.5);
  EXPECT_FALSE(inserted);
  EXPECT_EQ(*v, 1.5);
  map.set(42, 3.5);
  map.set(43, 4.5);
  EXPECT_EQ(*map.find(42), 3.5);
  EXPECT_EQ(*map.find(43), 4.5);
  EXPECT_EQ(map.size(), 2u);
  EXPECT_EQ(map.find(44), nullptr);
}

}  // namespace
}  // namespace sketchsurf
