// The --max-* options that raise (or lower) the resource limits of core/limits.h, and the checks
// that several commands' options share.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "cli/commands.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"
#include "solver/solve.h"

namespace radrecon::cli {

namespace {

/// The first number after `key` in the text file at `path` ("MemAvailable:" of /proc/meminfo, in
/// kB there), or nullopt.
std::optional<double> number_after(const char* path, const std::string& key) {
  std::ifstream in(path);
  for (std::string word; in >> word;)
    if (word == key) {
      double v = 0;
      if (in >> v) return v;
      return std::nullopt;
    }
  return std::nullopt;
}

/// The number in the text file at `path` ("max", or none: nullopt).
std::optional<double> number_in(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  return in >> text ? parse_finite(text) : std::nullopt;
}

/// The bytes a cgroup memory limit leaves this process's group (a container's): cgroup v2's
/// memory.max less memory.current, or v1's memory.limit_in_bytes less memory.usage_in_bytes;
/// nullopt where no limit is found ("max"; v1's "no limit" is a huge number, which min() passes).
std::optional<double> cgroup_memory_left() {
  std::ifstream groups("/proc/self/cgroup");  // "0::/PATH" (v2), "N:memory:/PATH" (v1)
  for (std::string line; std::getline(groups, line);) {
    if (line.rfind("0::", 0) == 0) {
      const std::string dir = "/sys/fs/cgroup" + line.substr(3);
      const std::optional<double> max = number_in(dir + "/memory.max"), current = number_in(dir + "/memory.current");
      if (max && current) return *max - *current;
    } else if (const size_t at = line.find(":memory:"); at != std::string::npos) {
      const std::string dir = "/sys/fs/cgroup/memory" + line.substr(at + 8);
      const std::optional<double> max = number_in(dir + "/memory.limit_in_bytes"), used = number_in(dir + "/memory.usage_in_bytes");
      if (max && used) return *max - *used;
    }
  }
  return std::nullopt;
}

}  // namespace

/// Bytes this process may still allocate: the memory the kernel counts as available (free and
/// reclaimable: /proc/meminfo's MemAvailable; the physical memory where it cannot be read), or
/// less under a cgroup's memory limit (a container) or a limit on its address space (ulimit -v),
/// less what they count in use already.
size_t memory_available_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  double available = pages > 0 && page > 0 ? static_cast<double>(pages) * page : 1e300;
  if (const std::optional<double> kb = number_after("/proc/meminfo", "MemAvailable:")) available = std::min(available, *kb * 1024);
  if (const std::optional<double> left = cgroup_memory_left()) available = std::min(available, *left);
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    double mapped = 0;  // pages mapped now: the first field of /proc/self/statm
    if (std::ifstream statm("/proc/self/statm"); statm >> mapped) mapped *= page;
    available = std::min(available, static_cast<double>(limit.rlim_cur) - mapped);
  }
  return static_cast<size_t>(std::clamp(available, 0.0, 1e18));
}

std::string megabytes(double bytes) { return std::to_string(static_cast<long long>(std::ceil(bytes / 1e6))) + " MB"; }

std::string picture_size_text(int width, int height, int samples_per_axis) {
  const long long per_pixel = static_cast<long long>(samples_per_axis) * samples_per_axis;
  return std::to_string(width) + "x" + std::to_string(height) + " pixels at " + std::to_string(per_pixel) +
         (per_pixel == 1 ? " ray" : " rays") + " each";
}

void refuse_beyond_memory(const std::string& option, const std::string& asked, double needed_bytes,
                          const std::string& advice) {
  refuse_beyond_memory(option, asked, needed_bytes, [&](double) { return advice; });
}

void refuse_beyond_memory(const std::string& option, const std::string& asked, double needed_bytes,
                          const std::function<std::string(double available_bytes)>& advice) {
  const auto available = static_cast<double>(memory_available_bytes());
  if (needed_bytes > available)
    throw UserError(option, asked + " need about " + megabytes(needed_bytes) + " of memory, and " + megabytes(available) +
                                " are available: " + advice(available));
}


void add_limit_options(CLI::App& cmd, std::initializer_list<Limit> limits) {
  for (const Limit which : limits) {
    const LimitSpec& spec = limit_spec(which);
    cmd.add_option_function<long long>(
           spec.option, [which](const long long& value) { set_limit(which, value); },
           std::string("Limit: at most this many ") + spec.unit + " (default " + std::to_string(spec.default_value) +
               ": " + spec.why + "); beyond it, refused with nothing written")
        ->transform(CLI::Validator(  // transform: the text it rewrites is what CLI11 converts
            [](std::string& text) -> std::string {
              // Read whole: CLI11's own check would say "not in range 0.000000 to 1.797...e308".
              const std::optional<long long> value = parse_integer(text);
              if (!value || *value < 1) return "must be a whole number of at least 1, got '" + text + "'";
              text = std::to_string(*value);  // as read here: CLI11 would take "010" as octal
              return {};
            },
            "POSITIVE"))
        ->group("Limits");
  }
}

CLI::Validator number_check(std::function<std::string(double)> problem, const std::string& description) {
  return CLI::Validator(
      [problem = std::move(problem)](std::string& text) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value)) return "must be a number, got '" + text + "'";
        return problem(value);
      },
      description);
}

CLI::Validator residual_check() {
  return number_check(residual_problem, "in [" + format_number(kMinResidual) + ", " + format_number(kMaxResidual) + "]");
}

CLI::Validator far_field_error_check() {
  return number_check(far_field_error_problem,
                      "0 or in [" + format_number(kMinFarFieldError) + ", " + format_number(kMaxFarFieldError) + "]");
}

CLI::Validator positive_at_most(double most) {
  return number_check(
      [most](double value) -> std::string {
        if (value > 0 && value <= most) return {};  // NaN fails
        return "must be positive and at most " + format_number(most) + ", got " + format_number(value);
      },
      "POSITIVE at most " + format_number(most));
}

}  // namespace radrecon::cli
