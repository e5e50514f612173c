// The --max-* options that raise (or lower) the resource limits of core/limits.h.
#include <string>

#include "cli/commands.h"
#include "core/limits.h"

namespace radrecon::cli {

void add_limit_options(CLI::App& cmd, std::initializer_list<Limit> limits) {
  for (const Limit which : limits) {
    const LimitSpec& spec = limit_spec(which);
    cmd.add_option_function<long long>(
           spec.option, [which](const long long& value) { set_limit(which, value); },
           std::string("Limit: at most this many ") + spec.unit + " (default " + std::to_string(spec.default_value) +
               ": " + spec.why + "); beyond it, refused with nothing written")
        ->check(CLI::PositiveNumber)
        ->group("Limits");
  }
}

}  // namespace radrecon::cli
