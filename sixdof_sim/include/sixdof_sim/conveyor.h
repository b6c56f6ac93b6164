#pragma once
// Conveyors, object sources and sinks of a world (world file `conveyors:`, `sources:`, `sinks:`; worlds/README.md).
// The World builds each conveyor's belt as a static box object and moves what rests on it by a surface velocity
// (ConveyorSpec); after every physics step the sources spawn and the sinks delete (World::setConveyorSpeed and the
// state readers in world.h).

#include <string>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// Each checks one spec (names non-empty, finite poses, sizes > 0, a unit direction, friction >= 0, mass > 0,
// 0 < min_size <= max_size, a timing that is either period > 0 or 0 < min_interval <= max_interval, ...); the message
// names the entry and the field.
Result validateConveyorSpec(const ConveyorSpec& spec);
Result validateSourceSpec(const SourceSpec& spec);
Result validateSinkSpec(const SinkSpec& spec);

// The whole of a world's conveyors, sources and sinks: each spec valid, names unique (conveyors among the world's
// objects too, as their belts are objects), every source on a conveyor of the world. The message names the entry.
Result validateConveyors(const WorldSpec& world);

// The static box object of a conveyor's belt (named as the conveyor).
ObjectSpec beltObject(const ConveyorSpec& conveyor);

// The belt surface's velocity in the world frame.
Eigen::Vector3d beltVelocity(const ConveyorSpec& conveyor, double speed);

}  // namespace sixdof_sim
