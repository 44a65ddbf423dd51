// surface: size, pose, mesh, texture, representation, max_depth or max_depth_fraction, green,
// sampling, material, smoothing_sigma.
#include "scenes/scene_sections.hpp"
#include "textures/smoothing.hpp"

namespace thx::scene::detail {

namespace {

// Deeper than this is no longer a texture on a plane but geometry.
constexpr double kMaxReliefDepthM = 0.1;

std::optional<double> parseMaxDepth(const Field& field, const std::optional<tex::Representation>& representation) {
  const bool relief = representation.value_or(tex::Representation::Relief) == tex::Representation::Relief;
  const NumberRange range = positiveUpTo(kMaxReliefDepthM, "m");
  NumberRange any_finite;
  any_finite.unit = "m";
  const double depth = field.number(any_finite);
  if (depth <= 0.0)
    field.fail(relief ? "a relief surface needs a positive max_depth" : "max_depth must be positive",
               range.describe() + " (depth into the surface), or leave max_depth out to use the texture's own");
  if (!range.contains(depth)) field.fail("out of range", range.describe());
  if (!relief) field.warn("max_depth is ignored for representation: normal (a normal map has no depth)");
  return depth;
}

// The paper's form: depth as a fraction of the object's size, here the surface's width size[0]
// (its extent along the plane's x axis, which the texture's u spans).
double parseMaxDepthFraction(const Field& field, const std::optional<tex::Representation>& representation,
                             double width_m) {
  const bool relief = representation.value_or(tex::Representation::Relief) == tex::Representation::Relief;
  const double fraction = field.number(positiveUpTo(1.0, "of size[0]"));
  const double depth = fraction * width_m;
  if (depth > kMaxReliefDepthM) {
    field.fail("the depth it gives is too deep for a texture",
               "at most " + formatNumber(kMaxReliefDepthM) + " m, i.e. a fraction up to " +
                   formatNumber(kMaxReliefDepthM / width_m) + " of size[0] = " + formatNumber(width_m) + " m",
               "'" + formatNumber(fraction) + "' (" + formatNumber(depth) + " m)");
  }
  if (!relief) field.warn("max_depth_fraction is ignored for representation: normal (a normal map has no depth)");
  return depth;
}

tex::SampleOptions parseSampling(const Field& field) {
  field.expectKeys({"filter", "address"});
  tex::SampleOptions options;
  if (auto f = field.find("filter"))
    options.filter = f->choice<tex::Filter>({{"nearest", tex::Filter::Nearest}, {"bilinear", tex::Filter::Bilinear}});
  if (auto a = field.find("address"))
    options.address = a->choice<tex::Address>({{"wrap", tex::Address::Wrap}, {"clamp", tex::Address::Clamp}});
  return options;
}

// The slab under the texture: a thickness that is not positive is an error of its own wording.
std::optional<double> parseThickness(const Field& field) {
  const auto t = field.find("thickness");
  if (!t) return std::nullopt;
  NumberRange any;
  const double thickness = t->number(any);
  const NumberRange range = positiveUpTo(1.0, "m");
  if (thickness <= 0.0) t->fail("the slab's thickness must be positive", range.describe());
  if (!range.contains(thickness)) t->fail("out of range", range.describe());
  return thickness;
}

Roughness parseRoughness(const Field& field) {
  field.expectKeys({"beta", "amplitude", "spacing"});
  Roughness r;
  if (auto f = field.find("beta")) r.beta = f->number(closedRange(0.0, 4.0, ""));
  if (auto f = field.find("amplitude")) r.amplitude = f->number(closedRange(0.0, 10.0, "(micro force per newton of normal force)"));
  if (auto f = field.find("spacing")) r.spacing_m = f->number(positiveUpTo(1e-2, "m"));
  return r;
}

}  // namespace

TextureSource parseTexture(const Field& field, const Surface& surface, const std::string& size_name) {
  const FileOrGenerator given =
      parseFileOrGenerator(field, {"file", "generator", "size", "seed", "params"}, "texture",
                           "{file: PATH} or {generator: KIND, size: N, seed: S, params: {...}}");
  TextureSource source;
  source.where = field.location();
  if (given.file) {
    refuseKeys(field, {"size", "seed", "params"}, "generator textures", "file:");
    source.kind = TextureSource::Kind::File;
    source.file = parseExistingFile(*given.file, "texture file (PNG)");
  } else {
    source.kind = TextureSource::Kind::Generator;
    source.generator = parseGenerator(field, surface, size_name);
  }
  return source;
}

Surface parseSurface(const Field& field) {
  if (field.isNull()) field.fail("missing value", "a mapping with at least size and texture");
  field.expectKeys({"size", "pose", "texture", "representation", "max_depth", "max_depth_fraction", "green",
                    "sampling", "material", "smoothing_sigma", "thickness", "held", "roughness", "mesh"});
  Surface s;
  s.size_m = field.at("size", "[x, y] in metres").vector2(positiveUpTo(10.0, "m"));
  if (auto p = field.find("pose")) s.pose = parsePose(*p);
  if (auto m = field.find("mesh")) s.mesh = parseMesh(*m, s);
  if (auto r = field.find("representation"))
    s.representation = r->choice<tex::Representation>(
        {{"normal", tex::Representation::Normal}, {"relief", tex::Representation::Relief}});
  s.texture = parseTexture(field.at("texture", "{file: PATH} or {generator: KIND, ...}"), s);
  if (s.texture.kind == TextureSource::Kind::Generator && !s.representation)
    s.representation = tex::Representation::Relief;  // what generators produce
  const auto depth = field.find("max_depth");
  const auto fraction = field.find("max_depth_fraction");
  if (depth && fraction)
    fraction->fail("both max_depth and max_depth_fraction given",
                   "one of them: metres, or a fraction of size[0]", "");
  if (depth) s.max_depth_m = parseMaxDepth(*depth, s.representation);
  if (fraction) s.max_depth_m = parseMaxDepthFraction(*fraction, s.representation, s.size_m.x());
  if (auto g = field.find("green")) {
    s.green = g->choice<tex::GreenConvention>(
        {{"opengl", tex::GreenConvention::OpenGL}, {"directx", tex::GreenConvention::DirectX}});
    if (s.texture.kind == TextureSource::Kind::Generator)
      g->warn("green is ignored for generated textures (it describes how a file stores normals)");
  }
  if (auto sm = field.find("sampling")) s.sampling = parseSampling(*sm);
  s.material = *findMaterial("ceramic");
  if (auto m = field.find("material")) s.material = parseMaterial(*m);
  if (auto sigma = field.find("smoothing_sigma"))
    s.smoothing_sigma_texels = sigma->number(closedRange(0.0, tex::kMaxSmoothingSigma, "texels"));
  if (auto t = parseThickness(field)) s.thickness_m = *t;
  if (auto h = field.find("held"))
    s.held = h->choice<SlabSupport>({{"free", SlabSupport::Free}, {"edges", SlabSupport::ClampedEdges}});
  if (auto r = field.find("roughness")) s.roughness = parseRoughness(*r);
  return s;
}

}  // namespace thx::scene::detail
