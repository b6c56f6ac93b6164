// The setup assistant's collision matrix: which link pairs never, always or by default collide, and the adjacent
// ones (MoveIt Setup Assistant's reasons), by sampling random states.
#include "sixdof_core/setup_assistant.h"

#include <pybind11/functional.h>

#include <functional>

#include "common.h"

namespace sixdof_core::python {

void bindSetupAssistant(py::module_& m) {
  py::enum_<DisableReason>(m, "DisableReason")
      .value("ADJACENT", DisableReason::kAdjacent, "Joined by a joint (across links without geometry).")
      .value("DEFAULT", DisableReason::kDefault, "Colliding at the default state.")
      .value("ALWAYS", DisableReason::kAlways, "Colliding in more than always_fraction of the samples.")
      .value("NEVER", DisableReason::kNever, "Colliding in none of the samples.")
      .value("GRIPPER", DisableReason::kGripper,
             "Two links of a gripper (an end effector's parent link and the links below it) colliding in some samples.");

  py::class_<CollisionMatrixOptions>(m, "CollisionMatrixOptions", "How the collision matrix is sampled.")
      .def(py::init([](std::size_t density, std::uint64_t seed, double always_fraction) {
             CollisionMatrixOptions o;
             o.density = density;
             o.seed = seed;
             o.always_fraction = always_fraction;
             return o;
           }),
           py::arg("density") = CollisionMatrixOptions().density, py::arg("seed") = 0,
           py::arg("always_fraction") = CollisionMatrixOptions().always_fraction)
      .def_readwrite("density", &CollisionMatrixOptions::density,
                     "Random samples (MoveIt's density: 1,000 low .. 100,000 high).")
      .def_readwrite("seed", &CollisionMatrixOptions::seed)
      .def_readwrite("always_fraction", &CollisionMatrixOptions::always_fraction);

  py::class_<ComputedPair>(m, "ComputedPair", "A link pair the setup assistant disables, and why.")
      .def_readonly("link1", &ComputedPair::link1, "The link first in model order.")
      .def_readonly("link2", &ComputedPair::link2)
      .def_readonly("reason", &ComputedPair::reason)
      .def_property_readonly(
          "reason_name", [](const ComputedPair& p) { return reasonName(p.reason); },
          "The SRDF's reason: 'Adjacent', 'Default', 'Always', 'Never' or 'Gripper'.")
      .def_readonly("colliding_samples", &ComputedPair::colliding_samples);

  py::class_<DisabledCollisions>(m, "DisabledCollisions", "The computed collision matrix and its counts.")
      .def_readonly("disabled", &DisabledCollisions::disabled, "By reason, then by the links' model order.")
      .def_readonly("link_pairs", &DisabledCollisions::link_pairs, "Pairs of links that both have geometry.")
      .def_readonly("samples", &DisabledCollisions::samples)
      .def_readonly("pair_checks", &DisabledCollisions::pair_checks);

  m.def(
      "compute_disabled_collisions",
      [](const ModelPtr& model, CollisionMatrixOptions options,
         const std::optional<std::function<void(std::size_t, std::size_t)>>& progress) {
        if (progress) {
          options.progress = [&progress](std::size_t done, std::size_t total) {
            py::gil_scoped_acquire acquire;
            (*progress)(done, total);
          };
        }
        py::gil_scoped_release release;
        return computeDisabledCollisions(model, options);
      },
      py::arg("model"), py::arg("options") = CollisionMatrixOptions(), py::arg("progress") = py::none(),
      "The setup assistant's disabled-collision matrix of every pair of links with geometry. progress(done, "
      "total) is called while sampling. Raises ValueError on density 0 or always_fraction outside (0, 1).");
  m.def(
      "adjacent_link_pairs", [](const ModelPtr& model) { return adjacentLinkPairs(*model); }, py::arg("model"),
      "Pairs of links with geometry joined by a joint once links without geometry are collapsed.");
}

}  // namespace sixdof_core::python
