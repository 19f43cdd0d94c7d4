#pragma once
/// Equations of motion per mode as printed in the thesis (eqs. 4.23, 4.35, 4.39, 4.42), with
/// the OCR's subscript and prime typos corrected (each correction is checked against the
/// generic assembly of kinematics.h in tests/reference/modes_test.cc), and the linearized
/// equations of section 4.3.3.
#include <array>

#include "reference/thesis/geometry.h"
#include "reference/thesis/kinematics.h"
#include "scene/mode.h"
#include "scene/scene.h"

namespace rockbench::reference {

/// Angular accelerations (theta1'', theta2'') in rad/s^2 of `mode` at state s under base
/// acceleration (xg'', yg'') in m/s^2. Mode 3: equal; mode 4: theta1'' = 0; rest: zeros.
/// For one block, mode 3 is Housner's equation (3.29) and theta2'' mirrors theta1''.
std::array<double, 2> ModeAccelerations(const Geometry& geo, Mode mode, const State& s,
                                        double xg_mps2, double yg_mps2,
                                        Equations equations = Equations::kNonlinear);
/// The same with the state's tilts already taken (TiltsOf(s)); the angle-difference formulas
/// give sin(theta - a) and cos(theta - a) from them and the geometry's constant angles.
std::array<double, 2> ModeAccelerations(const Geometry& geo, Mode mode, const State& s,
                                        const Tilts& tilts, double xg_mps2, double yg_mps2,
                                        Equations equations = Equations::kNonlinear);

}  // namespace rockbench::reference
