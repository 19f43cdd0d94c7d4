#pragma once
/// The pivot-chain placement of the blocks moved to the scene vocabulary, where the engines and
/// the renders share it: scene/stack_pose.h (PlanarPose, StackPlacement, PivotSide, PlaceStack,
/// Corners). This header only forwards there, for the code that still includes it
/// (tests/engines/monitor_test.cc); include scene/stack_pose.h instead.
#include "scene/stack_pose.h"
