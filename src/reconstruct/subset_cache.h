#pragma once
// Objects built over subsets of the samples, each built once and shared between threads. With
// barriers, the interpolant at a query is the one over the samples it sees, and neighbouring
// queries see the same: the RBF fits of multiquadric.h and local_multiquadric.h, the Delaunay
// triangulations of natural_neighbour.h.

#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <type_traits>
#include <utility>
#include <vector>

namespace radrecon {

/// Thread-safe. An object depends on its key and subset alone, so results do not depend on which
/// thread built it first. The objects kept hold at most `budget` subset members in all; past it,
/// an object is built for its caller and not kept (the caller may hold on to it).
template <typename T>
class SubsetCache {
 public:
  explicit SubsetCache(size_t budget = std::numeric_limits<size_t>::max()) : budget_(budget) {}

  /// The object kept over `subset` under `key`, or null.
  std::shared_ptr<const T> find(unsigned key, const std::vector<unsigned>& subset) const {
    std::shared_lock lock(mutex_);
    const auto it = objects_.find({key, subset});
    return it != objects_.end() ? it->second : nullptr;
  }

  /// The object over `subset` (sorted sample indices) under `key` (e.g. a patch), made by
  /// `build()` the first time (a T, or a std::shared_ptr to one).
  template <typename Build>
  std::shared_ptr<const T> get(unsigned key, const std::vector<unsigned>& subset, Build&& build) const {
    {
      std::shared_lock lock(mutex_);
      const auto it = objects_.find({key, subset});
      if (it != objects_.end()) return it->second;
    }
    std::shared_ptr<const T> object;
    if constexpr (std::is_convertible_v<decltype(build()), std::shared_ptr<const T>>) object = build();
    else object = std::make_shared<const T>(build());
    std::unique_lock lock(mutex_);
    if (kept_ + subset.size() > budget_) {
      const auto it = objects_.find({key, subset});
      return it != objects_.end() ? it->second : object;
    }
    const auto [it, inserted] = objects_.try_emplace({key, subset}, std::move(object));
    if (inserted) kept_ += subset.size();
    return it->second;
  }

 private:
  size_t budget_;
  mutable std::shared_mutex mutex_;
  mutable size_t kept_ = 0;  ///< subset members of the objects kept
  mutable std::map<std::pair<unsigned, std::vector<unsigned>>, std::shared_ptr<const T>> objects_;
};

}  // namespace radrecon
