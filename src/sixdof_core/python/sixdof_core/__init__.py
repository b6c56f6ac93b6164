"""sixdof's ROS-free C++ core in Python: robot model, state, IK, collision scene, planning and time parameterization.

The classes and functions are the core's (src/sixdof_core/include/sixdof_core/*.h) under Python names: one model, no
ROS master needed, C++ speed (plans and long queries run without the GIL). Poses are 4x4 homogeneous numpy matrices,
joint values 1-D arrays, paths 2-D arrays (one row per point). Bad input raises ValueError (RobotModelError, SrdfError,
AnalyticIkUnsupported and SceneError are subclasses) with the core's message; IK, planning, Cartesian-path and
time-parameterization failures come back as results with a status and a message, as in the C++ API.

    import sixdof_core
    model = sixdof_core.RobotModel.from_files("robot.urdf", "robot.srdf")
    group = model.groups[0]
    ik = sixdof_core.create_ik_solver("numeric", model, group.name)
    result = ik.solve(sixdof_core.RobotState(model).link_pose(group.chain_tip))
"""

from sixdof_core import _sixdof_core

# The extension module's public names, re-exported; __init__.pyi declares them for type checkers.
__all__ = sorted(name for name in vars(_sixdof_core) if not name.startswith("_"))
globals().update({name: getattr(_sixdof_core, name) for name in __all__})
