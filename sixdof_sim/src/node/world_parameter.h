#pragma once
// The world the simulator loaded, as the node's ~world parameter: what Python nodes and scripts read instead
// of parsing the world file again (sixdof_commander.sim_world, worlds/README.md "The ~world parameter").

#include <xmlrpcpp/XmlRpcValue.h>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// {name, objects: [...], bins: [...], cameras: [...]} with every default applied. Objects: name, shape
// (box: size; cylinder: radius, length; sphere: radius; mesh: mesh, scale), position, orientation [x, y, z, w],
// static, collision, table, bin, color [r, g, b, a]. Bins: name, color, position (bottom centre), yaw, size
// (outer footprint), wall_height, wall_thickness. Cameras: name, parent_link ('' = the world).
XmlRpc::XmlRpcValue worldParameter(const WorldSpec& world);

}  // namespace sixdof_sim
