#pragma once
// The mesh import error tests' one check: a model file refused whole, with a message naming it.

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "core/error.h"
#include "io/mesh_import.h"
#include "support/temp_dir.h"

namespace radrecon::testing_support {

/// Passes when importing dir/name, written with `content`, throws UserError whose message names
/// the file and contains every one of `needles`.
inline testing::AssertionResult Refused(const TempDir& dir, const std::string& name, const std::string& content,
                                 std::initializer_list<std::string> needles) {
  const std::string path = (dir / name).string();
  write_file(path, content);
  try {
    import_mesh(path);
  } catch (const UserError& e) {
    const std::string message = e.what();
    if (message.find(name) == std::string::npos) return testing::AssertionFailure() << "\"" << message << "\" does not name the file";
    for (const std::string& needle : needles)
      if (message.find(needle) == std::string::npos)
        return testing::AssertionFailure() << "\"" << message << "\" does not mention \"" << needle << "\"";
    return testing::AssertionSuccess() << message;
  } catch (const std::exception& e) {
    return testing::AssertionFailure() << "threw a non-UserError exception: " << e.what();
  } catch (...) {
    return testing::AssertionFailure() << "threw something not an exception";
  }
  return testing::AssertionFailure() << "accepted";
}

}  // namespace radrecon::testing_support
