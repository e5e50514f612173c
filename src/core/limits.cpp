#include "core/limits.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <system_error>

#include "core/check.h"
#include "core/error.h"

namespace radrecon {

namespace {

constexpr std::array<LimitSpec, std::size(kAllLimits)> kSpecs = {{
    // The memory and time per unit: docs/scaling.md.
    {"--max-samples", "samples", 10'000'000, "about 270 bytes a sample with its triangulation: some 2.7 GB"},
    {"--max-raster-points", "points", 100'000'000, "about 26 bytes a point and its value (a point counts once for each value column): some 2.6 GB"},
    {"--max-rays", "rays", 1LL << 32, "8192 x 8192 pixels at 8 x 8 rays: some 25 minutes on two cores"},
    {"--max-elements", "elements", 10'000'000, "about 900 bytes an element (a solve's peak memory: 870-880 on the paper scene, grid:200 to grid:800): some 9 GB, and the progressive solver's kept views of its patches, 128 MiB at most"},
    {"--max-leaves", "leaves", 10'000'000, "the links (--max-links) grow faster than the leaves"},
    {"--max-links", "links", 4'000'000, "about 2.6 KiB a link with its quadtrees: some 10 GB"},
    {"--max-file-bytes", "bytes", 1LL << 30, "1 GiB: every reader holds its file in memory, several times over"},
}};

/// The limits set by set_limit(); 0 where the default holds.
std::array<std::atomic<long long>, std::size(kAllLimits)> g_set{};

size_t index_of(Limit which) { return static_cast<size_t>(which); }

}  // namespace

const LimitSpec& limit_spec(Limit which) { return kSpecs[index_of(which)]; }

long long limit_value(Limit which) {
  const long long set = g_set[index_of(which)].load(std::memory_order_relaxed);
  return set > 0 ? set : kSpecs[index_of(which)].default_value;
}

void set_limit(Limit which, long long value) {
  RR_CHECK(value >= 1, "a limit is at least 1");
  g_set[index_of(which)].store(value, std::memory_order_relaxed);
}

void check_limit(Limit which, long long amount, const std::string& where, const std::string& what,
                 const std::string& advice) {
  const long long limit = limit_value(which);
  if (amount <= limit) return;
  const LimitSpec& spec = limit_spec(which);
  throw UserError(where, what + " " + std::to_string(amount) + " " + spec.unit + ", beyond the limit of " +
                             std::to_string(limit) + "; " + (advice.empty() ? "" : advice + ", or ") + spec.option +
                             " raises it (nothing was written)");
}

void check_input_file_size(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec) return;
  check_limit(Limit::file_bytes, static_cast<long long>(std::min<std::uintmax_t>(bytes, 1ULL << 62)), path,
              "the file holds");
}

}  // namespace radrecon
