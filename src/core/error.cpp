#include "core/error.h"

namespace radrecon {

UserError::UserError(const std::string& where, const std::string& what)
    : std::runtime_error(where.empty() ? what : where + ": " + what) {}

UserError::UserError(const std::string& what) : std::runtime_error(what) {}

}  // namespace radrecon
