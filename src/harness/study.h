#pragma once
/// A study: a base scene, the runs to make of it ("reference" and engines) and the axes that
/// make its members. Member i's scene depends only on the study file and i, so any process
/// (a worker, an MPI rank) that reads the same study builds the same member. See
/// docs/ensemble.md for the file's schema.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace rockbench {

/// One value of an axis: what members.csv prints and what the scene gets.
struct AxisValue {
  std::string text;     ///< as printed in members.csv (numbers: shortest round-trip text)
  std::string toml;     ///< as a TOML value for the scene override (strings quoted)
  double number = 0.0;  ///< numeric value (derived axes need one)
  bool is_number = false;
};

/// One axis: a scene key (as --set takes it) or a derived key (below), and its values.
///
/// Derived keys (applied after the scene is read, in this order):
/// - `size_factor`: every length of both blocks (width, height, depth) times the factor; a mass
///   given in kg times its cube (geometrically similar blocks of the same material).
/// - `pulse.frequency_ratio`: base.horizontal.frequency_hz = ratio * p / (2 pi), with block 1's
///   p = sqrt(3 g / (4 R)), R its half-diagonal and g the run's gravity (Zhang & Makris 2001).
/// - `pulse.amplitude_ratio`: base.horizontal.amplitude_g = ratio * g tan(alpha1) / g0, with
///   alpha1 = atan(B1 / H1) (the uplift acceleration of block 1 alone).
/// - `base.horizontal.pga_g` / `base.horizontal.pgv_mps`: the horizontal component scaled (its
///   `scale` multiplied) so that its PGA (in g0 = 9.80665 m/s^2) or PGV over the run equals
///   the value.
struct StudyAxis {
  std::string key;
  std::vector<AxisValue> values;
  bool derived = false;
};

/// How the axes make members.
enum class StudyCombine {
  kProduct,  ///< the Cartesian product, the last axis varying fastest
  kZip,      ///< member i takes value i of every axis (all axes of one length)
};

struct StudyDef {
  std::filesystem::path path;          ///< the study file
  std::string title;                   ///< optional free text
  std::filesystem::path scene_path;    ///< the base scene (resolved against the study's folder)
  std::vector<std::string> overrides;  ///< `set = [...]`: applied to every member
  std::vector<std::string> engines;    ///< "reference" and registered engine names, in order
  std::vector<StudyAxis> axes;
  StudyCombine combine = StudyCombine::kProduct;
  double wall_limit_s = 600.0;  ///< one run (member, engine) is killed after this wall time
  /// Impacts slower than this are not counted (CompareOptions::min_impact_rate_radps).
  double min_impact_rate_radps = 0.02;

  int64_t member_count() const;
  /// Member i's value index on every axis.
  std::vector<int> ValueIndices(int64_t member) const;
};

/// Reads a study file. Errors (SceneError) name the file, line and key and what was expected:
/// unknown keys, an engine not registered or not built, an empty axis, a scene key the scene
/// schema refuses (the base scene is read with every axis's first value to check).
StudyDef LoadStudy(const std::filesystem::path& path);
/// LoadStudy on a study file's text already in memory; `path` names it and anchors the
/// relative scene path.
StudyDef ParseStudy(const std::string& text, const std::filesystem::path& path);

/// Member i's scene: the base scene with the study's overrides and member i's axis values.
/// Throws SceneError when that member's scene is invalid (the row says so).
Scene MemberScene(const StudyDef& study, int64_t member);

}  // namespace rockbench
