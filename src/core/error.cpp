#include "core/error.h"

#include <cstdio>

namespace radrecon {

UserError::UserError(const std::string& where, const std::string& what)
    : std::runtime_error(where.empty() ? what : where + ": " + what) {}

UserError::UserError(const std::string& what) : std::runtime_error(what) {}

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
