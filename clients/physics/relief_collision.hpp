#pragma once
// Bullet collision algorithm for (sphere | box | capsule | cylinder) against a ReliefPlaneShape.
//
// Each step it rasterises the object's underside over its footprint texels (relief_raster.hpp),
// picks at most 4 contacts (contact_selection.hpp) and reports them with the relief normals
// there. Its manifold is cleared at the start of every step: cached points fixed to a rolling
// ball's surface rotate behind the centre and inject energy (docs/design.md §7 fact 4), and the
// rasteriser finds every contact afresh anyway. Two exceptions keep their contacts between steps,
// merged with the new ones: a box with a relief on its faces (textured_box.hpp), grouped by normal
// into up to five manifolds (relief_collision.cpp, texturedBoxCollision), and a cylinder standing
// on an end face, on two rim points of the face's fall line (end_face_contacts.hpp). A ball with a
// bump map (textured_ball.hpp) meets the plane by the textured box's pair depth, its points found
// afresh each step as any ball's (relief_collision.cpp, texturedBallCollision).
// A box (textured or not), capsule or cylinder against a relief-textured mesh (mesh_relief_chart.hpp)
// takes the same rule on the mesh's chart under it, the relief standing on the mesh's bend (on a
// mesh without a relief, on its smooth chart: the bend alone, sampled over the object); each
// point names the triangle under it (m_index1), as Bullet's own points on a mesh do; the chart
// stops at a crease within the object's reach, and each surface across it is met the same way on
// a chart of its own, cut at its creases in turn, in manifolds of its own (chart_boundary.hpp). A
// ball with a bump map does the same, by its own rule (texturedBallCollision); a plain sphere on
// such a mesh stays with Bullet's sphere-triangle points, lifted onto the relief (mesh_contact.hpp).
// A box that a textured object meets, or a textured box that a smaller box meets (box_ground.hpp),
// is met as a mesh of its faces: the mesh rules, the box's moving frame. A textured object on a
// plain plane (plain_plane.hpp) meets it as a plain box's face: a smooth chart laid under it.
//
// Contact convention (the manifold is always (object, relief), whatever order the dispatcher
// hands the pair in): normal = relief normal in world frame, pointing from the relief to the
// object; distance = the signed gap between the contact point on the object and the texel's
// tangent plane, along n (so the solver's correction along n removes exactly the overlap); the
// point on the object is where its surface faces -n (underside.hpp, contactOnObject): q = c - r n
// for a sphere (Eq. 2), the axis point for a capsule or a cylinder's side, the lowest point above
// the texel for a box or a cylinder's end face.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "clients/physics/box_ground.hpp"
#include "clients/physics/chart_boundary.hpp"
#include "clients/physics/ground_bend.hpp"
#include "clients/physics/manifold_algorithm.hpp"
#include "clients/physics/mesh_relief_chart.hpp"
#include "clients/physics/relief_plane_shape.hpp"
#include "clients/physics/speculative_contacts.hpp"
#include "clients/physics/textured_ball_basins.hpp"
#include "clients/physics/textured_box.hpp"
#include "clients/physics/underside.hpp"

namespace thx::phys {

class ReliefCollisionAlgorithm : public ManifoldAlgorithm {
 public:
  // `ground`: the ground's mesh where it is built once for the world (a textured box's or a ball
  // with a bump map's: ObjectFacesCatalog); nullptr: built on first need (a plain box's).
  ReliefCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0,
                           const btCollisionObjectWrapper* body1, bool swapped, const ObjectGround* ground = nullptr)
      : ManifoldAlgorithm(ci, body0, body1), swapped_(swapped), shared_ground_(ground) {}

  ~ReliefCollisionAlgorithm() override;

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo& info, btManifoldResult* result) override;
  void getAllContactManifolds(btManifoldArray& manifolds) override;

  struct CreateFunc : btCollisionAlgorithmCreateFunc {
    explicit CreateFunc(bool swapped) { m_swapped = swapped; }
    btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                   const btCollisionObjectWrapper* body0,
                                                   const btCollisionObjectWrapper* body1) override {
      return create<ReliefCollisionAlgorithm>(ci, body0, body1, m_swapped);
    }
  };

 private:
  // A textured box's contacts come in up to kNormalGroups groups by their normals' tilt, each in
  // its own manifold of at most four points (relief_collision.cpp, normalGroup); group 0 is the
  // pair's own manifold on the chart under the object.
  static constexpr std::size_t kNormalGroups = 5;
  // Which chart's manifolds: the one under the object (kUnder) or a surface across a crease from
  // it (its slot, 0 to ChartBoundary::kMaxSurfaces - 1).
  static constexpr int kUnder = -1;
  // `boundary` (a mesh's chart's; nullptr on the plane): texels past it are not the mesh's.
  void texturedBoxCollision(const btCollisionObjectWrapper& object, const btCollisionObjectWrapper& relief,
                            const tex::TexturedSurface& surface, const GroundBend& bend, const Underside& underside,
                            const FaceTexture& faces, const ChartBoundary* boundary, double threshold,
                            const Eigen::Isometry3d& world_from_plane, int chart, btManifoldResult* result);
  btPersistentManifold* groupManifold(int chart, std::size_t g, const btCollisionObject* object,
                                      const btCollisionObject* relief);
  // A ball with a bump map keeps up to kMaxBallBasins points, four to a manifold: its own and the
  // chart's group manifolds from 1 on, returned cleared.
  static constexpr std::size_t kBallMoreManifolds = kMaxBallBasins / kMaxReliefContacts - 1;
  static_assert(kMaxBallBasins % kMaxReliefContacts == 0 && kBallMoreManifolds < kNormalGroups);
  std::array<btPersistentManifold*, kBallMoreManifolds> ballManifolds(int chart, const btCollisionObject* object,
                                                                      const btCollisionObject* relief);
  void clearGroupManifolds();
  // An untextured object (the plane's general rule: raster, selection, basins, refinement), on the
  // relief plane or on a mesh's chart standing on its bend; `level_runs` (the plane's) lets a box's
  // row-by-row path skip level stretches, on flat ground only; `motion` (the object's) decides
  // which of a ball's further points Bullet may take (speculative_contacts.hpp).
  void plainObjectCollision(const tex::TexturedSurface& surface, const GroundBend& bend, const Underside& underside,
                            bool on_end_face, const ReliefLevelRuns* level_runs, const ChartBoundary* boundary,
                            double threshold, const Eigen::Isometry3d& world_from_plane, const BodyMotion& motion,
                            btManifoldResult* result);
  // A textured box or a ball with a bump map against a plain plane (plain_plane.hpp): the rule of a
  // plain box's face, on a smooth chart laid under the object.
  void plainPlaneCollision(const btCollisionObjectWrapper& object, const btCollisionObjectWrapper& plane,
                           btManifoldResult* result);
  // An object against a mesh with a chart (mesh_relief_chart.hpp: a relief's or a smooth one): the
  // same rule as on the plane (a textured box's, `faces`, or the untextured one's) on the mesh's
  // chart under it, and on the chart of each surface across a crease within its reach.
  // `triangles`: the mesh's faces as Bullet's, where the chart's boundary is looked for.
  // `ground`: a scene's mesh, or a box's or a ball's (box_ground.hpp), centred on its frame's
  // origin, where a cylinder's chart is laid under its axis's point nearest that centre. A ball's
  // cube-sphere has no creases (below).
  enum class MeshGround { Scene, Box, Ball };
  void meshCollision(const btCollisionObjectWrapper& object, const btCollisionObjectWrapper& mesh,
                     const MeshRelief& relief, const btConcaveShape& triangles, const FaceTexture* faces,
                     MeshGround ground, btManifoldResult* result);
  // The rule on one chart, into that chart's manifolds; each point names the triangle under it.
  // Returns the chart's boundary: none on a ball's cube-sphere, smooth everywhere. There the 60
  // degrees of chart_boundary.hpp lie within an object's reach round the ball's own curvature, and
  // the charts laid "across" them met the object too, on their bends 60 degrees off: two balls
  // recessed 0.5 mm pressed together along a line off the world's axes rested 0.43 mm off their
  // touch, or were thrown apart (2026-12-05, TexturedBallPairs.PressedTogetherAlongAnyLineTheyRestWhereTheirSurfacesTouch).
  ChartBoundary chartCollision(const btCollisionObjectWrapper& object, const btCollisionObjectWrapper& mesh,
                               const MeshRelief& relief, const btConcaveShape& triangles, const FaceTexture* faces,
                               const MeshChart& chart, int slot, MeshGround ground,
                               const Eigen::AlignedBox3d& reach, double threshold, btManifoldResult* result);
  // The slot of the surface across a crease whose face normal is `normal` (mesh frame): the one
  // that held it last step, else a free one, emptied; kUnder when none is free.
  int surfaceSlot(const Eigen::Vector3d& normal, std::uint32_t taken);
  void clearSlot(int slot);
  // The manifolds of one chart (kUnder: the pair's and the textured box's groups), or of all.
  void slotManifolds(int slot, btManifoldArray& manifolds);
  void chartManifolds(btManifoldArray& manifolds);

  // The surfaces across creases from the chart under the object, each in a slot kept while it stays
  // within reach (a textured box's kept points stay with their surface). Made on first need: the
  // algorithm comes from Bullet's pool, sized for its own algorithms.
  struct SurfaceSlot {
    btPersistentManifold* groups[kNormalGroups] = {};
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    bool held = false;  // it held a surface last step
    BallBasinHint ball_hint;  // a ball with a bump map on this chart (textured_ball_basins.hpp)
  };
  struct SurfaceSlots {
    std::array<SurfaceSlot, ChartBoundary::kMaxSurfaces> slots;
  };

  bool swapped_ = false;  // true: body0 is the relief plane, body1 the object
  std::uint32_t foot_triangle_ = 0xffffffffu;  // on a mesh: the triangle under the box last step
  bool by_pole_ = false;                       // on a mesh: its chart smooth by a pole of the uv (chartUnder)
  btPersistentManifold* groups_[kNormalGroups - 1] = {};
  std::unique_ptr<SurfaceSlots> surfaces_;
  // A ball with a bump map on the plane or the chart under it: how far out its basins lay last step.
  BallBasinHint ball_hint_;
  // How wide a gap a ball's further basins can close within the dispatch's step (closableGap; 0
  // outside a step).
  double closable_gap_m_ = 0.0;
  // Against a box or a ball with a bump map (box_ground.hpp): its surface as a mesh, the world's
  // (shared_ground_) or made on first need.
  const ObjectGround* shared_ground_ = nullptr;
  std::unique_ptr<ObjectGround> object_ground_;
};

// The shapes the relief algorithm understands, seen from the plane; nullopt for any other shape.
std::optional<Underside> undersideOf(const btCollisionShape& shape, const Eigen::Isometry3d& plane_from_object);

// Whether the relief algorithm takes this (object, mesh) pair: a box (textured or not), capsule,
// cylinder or ball with a bump map against a mesh with a chart attached (mesh_relief_chart.hpp: a
// relief's or a smooth one). Bullet's own convex-concave algorithm takes the rest (a plain
// sphere, a mesh without a chart).
bool reliefTakesMeshPair(const btCollisionShape& object, const btCollisionShape& mesh);

// Registers the algorithm for sphere, box, capsule and cylinder against CUSTOM_CONCAVE_SHAPE_TYPE,
// in both orders, and for box, capsule and cylinder against a triangle mesh (ours on a relief mesh). The create functions are static: they outlive any dispatcher.
void registerReliefCollision(btCollisionDispatcher& dispatcher);

}  // namespace thx::phys
