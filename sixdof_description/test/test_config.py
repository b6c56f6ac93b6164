"""kinematics.yaml, joint_limits.yaml and controllers.yaml: formats of docs/design.md, values consistent."""

import pytest
import yaml

ARM = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"]
GRIPPER = ["finger1_joint", "finger2_joint"]


def _load(pkg, name):
    with open(pkg / "config" / name, encoding="utf-8") as f:
        return yaml.safe_load(f)


def test_kinematics(pkg):
    assert _load(pkg, "kinematics.yaml") == {"arm": {
        "kinematics_solver": "analytic",
        "kinematics_solver_search_resolution": 0.005,
        "kinematics_solver_timeout": 0.005,
        "kinematics_solver_attempts": 3,
        "position_only_ik": False,
    }}


def test_joint_limits_match_the_urdf(pkg, robot):
    limits = _load(pkg, "joint_limits.yaml")["joint_limits"]
    assert list(limits) == ARM + GRIPPER
    urdf_joints = {j.name: j for j in robot.joints}
    for name, lim in limits.items():
        assert lim["has_velocity_limits"] is True and lim["has_acceleration_limits"] is True
        assert lim["max_velocity"] == pytest.approx(urdf_joints[name].limit.velocity)
        assert lim["max_acceleration"] > 0.0


def test_controllers(pkg):
    c = _load(pkg, "controllers.yaml")
    assert c["joint_state_controller"]["type"] == "joint_state_controller/JointStateController"
    for name, joints in (("arm_controller", ARM), ("gripper_controller", GRIPPER)):
        ctrl = c[name]
        assert ctrl["type"].endswith("/JointTrajectoryController")
        assert ctrl["joints"] == joints
        assert list(ctrl["gains"]) == joints
        for j in joints:
            assert ctrl["gains"][j]["p"] > 0 and ctrl["gains"][j]["d"] > 0 and ctrl["gains"][j]["i"] >= 0
            assert ctrl["constraints"][j]["goal"] > 0 and ctrl["constraints"][j]["trajectory"] >= 0
        assert ctrl["constraints"]["goal_time"] > 0
        assert ctrl["constraints"]["stopped_velocity_tolerance"] > 0
    listed = {entry["name"]: entry for entry in c["controller_list"]}
    assert set(listed) == {"arm_controller", "gripper_controller"}
    assert listed["arm_controller"]["joints"] == ARM and listed["gripper_controller"]["joints"] == GRIPPER
    for entry in listed.values():
        assert (entry["action_ns"], entry["type"]) == ("follow_joint_trajectory", "FollowJointTrajectory")
