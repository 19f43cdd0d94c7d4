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
///   the value. In a cylinder scene with a [base.transverse] component: the x component alone.
/// - `base.pga_resultant_g`: both horizontal components ([base.horizontal] and
///   [base.transverse]) scaled by one factor so that the peak of their resultant over the run,
///   max over t of sqrt(a_x(t)^2 + a_y(t)^2) in g0 (MeasureResultantPga), equals the value; the
///   ratio of the two components is kept. Refused beside `base.horizontal.pga_g` or `pgv_mps`.
///
/// With `zip_with = "KEY"` an axis takes the value index of the earlier axis KEY in every
/// member (its values paired with KEY's, one to one: a record's two components) instead of
/// adding a dimension to the product.
struct StudyAxis {
  std::string key;
  std::vector<AxisValue> values;
  bool derived = false;
  int line = 0;  ///< the line of its [[axis]] table in the study file (messages)
  /// The index of the earlier axis whose value index this one takes (`zip_with`); -1: none.
  int zip_with = -1;
};

/// Most runs (members x engines) a study may have. A run takes a worker between a few
/// milliseconds and minutes; members.csv holds about 500 bytes a row, and its last rewrite
/// (MembersJournal::Finish) holds the file about three times in memory: a million runs make a
/// 0.5 GB file and about 1.5 GB at the end, within the default memory budget of 2 GiB
/// (docs/ensemble.md, "Limits").
inline constexpr int64_t kMaxStudyRuns = 1000000;
/// Most members of a study (each has at least one run).
inline constexpr int64_t kMaxStudyMembers = kMaxStudyRuns;

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
  int scene_line = 0;           ///< the line of `scene` (messages)
  int set_line = 0;             ///< the line of `set` (messages)
  /// Impacts slower than this are not counted (CompareOptions::min_impact_rate_radps).
  double min_impact_rate_radps = 0.02;
  /// Blocks of every member's stack (member 0's: no key an axis or `set` takes changes it).
  int blocks = 1;
  /// Member 0's body is a cylinder rocking in 3-D (docs/three-d.md): every member's must be,
  /// every run is the reference or an engine that builds cylinders, and members.csv has the
  /// cylinder's columns (MembersCsvHeader).
  bool cylinder = false;

  int64_t member_count() const;
  /// Member i's value index on every axis.
  std::vector<int> ValueIndices(int64_t member) const;
};

/// Which members' scenes LoadStudy builds to check the study.
enum class StudyCheck {
  /// Every value of every axis: with `combine = "product"` the members that differ from member
  /// 0 on one axis (each value meets the others' first values), with "zip" every member. A
  /// value the scene refuses is an error of the study, before anything runs.
  kEveryValue,
  /// Member 0 only (a worker: its parent checked the rest).
  kFirstMember,
};

/// Reads a study file. Errors (SceneError) name the file, line and key and what was expected:
/// unknown keys, an engine not registered or not built, an engine that does not build the base
/// scene's body (box2d for a cylinder), an empty axis, a scene key or value
/// the scene refuses (naming the axis and value, or the `set` entry, that gave it), a study of
/// more than kMaxStudyRuns runs, control characters or an impossible path in a file name.
StudyDef LoadStudy(const std::filesystem::path& path, StudyCheck check = StudyCheck::kEveryValue);
/// LoadStudy on a study file's text already in memory; `path` names it and anchors the
/// relative scene path.
StudyDef ParseStudy(const std::string& text, const std::filesystem::path& path,
                    StudyCheck check = StudyCheck::kEveryValue);

/// Member i's scene: the base scene with the study's overrides and member i's axis values.
/// Throws SceneError when that member's scene is invalid: "STUDY:LINE: axis KEY = VALUE
/// (member i: every axis's value): the scene's message", or "STUDY:LINE: set \"ENTRY\": ..."
/// or "STUDY:LINE: scene ...: ..." when the `set` entry or the base scene itself is at fault
/// (the culprit is found by building the scene again with the overrides added one at a time).
Scene MemberScene(const StudyDef& study, int64_t member);

/// "member 3: key1 = v1, key2 = v2": a member and its axis values (each cut to an excerpt),
/// for messages and rows.
std::string MemberText(const StudyDef& study, int64_t member);

}  // namespace rockbench
