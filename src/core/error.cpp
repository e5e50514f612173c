#include "core/error.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace radrecon {

UserError::UserError(const std::string& where, const std::string& what)
    : std::runtime_error(where.empty() ? what : where + ": " + what) {}

UserError::UserError(const std::string& what) : std::runtime_error(what) {}

std::string with_failed_write_reason(const std::string& said) {
  const int error = errno;
  if (error != ENOSPC && error != EFBIG && error != EDQUOT && error != EIO) return said;
  const std::string reason = std::strerror(error);
  return said.find(reason) != std::string::npos ? said : said + " (" + reason + ")";
}

namespace {
thread_local std::vector<std::string>* warning_sink = nullptr;
}  // namespace

void warn(const std::string& message) {
  if (warning_sink != nullptr) warning_sink->push_back(message);
  else std::fprintf(stderr, "radrecon: warning: %s\n", message.c_str());
}

WarningCollector::WarningCollector() : outer_(warning_sink) { warning_sink = &messages_; }
WarningCollector::~WarningCollector() { warning_sink = outer_; }

}  // namespace radrecon
