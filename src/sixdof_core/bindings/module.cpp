// The extension module sixdof_core._sixdof_core, which the Python package sixdof_core re-exports.
#include <ompl/util/Console.h>

#include "common.h"
#include "sixdof_core/ik_analytic.h"
#include "sixdof_core/srdf_writer.h"

namespace sixdof_core::python {

void bindExceptions(py::module_& m) {
  // Bad input raises ValueError, or one of these subclasses of it, with the core's message.
  py::register_exception<RobotModelError>(m, "RobotModelError", PyExc_ValueError).attr("__doc__") =
      "A malformed URDF or SRDF, an unreadable file or an unresolvable mesh.";
  py::register_exception<SrdfError>(m, "SrdfError", PyExc_ValueError).attr("__doc__") = "A malformed SRDF.";
  py::register_exception<AnalyticIkUnsupported>(m, "AnalyticIkUnsupported", PyExc_ValueError).attr("__doc__") =
      "A chain the closed-form IK does not fit; the message names the condition.";
  // The core throws std::out_of_range for an unknown link or joint name: bad input as well.
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const std::out_of_range& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace sixdof_core::python

PYBIND11_MODULE(_sixdof_core, m) {
  using namespace sixdof_core::python;
  m.doc() =
      "Bindings of sixdof's ROS-free C++ core (import them from the package sixdof_core): robot model, state, "
      "kinematics and IK, collision scene, planning, Cartesian paths, time parameterization and the setup "
      "assistant's collision matrix. Poses are 4x4 homogeneous matrices, joint values 1-D arrays, paths 2-D "
      "arrays (one row per point).";
  // OMPL's console at warnings and errors: its information lines on every plan would flood a notebook.
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  bindExceptions(m);
  bindModel(m);
  bindState(m);
  bindKinematics(m);
  bindCollision(m);
  bindPlanning(m);
  bindTrajectory(m);
  bindSetupAssistant(m);
  bindWireFormat(m);
}
