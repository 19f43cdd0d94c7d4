#pragma once
/// Agreement of one compared quantity of one body with a reference given as a function of time,
/// for a body of any kind (scene/body_kind.h): the quantity is named by its stem and read from
/// the history with StateQuantityReader. The planar block's full comparison with the reference
/// model (local tolerance, predictability split, impacts) is CompareWithReference (agreement.h);
/// this is what any kind gets from its history alone, against a closed form or another run.
#include <functional>
#include <string_view>

#include "compare/agreement.h"
#include "scene/history.h"

namespace rockbench {

/// The error of body `body`'s (1-based) quantity `stem` in `engine` against `reference(t)` at
/// every engine sample up to `until_s`, on a constant tolerance (rad): the largest and RMS
/// error, the largest ratio to the tolerance and its time, the horizon (the first time the
/// error exceeds the tolerance; until_s when it never does), and the peaks of both. Throws
/// std::invalid_argument when the history has no such quantity or body.
AngleAgreement CompareBodyQuantity(const History& engine, std::string_view stem, int body,
                                   const std::function<double(double t_s)>& reference,
                                   double tolerance_rad, double until_s);

}  // namespace rockbench
