#pragma once
/// Body kinds: what a body's state holds, named once. A body of a stack is of one kind (the
/// `shape` key of its [[block]] table, "block" when absent): the planar rigid block of the thesis
/// today. A kind lists its state's quantities; a history (scene/history.h) carries those of its
/// bodies, its files name them with BodyColumn, and the comparison judges the ones marked as
/// compared angles, so that a new kind of body (a cylinder rocking in three dimensions: tilt,
/// azimuth, spin) adds a kind, not a field to every result type.
#include <string>
#include <string_view>
#include <vector>

namespace rockbench {

/// One quantity of a body's state.
struct StateQuantity {
  /// The column stem: body k's column is the stem followed by k ("theta" -> "theta2").
  std::string stem;
  std::string unit;  ///< "rad", "rad/s", "m"
  /// Judged point by point against the reference as an angle (the local angle tolerance,
  /// docs/verdicts.md); otherwise carried and written, not judged as an angle.
  bool compared_angle = false;
};

/// A kind of body.
struct BodyKind {
  std::string shape;                 ///< the [[block]] table's `shape`
  std::vector<StateQuantity> state;  ///< the quantities of its state, in column order
  /// The mode column's text of a one-body stack whose contact is its face, one side's support
  /// or the other's (Contact's order), when the kind names them: a cylinder's "rest" and "rim".
  /// Empty: the planar block's names (ConfigurationName).
  std::vector<std::string> contact_names;
  /// The stem of the rate that events.csv carries before and after an event ("omega1_before").
  std::string event_rate_stem = "omega";
};

/// The planar rigid block (shape "block"): theta (rad, compared) and omega (rad/s). Its slip u
/// and lift z (m) are carried when the scene tracks them (Scene::tracks_slip_and_lift).
const BodyKind& PlanarBlockKind();

/// The solid circular cylinder rocking and rolling in 3-D on a rim point (shape "cylinder",
/// docs/three-d.md): tilt, azimuth, spin (rad); tilt_x = tilt cos(azimuth) and tilt_y = tilt
/// sin(azimuth) (rad, the compared angles: continuous through upright); the rates of tilt,
/// azimuth and spin (rad/s). Its mode is "rest" (on its face) or "rim" (on a rim point).
const BodyKind& CylinderKind();
inline constexpr std::string_view kCylinderShape = "cylinder";

/// The name of body `body`'s (1-based) quantity `stem`: BodyColumn("theta", 3) is "theta3".
/// Every per-body column of a file and key of a summary is made by it.
std::string BodyColumn(std::string_view stem, int body);

/// Adds a kind of body. Throws std::invalid_argument when its shape is taken or empty, or when
/// it has no quantity, an empty stem or the same stem twice.
void RegisterBodyKind(const BodyKind& kind);
/// The kind whose shape is `shape`, or null.
const BodyKind* FindBodyKind(std::string_view shape);
/// Every registered shape, in the order registered ("block" first).
std::vector<std::string> BodyShapes();

}  // namespace rockbench
