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

/// Bytes this process may still allocate: the physical memory, or less under a limit on its
/// address space (ulimit -v) less what it maps already.
size_t memory_available_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  double available = pages > 0 && page > 0 ? static_cast<double>(pages) * page : 1e300;
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
