// What goes wrong gets a clear error, never a crash (issue 15): a shader that does not compile
// names its file and line, an image file type that is not known names the file, bad command
// lines name the option and the value.
#include <gtest/gtest.h>

#include "clients/visual/image_writer.hpp"
#include "clients/visual/options.hpp"
#include "clients/visual/shader_program.hpp"
#include "clients/visual/shader_sources.hpp"
#include "clients/visual/gl_error.hpp"
#include "tests/visual/visual_fixture.hpp"

namespace thx::visual::test_gl_errors {
namespace {

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(VisualGlErrors, InfoLogLocationsBecomeFileAndLine) {
  const std::string log = "0:12(5): error: `foo' undeclared\n0:13(1): error: syntax error\n";
  EXPECT_EQ(namedInfoLog("surface.frag", log),
            "  surface.frag:12: error: `foo' undeclared\n  surface.frag:13: error: syntax error\n");
  EXPECT_EQ(namedInfoLog("x.vert", "0(7) : error C0000: bad\n"), "  x.vert:7: error C0000: bad\n");
}

TEST(VisualGlErrors, ShaderThatDoesNotCompileNamesFileAndLine) {
  testing::context();
  const ShaderSource broken{"broken.frag", "#version 330 core\nout vec4 c;\nvoid main() { c = undeclared_name; }\n"};
  const std::string m = messageOf([&] { ShaderProgram p(embeddedShader("object.vert"), broken); });
  EXPECT_NE(m.find("shader broken.frag does not compile"), std::string::npos) << m;
  EXPECT_NE(m.find("broken.frag:3:"), std::string::npos) << m;
  EXPECT_NE(m.find("undeclared_name"), std::string::npos) << m;
}

TEST(VisualGlErrors, DefinesKeepTheFilesLineNumbers) {
  testing::context();
  ShaderSource s = embeddedShader("surface.frag");
  s.text += "\nvoid broken() { return 1; }\n";  // the line after the file's last one
  const int last_line = int(std::count(s.text.begin(), s.text.end(), '\n'));
  const std::string m =
      messageOf([&] { ShaderProgram p(embeddedShader("surface.vert"), withDefines(s, {"MODE_RELIEF"})); });
  EXPECT_NE(m.find("surface.frag:" + std::to_string(last_line) + ":"), std::string::npos) << m;
}

TEST(VisualGlErrors, EveryEmbeddedShaderCompilesInEveryMode) {
  testing::context();
  for (const std::vector<std::string>& defines :
       {std::vector<std::string>{}, {"MODE_RELIEF"}, {"MODE_MESH"}}) {
    EXPECT_NO_THROW(ShaderProgram(embeddedShader("surface.vert"), withDefines(embeddedShader("surface.frag"), defines)));
  }
  EXPECT_NO_THROW(ShaderProgram(embeddedShader("object.vert"), embeddedShader("object.frag")));
  EXPECT_THROW(embeddedShader("missing.frag"), GlError);
}

TEST(VisualGlErrors, UnknownImageTypeNamesTheFile) {
  const Rgba8Image image{2, 2, std::vector<std::uint8_t>(16, 0)};
  const std::string m = messageOf([&] { writeImage("/tmp/frame.jpg", image); });
  EXPECT_NE(m.find("/tmp/frame.jpg: unknown image type '.jpg'; expected .png or .ppm"), std::string::npos) << m;
  EXPECT_NE(messageOf([&] { writeImage("/nonexistent-dir/x.png", image); }).find("/nonexistent-dir/x.png: cannot write"),
            std::string::npos);
}

TEST(VisualGlErrors, CommandLineMistakesNameOptionAndValue) {
  const auto parse = [](std::vector<std::string> a) { return messageOf([&] { parseOptions(a); }); };
  EXPECT_EQ(parse({"--scene", "s.yaml", "--screenshot", "x.png", "--mode", "bump"}),
            "--mode: expected normal, relief or mesh:N, got 'bump'");
  EXPECT_NE(parse({"--scene", "s.yaml", "--screenshot", "x.png", "--mode", "mesh:0"}).find("--mode mesh:N"),
            std::string::npos);
  EXPECT_EQ(parse({"--scene", "s.yaml"}), "give exactly one of --screenshot FILE, --frames N --out DIR, --replay-log FILE --out DIR and --window");
  EXPECT_EQ(parse({"--scene", "s.yaml", "--frames", "3"}), "--frames N needs --out DIR");
  EXPECT_EQ(parse({"--scene", "s.yaml", "--screenshot", "x.png", "--size", "640"}),
            "--size: expected WxH in pixels, e.g. 640x360, got '640'");
  EXPECT_EQ(parse({"--scene", "s.yaml", "--screenshot", "x.png", "--search", "cone"}),
            "--search: expected linear or maxmip, got 'cone'");
  EXPECT_EQ(parseOptions({"--scene", "s.yaml", "--screenshot", "x.png", "--search", "maxmip"}).render.steps.search,
            ReliefSearch::MaxMip);
  const Options ok = parseOptions({"--scene", "s.yaml", "--frames", "4", "--out", "d", "--mode", "mesh:64"});
  EXPECT_EQ(ok.render.mode, SurfaceMode::Mesh);
  EXPECT_EQ(ok.render.mesh_n, 64);
  EXPECT_DOUBLE_EQ(ok.orbit_deg_per_frame, 90.0);
}

}  // namespace
}  // namespace thx::visual::test_gl_errors
