// visual-client: the scene as the eye sees it (kHelp in options.cpp; docs/visual.md).
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "base/program_main.hpp"
#include "meshes/builtin_shapes.hpp"
#include "clients/visual/frame_renderer.hpp"
#include "clients/visual/headless_context.hpp"
#include "clients/visual/image_writer.hpp"
#include "clients/visual/live_client.hpp"
#include "clients/visual/mesh_frame_renderer.hpp"
#include "clients/visual/options.hpp"
#include "clients/visual/replay_devices.hpp"
#include "clients/visual/replay_frames.hpp"
#include "clients/visual/scene_objects.hpp"
#include "clients/visual/window_presenter.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_mesh.hpp"
#include "scenes/scene_surface.hpp"
#include "thx_client/logged_scene.hpp"
#include "textures/smoothing.hpp"

namespace {

using namespace thx;
using namespace thx::visual;

std::string framePath(const Options& o, int f) { return visual::framePath(o.out_dir, f, o.frame_format); }

// What a recorded frame shows: the scene's objects where the recording's physics poses put them,
// and each drawn device's pen (tip, proxy), unless the options leave either out.
std::vector<ObjectInstance> replayedObjects(const Options& o, const scene::Scene& scene,
                                            const tex::TexturedSurface& surface, const ReplayFrame& frame) {
  std::vector<ObjectInstance> objects;
  if (!o.no_objects) objects = objectsAt(scene, frame.bodies);
  if (!o.no_pen) {
    const std::vector<ObjectInstance> pens = pensAt(surface, pensOf(frame), &scene);
    objects.insert(objects.end(), pens.begin(), pens.end());
  }
  return objects;
}

// The recording's frames (at most --frames N) with the pens --device picks (replay_devices.hpp).
std::vector<ReplayFrame> recordedFrames(const Options& o, const scene::Scene& scene) {
  std::vector<ReplayFrame> frames =
      replayFrames(o.replay_log, scene.rates.servo_hz, o.replay_rate_hz, replayedDevices(o.replay_log, o.device));
  if (o.frames > 0 && frames.size() > std::size_t(o.frames)) frames.resize(std::size_t(o.frames));
  return frames;
}

// A recorded session frame by frame: the pens (tip, proxy) where the recording put them, the objects
// at the recorded physics poses (at rest before the first, or when the log has none).
int replay(const Options& o, const scene::Scene& scene, const tex::TexturedSurface& surface,
           const CameraPlacement& placement) {
  const std::vector<ReplayFrame> frames = recordedFrames(o, scene);
  HeadlessContext context;
  FrameRenderer renderer(surface, o.render, o.width, o.height);
  renderer.setTexturedObjects(scene);
  const Camera camera(placement, surface.mapping().plane_to_world, o.width, o.height);
  std::filesystem::create_directories(o.out_dir);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    renderer.render(camera, replayedObjects(o, scene, surface, frames[f]));
    writeImage(framePath(o, int(f)), renderer.framebuffer().readColour(), o.png_level);
  }
  if (!o.quiet)
    std::fprintf(stderr, "visual-client: wrote %zu frames of %s to %s\n", frames.size(), o.replay_log.c_str(),
                 o.out_dir.c_str());
  return 0;
}

// A textured mesh instead of the plane, the scene's texture wrapped on it in its tangent frames:
// the scene's own (surface.mesh, placed by its pose) or --surface-mesh's built-in shape (centred on
// the plane's origin, the camera's default target). Immovable: `surface` points at `shape`.
struct MeshView {
  mesh::TexturedMesh shape;
  MeshSurface surface;
  std::string name;
  Eigen::Isometry3d orbit_frame = Eigen::Isometry3d::Identity();  // the camera's: the plane's, or the scene mesh's centre
  CameraPlacement placement;
};

void buildMeshView(MeshView& view, const Options& o, const scene::Scene& scene, const tex::TexturedSurface& surface,
                   const CameraPlacement& placement) {
  MeshSurface& mesh = view.surface;
  view.orbit_frame = surface.mapping().plane_to_world;
  view.placement = placement;
  if (!o.surface_mesh.empty()) {
    mesh::GeneratedMesh built = mesh::builtInShape(o.surface_mesh, surfaceMeshSize(scene), surfaceMeshTile(o, scene));
    view.shape = std::move(built.mesh);
    mesh.tile_m = built.tile_used_m;
    mesh.mesh_to_world = surface.mapping().plane_to_world * Eigen::Translation3d(-mesh::boundsCentre(view.shape));
    view.name = o.surface_mesh;
  } else {
    scene::SceneMesh built = scene::buildSceneMesh(scene);
    view.shape = std::move(built.mesh);
    mesh.tile_m = built.tile_m;
    mesh.mesh_to_world = built.mesh_to_world;
    view.name = "surface.mesh";
    // The camera orbits the mesh's centre, in the mesh's frame, from where the whole mesh is seen.
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& p : view.shape.positions) box.extend(p);
    view.orbit_frame = built.mesh_to_world * Eigen::Translation3d(box.center());
    if (!o.distance_given) view.placement.distance_m = 1.3 * box.sizes().maxCoeff();
  }
  mesh.mesh = &view.shape;
  mesh.map = &surface.map();
  mesh.filter = surface.sampling().filter;
  mesh.use_relief = surface.usesRelief();
  if (!o.quiet)
    std::fprintf(stderr, "visual-client: %s, %zu triangles, tile %.4g x %.4g m\n", view.shape.source.c_str(),
                 view.shape.triangles.size(), mesh.tile_m.x(), mesh.tile_m.y());
}

// Orbit frames or a screenshot of the mesh, with the scene's objects where it places them (not
// on --surface-mesh's shape, which is not the scene's).
int drawSurfaceMesh(const Options& o, const scene::Scene& scene, const tex::TexturedSurface& surface,
                    const CameraPlacement& placement) {
  HeadlessContext context;
  if (!o.quiet) std::fprintf(stderr, "visual-client: %s\n", context.description().c_str());
  MeshView view;
  buildMeshView(view, o, scene, surface, placement);
  const Eigen::Isometry3d& plane = view.orbit_frame;
  MeshFrameRenderer renderer(view.surface, o.render, o.width, o.height);
  renderer.setTexturedObjects(scene);
  std::vector<ObjectInstance> objects;
  if (!o.no_objects && o.surface_mesh.empty()) objects = objectsAtRest(scene);
  if (!o.screenshot.empty()) {
    renderer.render(Camera(view.placement, plane, o.width, o.height), objects);
    writeImage(o.screenshot, renderer.framebuffer().readColour(), o.png_level);
    if (!o.quiet)
      std::fprintf(stderr, "visual-client: wrote %s (%s, %s)\n", o.screenshot.c_str(), view.name.c_str(),
                   modeName(o.render).c_str());
    return 0;
  }
  std::filesystem::create_directories(o.out_dir);
  for (int f = 0; f < o.frames; ++f) {
    CameraPlacement p = view.placement;
    p.azimuth_deg += f * o.orbit_deg_per_frame;
    renderer.render(Camera(p, plane, o.width, o.height), objects);
    writeImage(framePath(o, f), renderer.framebuffer().readColour(), o.png_level);
  }
  if (!o.quiet) std::fprintf(stderr, "visual-client: wrote %d frames to %s\n", o.frames, o.out_dir.c_str());
  return 0;
}

// A recorded session on a mesh scene, frame by frame: the mesh, the scene's objects where
// physics-client's poses in the recording put them (a combined session), and the pens (tip, proxy).
int replayOnMesh(const Options& o, const scene::Scene& scene, const scene::SceneSurface& scene_surface,
                 const CameraPlacement& placement) {
  const tex::TexturedSurface& surface = scene_surface.surface;
  MeshView view;
  buildMeshView(view, o, scene, surface, placement);
  // The recording's hellos name the mesh scene's fingerprint: the texture's hashed with the mesh.
  const std::uint64_t fingerprint =
      scene::meshSceneFingerprint(scene_surface.fingerprint, view.shape, view.surface.mesh_to_world, view.surface.tile_m);
  client::checkLoggedScene(client::loggedScenes(o.replay_log), {scene_surface.scene_name, fingerprint}, o.replay_log,
                           false, false);
  const std::vector<ReplayFrame> frames = recordedFrames(o, scene);
  HeadlessContext context;
  MeshFrameRenderer renderer(view.surface, o.render, o.width, o.height);
  renderer.setTexturedObjects(scene);
  const Camera camera(view.placement, view.orbit_frame, o.width, o.height);
  std::filesystem::create_directories(o.out_dir);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    renderer.render(camera, replayedObjects(o, scene, surface, frames[f]));
    writeImage(framePath(o, int(f)), renderer.framebuffer().readColour(), o.png_level);
  }
  if (!o.quiet)
    std::fprintf(stderr, "visual-client: wrote %zu frames of %s on the mesh to %s\n", frames.size(),
                 o.replay_log.c_str(), o.out_dir.c_str());
  return 0;
}

int run(const Options& o) {
  const scene::Scene scene = scene::loadScene(o.scene);
  scene::SurfaceTextureOptions texture_options;
  texture_options.smooth = &tex::smoothTexture;
  const scene::SceneSurface surface = scene::buildSceneSurface(scene, texture_options);

  if (o.live && scene.surface.mesh)
    throw Error(Error::Kind::Config, o.scene + ": surface.mesh: live frames draw the plane; a mesh scene is drawn "
                                               "from a recording (--replay-log LOG) or as orbit frames (--frames N --out DIR)");
  if (o.live) return runLive(o);
  const CameraPlacement placement = cameraPlacement(o, scene);
  if (!o.replay_log.empty()) {
    if (scene.surface.mesh) return replayOnMesh(o, scene, surface, placement);
    // The recording's hellos name the scene's texture fingerprint: it must be this one's.
    client::checkLoggedScene(client::loggedScenes(o.replay_log), {surface.scene_name, surface.fingerprint}, o.replay_log,
                             false, false);
    return replay(o, scene, surface.surface, placement);
  }
  if (!o.surface_mesh.empty() || scene.surface.mesh) {
    if (o.window)
      throw Error(Error::Kind::Config, o.scene + ": surface.mesh: a mesh scene is drawn headless (--frames N --out DIR, "
                                                 "--screenshot FILE or --replay-log LOG); --window shows planes only");
    return drawSurfaceMesh(o, scene, surface.surface, placement);
  }
  std::vector<ObjectInstance> objects;
  if (!o.no_objects) objects = objectsAtRest(scene);
  if (!o.no_pen) {
    const std::vector<ObjectInstance> pens = pensAtRest(surface.surface, scene, std::nullopt, o.pen_xy);
    objects.insert(objects.end(), pens.begin(), pens.end());
  }

  if (o.window) {
    const int drawn = runWindow(surface.surface, o.render, placement, objects,
                                {o.width, o.height, o.window_frames, 0.0, o.quiet, o.window_screenshot, {}, 30.0, {}});
    if (!o.quiet) std::fprintf(stderr, "visual-client: window closed after %d frames\n", drawn);
    return 0;
  }
  HeadlessContext context;
  if (!o.quiet) std::fprintf(stderr, "visual-client: %s\n", context.description().c_str());
  FrameRenderer renderer(surface.surface, o.render, o.width, o.height);
  renderer.setTexturedObjects(scene);

  if (!o.screenshot.empty()) {
    renderer.render(Camera(placement, surface.surface.mapping().plane_to_world, o.width, o.height), objects);
    writeImage(o.screenshot, renderer.framebuffer().readColour(), o.png_level);
    if (!o.quiet) std::fprintf(stderr, "visual-client: wrote %s (%s)\n", o.screenshot.c_str(), modeName(o.render).c_str());
    return 0;
  }
  std::filesystem::create_directories(o.out_dir);
  for (int f = 0; f < o.frames; ++f) {
    CameraPlacement p = placement;
    p.azimuth_deg += f * o.orbit_deg_per_frame;
    renderer.render(Camera(p, surface.surface.mapping().plane_to_world, o.width, o.height), objects);
    writeImage(framePath(o, f), renderer.framebuffer().readColour(), o.png_level);
  }
  if (!o.quiet) std::fprintf(stderr, "visual-client: wrote %d frames to %s\n", o.frames, o.out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return thx::runProgram("visual-client", kHelp, argc, argv,
                         [](const std::vector<std::string>& args) { return run(parseOptions(args)); });
}
