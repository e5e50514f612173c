// Output paths checked before any work: an output that is an input (directly, through a
// symbolic link, "..", or a hard link) is refused; so are outputs that cannot be written.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "io/paths.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace paths_test {

namespace fs = std::filesystem;

class Paths : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "sub");
    std::ofstream(dir_ / "in.csv") << "x,y,v\n";
  }
  std::string at(const std::string& name) const { return (dir_ / name).string(); }
  testing_support::TempDir dir_{"radrecon_paths_test"};
};

template <typename F>
std::string refusal(F f) {
  return testing_support::user_error_message(f);
}

TEST_F(Paths, AnOutputThatIsAnInputIsRefusedHoweverItIsSpelled) {
  fs::create_symlink(at("in.csv"), at("link.csv"));
  fs::create_hard_link(at("in.csv"), at("hard.csv"));
  for (const std::string& out : {at("in.csv"), at("sub/../in.csv"), at("./in.csv"), at("link.csv"), at("hard.csv"),
                                 at("missing/../in.csv"), at("missing/../link.csv")}) {
    const std::string message = refusal([&] { refuse_overwriting_inputs(out, "--out", {at("in.csv")}); });
    EXPECT_NE(message.find("refusing to overwrite"), std::string::npos) << out << ": " << message;
    EXPECT_NE(message.find("--out"), std::string::npos) << message;
  }
  // The input named through a link is caught too.
  EXPECT_NE(refusal([&] { refuse_overwriting_inputs(at("in.csv"), "--out", {at("link.csv")}); }), "");
}

TEST_F(Paths, TwoOutputsThatAreOneFileAreRefusedNamingBoth) {
  fs::create_symlink("lm.glb", at("lm.exr"));  // to a file not made yet: the writing makes it
  fs::create_hard_link(at("in.csv"), at("hard.csv"));
  const std::vector<std::pair<std::string, std::string>> same[] = {
      {{"--out", at("lm.glb")}, {"--exr", at("lm.exr")}},
      {{"--exr", at("lm.exr")}, {"--out", at("lm.glb")}},
      {{"--out", at("in.csv")}, {"--other", at("hard.csv")}},
      {{"--out", at("x.csv")}, {"--other", at("sub/../x.csv")}},
      {{"--out", at("y.csv")}, {"--other", at("missing/../y.csv")}}};
  for (const auto& outputs : same) {
    const std::string message = refusal([&] { refuse_shared_outputs(outputs); });
    EXPECT_EQ(message, outputs[1].first + ": '" + outputs[1].second + "' is the same file as " + outputs[0].first + " '" +
                           outputs[0].second + "'; give each output its own file");
  }
  EXPECT_EQ(refusal([&] { refuse_shared_outputs({{"--out", at("lm.glb")}, {"--exr", at("other.exr")}, {"--x", ""}}); }), "");
}

TEST_F(Paths, OtherOutputsPass) {
  EXPECT_EQ(refusal([&] { refuse_overwriting_inputs(at("out.csv"), "--out", {at("in.csv")}); }), "");
  EXPECT_EQ(refusal([&] { refuse_overwriting_inputs(at("sub/in.csv"), "--out", {at("in.csv")}); }), "");
  EXPECT_EQ(refusal([&] { check_output_file(at("new/folder/out.csv"), "--out"); }), "");
  EXPECT_EQ(refusal([&] { check_output_file(at("in.csv"), "--out"); }), "");  // replacing a file is allowed
  EXPECT_EQ(refusal([&] { check_output_folder(at("sub"), "--out"); }), "");
  EXPECT_EQ(refusal([&] { check_output_folder(at("new/folder"), "--out"); }), "");
  EXPECT_FALSE(fs::exists(at("new"))) << "checks create nothing";
}

TEST_F(Paths, UnwritableOutputsAreRefused) {
  EXPECT_NE(refusal([&] { check_output_file("", "--out"); }).find("empty"), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_file(at("sub") + "/", "--out"); }).find("ends in '/'"), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_file(at("newdir") + "/", "--out"); }).find("ends in '/'"), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_file(at("sub"), "--out"); }).find("is a folder"), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_file(at("in.csv/x.csv"), "--out"); }).find("not a folder"), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_folder(at("in.csv"), "--out"); }).find("not a folder"), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_folder(at("in.csv/deeper"), "--out"); }).find("not a folder"), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_folder("", "--out"); }).find("empty"), std::string::npos);
}

}  // namespace paths_test
}  // namespace radrecon
