// Letter blocks (a box named with one letter or digit): its glyph (clients/visual/glyphs.hpp) in
// dark ink on the block's top face. Seen from above, every cell of the 5x7 glyph is checked at its
// centre, projected to the pixel the rasteriser shades: ink cells dark, the others the wood.
#include "clients/visual/glyphs.hpp"
#include "clients/visual/scene_objects.hpp"
#include "scenes/scene_loader.hpp"
#include "tests/visual/visual_fixture.hpp"

namespace thx::visual::testing::test_letter_blocks {
namespace {

TEST(VisualLetterBlocks, NamesGiveGlyphs) {
  EXPECT_EQ(blockLetter("A"), 'A');
  EXPECT_EQ(blockLetter("q"), 'Q');
  EXPECT_EQ(blockLetter("7"), '7');
  EXPECT_EQ(blockLetter("post1"), 0);
  EXPECT_EQ(blockLetter("-"), 0);
  const scene::Scene scene = scene::loadScene(std::string(THX_SOURCE_DIR) + "/scenes/letter_blocks.yaml");
  std::string letters;
  for (const ObjectInstance& o : objectsAtRest(scene))
    if (o.letter) letters += o.letter;
  EXPECT_EQ(letters, "ABC");
}

TEST(VisualLetterBlocks, TheGlyphIsOnTheTopFace) {
  const OwnedSurface s = generated("bricks", 64, {});
  RenderSettings settings = referenceLighting(SurfaceMode::Normal);
  settings.light = Lighting{80.0, -135.0, 0.3, 0.0};
  context();
  ObjectInstance block;
  block.shape = UnitShape::Box;
  block.model = Eigen::Translation3d(0.0, 0.0, 0.005) * Eigen::Scaling(Eigen::Vector3d(0.02, 0.02, 0.01));
  block.albedo = {0.65f, 0.45f, 0.25f};
  for (char letter : {'A', 'K', '4'}) {
    block.letter = letter;
    CameraPlacement placement;
    placement.elevation_deg = 85;
    placement.azimuth_deg = -90;
    placement.distance_m = 0.05;
    FrameRenderer renderer(s.surface, settings, kImageSide, kImageSide);
    const Camera camera(placement, s.surface.mapping().plane_to_world, kImageSide, kImageSide);
    renderer.render(camera, {block});
    const Rgba8Image image = renderer.framebuffer().readColour();
    const Glyph glyph = *glyph5x7(letter);
    int checked = 0;
    for (int row = 0; row < 7; ++row)
      for (int column = 0; column < 5; ++column) {
        const Eigen::Vector3d unit(-0.25 + 0.1 * (column + 0.5), 0.35 - 0.1 * (row + 0.5), 0.5);
        const Eigen::Vector4d clip = camera.viewProjection() * (block.model * unit).homogeneous();
        const int x = int((clip.x() / clip.w() + 1) / 2 * kImageSide), y = int((1 - clip.y() / clip.w()) / 2 * kImageSide);
        ASSERT_TRUE(x >= 0 && x < kImageSide && y >= 0 && y < kImageSide);
        const bool ink = (glyph[std::size_t(row)] >> (4 - column)) & 1;
        const int red = image.at(x, y, 0);
        EXPECT_EQ(ink, red < 60) << letter << " row " << row << " column " << column << ": red " << red;
        ++checked;
      }
    EXPECT_EQ(checked, 35);
  }
}

}  // namespace
}  // namespace thx::visual::testing::test_letter_blocks
