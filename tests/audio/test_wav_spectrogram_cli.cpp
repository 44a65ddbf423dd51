// The wav-spectrogram program, run as a separate process: --help, a picture of a tone, and the
// errors a user sees (exit status and the file named). Skipped, saying so, if it is not built.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/audio/wav_fixture.hpp"
#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"
#include "textures/png_io.hpp"

namespace thx::audio::test_wav_spectrogram_cli {
namespace {

namespace fs = std::filesystem;

class WavSpectrogramCli : public ::testing::Test {
 protected:
  void SetUp() override {
    tool_ = THX_WAV_SPECTROGRAM;  // tests/audio/CMakeLists.txt: built before this test
    ASSERT_TRUE(fs::exists(tool_)) << "wav-spectrogram not built at " << tool_;
  }
  std::string path(const std::string& name) const { return dir_.file(name); }
  // Runs the tool; its exit status, with stdout and stderr in out_ and err_.
  int run(std::vector<std::string> args) {
    args.insert(args.begin(), tool_.string());
    thx::test::ToolRun r = thx::test::runTool(args, dir_.path(), 30.0);
    out_ = std::move(r.out);
    err_ = std::move(r.err);
    return r.status;
  }
  fs::path tool_;
  thx::test::TempDir dir_{"thx_wav_spectrogram"};
  std::string out_, err_;
};

TEST_F(WavSpectrogramCli, HelpExitsZero) {
  EXPECT_EQ(run({"--help"}), 0);
  EXPECT_NE(out_.find("usage: wav-spectrogram IN.wav OUT.png"), std::string::npos) << out_;
}

TEST_F(WavSpectrogramCli, DrawsAToneAndSaysWhere) {
  test::writePcm16(path("tone.wav"), test::tone(2000, 0.5, 11025), 44100);
  ASSERT_EQ(run({path("tone.wav"), path("tone.png"), "--width", "200", "--height", "100"}), 0) << err_;
  EXPECT_NE(out_.find(path("tone.png")), std::string::npos) << out_;
  const tex::RawImage image = tex::readPng(path("tone.png"));
  EXPECT_GT(image.width, 200);
}

TEST_F(WavSpectrogramCli, AMissingOrBadFileIsNamedAndExitsOne) {
  EXPECT_EQ(run({path("missing.wav"), path("x.png")}), 1);
  EXPECT_NE(err_.find(path("missing.wav")), std::string::npos) << err_;
  test::writePcm16(path("tone.wav"), test::tone(2000, 0.5, 4096), 44100);
  EXPECT_EQ(run({path("tone.wav"), path("no_such_dir/x.png")}), 1);
  EXPECT_NE(err_.find(path("no_such_dir/x.png")), std::string::npos) << err_;
  EXPECT_FALSE(fs::exists(path("x.png")));
}

TEST_F(WavSpectrogramCli, ABadCommandLineExitsTwo) {
  EXPECT_EQ(run({path("a.wav")}), 2);
  EXPECT_EQ(run({path("a.wav"), path("b.png"), "--window", "1000"}), 2);
  EXPECT_NE(err_.find("--window 1000"), std::string::npos) << err_;
}

}  // namespace
}  // namespace thx::audio::test_wav_spectrogram_cli
