// What a built Surface holds (Surface::Impl), shared by the files of the
// surface stage: surface.cpp builds it, surface_evaluate.cpp evaluates it.
#pragma once

#include <optional>

#include <memory>
#include <vector>

#include "analysis/vertex_curvature.hpp"
#include "analysis/vertex_frames.hpp"
#include "bezier/bezier_surface.hpp"
#include "curvenet/surface.hpp"
#include "patches/patch.hpp"

namespace curvenet {
inline namespace v1 {

struct PatchLattice;

struct Surface::Impl {
  /// Where the patches' own coordinates have their origin in the world
  /// (zero unless the network lies far from the origin, see Surface::origin).
  Vec3 origin;
  std::vector<int> folded; ///< faces whose patch folds over itself (see patchFolds)
  /// Per face, where its patch passes through itself (patchSelfCrossing,
  /// in the patches' own coordinates); empty for the Bézier schemes.
  std::vector<std::optional<Vec3>> selfCrossings;
  /// Per face, its patch's 12-row fan lattice, where faces passing through
  /// each other are looked for (separateCrossingFaces); kept, so that a
  /// partial rebuild makes only its own faces' again. Gregory schemes only.
  std::vector<std::shared_ptr<const PatchLattice>> crossingLattices;
  Network network;
  SurfaceOptions options;
  bool referenceFences = false; ///< fence normals from the network's reference surface
  std::vector<VertexFrame> frames;
  std::vector<VertexCurvature> fitted;   ///< fitted from the curves (reported)
  std::vector<VertexCurvature> curvatures; ///< used by gregory-g2
  // Shared, immutable pieces: a partial rebuild (Surface::rebuildAfterEdit)
  // copies the Impl and keeps every piece its edit does not touch, so the
  // ribbons of unchanged patches keep pointing at live fences and curvatures.
  std::vector<std::shared_ptr<const NormalFence>> fences;
  /// The fence of faces[1] of a crease segment (isCreaseSegment), whose two
  /// faces take their own corners' normals at a crease vertex; null on every
  /// other segment, whose faces share `fences`.
  std::vector<std::shared_ptr<const NormalFence>> creaseFences;
  std::vector<std::shared_ptr<const TransversalCurvature>> edgeCurvatures; ///< gregory-g2
  /// gregory-g2 with G¹-measured edge curvature (master–slave, averaging,
  /// named masters, connection curves): the G¹ surface measured, kept so that
  /// an edit rebuilds only its faces near the edit.
  std::shared_ptr<const Surface> g1;
  /// gregory-g2 with MasterFaces::KeptG1: per face, whether it is a master
  /// face kept as its patch in `g1` (empty when no face is).
  std::vector<char> keptG1;
  std::vector<std::shared_ptr<const Patch>> patches;
  using DomainSide = DomainSideRange;
  /// Per face: the face side and side-parameter range of each domain side.
  std::vector<std::vector<DomainSide>> domainSides;
  /// bezier-g1 / coons-c0: the quintic patches (the transfinite members stay empty).
  std::shared_ptr<const bezier::BezierSurfaceData> bezier;
  std::vector<RepairMove> repairMoves; ///< SurfaceOptions::curves: the vertex repair made
  std::vector<std::string> repairSkipped; ///< RepairResult::skipped of that repair
};

/// The regular 4-sided domain of the bezier-g1 and coons-c0 faces, whose
/// quintic patches take (u, v) in the unit square inscribed in it.
const RegularDomain &squareDomain();

} // namespace v1
} // namespace curvenet
