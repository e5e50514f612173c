// Built into every plugin (io/plugin.h): its interface version, and the program's resource
// limits into the plugin's copy.

#include "core/limits.h"
#include "io/plugin.h"

extern "C" __attribute__((visibility("default"))) void radrecon_plugin_set_limit(int which, long long value) {
  radrecon::set_limit(static_cast<radrecon::Limit>(which), value);
}

extern "C" __attribute__((visibility("default"))) int radrecon_plugin_abi() { return radrecon::kPluginAbi; }
