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
  std::vector<std::string> named{name};
  named.insert(named.end(), needles);
  return refused_mentioning([&] { import_mesh(path); }, named);
}

}  // namespace radrecon::testing_support
