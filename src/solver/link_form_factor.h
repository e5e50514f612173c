#pragma once
// The form factor of a link of hierarchical radiosity (solver/hierarchical.h) from the geometry of
// its two ends, and a cache of them shared by solves of the same scene.

#include <bit>
#include <cstdint>
#include <functional>
#include <unordered_map>

#include "core/progress.h"
#include "mesh/quadtree.h"
#include "solver/bvh.h"

namespace radrecon {

/// One end of a link: a quadtree node (which need not be stored in a tree yet) of one side of a
/// scene surface.
struct LinkEnd {
  const Surface* surface = nullptr;
  size_t scene_surface = 0;  ///< the surface's index in the scene
  Vec3 normal;               ///< unit normal of the side
  QuadNode node;
};

struct LinkFormFactor {
  double f = 0;         ///< area-to-area visible form factor F(receiver -> source), dimensionless
  double f_spread = 0;  ///< max - min of the point form factors over the receiver's samples
};

/// Midpoint samples per receiver edge for a link's area-to-area form factor, and the finer rule
/// used where the point form factor jumps across the receiver (its spread exceeds this
/// fraction of its maximum): kLinkQuadratureFine per edge of each of the coarse rule's cells
/// next to a jump, a neighbouring cell whose value differs by more than kJumpShare of the
/// spread; the other cells keep their midpoint.
inline constexpr int kLinkQuadrature = 4;
inline constexpr int kLinkQuadratureFine = 4;
inline constexpr double kDiscontinuousSpread = 0.5;
inline constexpr double kJumpShare = 0.1;

/// F(receiver -> source): the mean over kLinkQuadrature^2 midpoint samples of the receiver (the
/// finer rule next to where the point value jumps: a shadow boundary, the foot of a wall standing
/// on the receiver) of the exact visible point-to-polygon form factor (visibility.h), with the occluders
/// found by `bvh` in the shaft between the two nodes when `may_be_occluded` (the surfaces' own
/// shaft holds some). Deterministic, and safe to call from several threads.
LinkFormFactor measure_link(const LinkEnd& receiver, const LinkEnd& source, const OccluderBvh& bvh,
                            bool may_be_occluded);

/// The form factors of links already computed, by the geometry of their two ends (surface side
/// and parameter cell): a link's form factor depends on nothing else, so solves of the same scene
/// at different thresholds (quadtree:LEAVES's search over epsilon) share the links their
/// hierarchies have in common. Not thread-safe: a solve reads and fills it from its own thread.
class LinkFormFactorCache {
 public:
  /// One end of a link: a node of the quadtree of surface side `tree` (the solver's numbering,
  /// the same for the same scene), known by its parameter cell.
  struct End {
    int tree;
    ParamCell cell;
  };
  using Value = LinkFormFactor;
  const Value* find(const End& receiver, const End& source) const {
    const auto it = map_.find(Key{receiver, source});
    return it == map_.end() ? nullptr : &it->second;
  }
  /// Adds the value unless the key is known; returns the value the cache holds for it (stable:
  /// the cache never moves a value).
  const Value* insert(const End& receiver, const End& source, const Value& v) {
    return &map_.emplace(Key{receiver, source}, v).first->second;
  }
  size_t size() const { return map_.size(); }

 private:
  struct Key {
    End r, s;
    bool operator==(const Key& o) const {
      const auto same = [](const End& a, const End& b) {
        return a.tree == b.tree && a.cell.u0 == b.cell.u0 && a.cell.v0 == b.cell.v0 && a.cell.u1 == b.cell.u1 &&
               a.cell.v1 == b.cell.v1 && a.cell.shape == b.cell.shape;
      };
      return same(r, o.r) && same(s, o.s);
    }
  };
  struct Hash {
    /// The bits of every field, multiplied and folded in turn (a coordinate's + 0.0 makes -0.0
    /// hash as 0.0, which it equals).
    size_t operator()(const Key& k) const {
      std::uint64_t h = 0x9e3779b97f4a7c15ULL;
      const auto mix = [&h](std::uint64_t v) {
        h = (h ^ v) * 0xff51afd7ed558ccdULL;
        h ^= h >> 32;
      };
      for (const End* e : {&k.r, &k.s}) {
        mix(static_cast<std::uint64_t>(e->tree) << 8 | static_cast<std::uint64_t>(e->cell.shape));
        for (const double x : {e->cell.u0, e->cell.v0, e->cell.u1, e->cell.v1}) mix(std::bit_cast<std::uint64_t>(x + 0.0));
      }
      return static_cast<size_t>(h);
    }
  };
  std::unordered_map<Key, Value, Hash> map_;
};

/// A link to measure: its ends' trees and nodes (a tree's, or a node not stored yet).
struct LinkRequest {
  int receiver_tree;
  const QuadNode* receiver;  ///< the caller's, alive until measure_into_cache() returns
  int source_tree;
  const QuadNode* source;
};

/// Link form factors measured between two progress reports (measure_into_cache()): some 0.2 s
/// of a hierarchical solve's final gather at 3.6 million links.
inline constexpr std::int64_t kMeasureBatch = 1 << 16;

/// Measures by `measure` (called in parallel) the requests not in `cache`, in batches of
/// kMeasureBatch after each of which `progress` (may be null) hears the share done, and adds them
/// to the cache in their order (so that the cache, and every solve that reads it, does not depend
/// on the threads). Returns each request's form factor, as the cache holds it.
std::vector<const LinkFormFactor*> measure_into_cache(LinkFormFactorCache& cache, const std::vector<LinkRequest>& requests,
                                                      Progress* progress,
                                                      const std::function<LinkFormFactor(const LinkRequest&)>& measure);

}  // namespace radrecon
