#!/usr/bin/env python3
"""A MoveIt-tutorial-style script (in the manner of MoveIt 1's "Move Group Python Interface" tutorial, written for
sixdof): only moveit_commander, moveit_msgs, geometry_msgs and rospy, so it runs unchanged on MoveIt 1 given
the robot-specific names below (group, hand group, the box's offset from the end-effector link).

Joint goal, pose goal, Cartesian path, display, execute, then a box added, attached, detached and removed.
Exit status 0 when every step succeeded, 1 otherwise.

    rosrun sixdof_scripts moveit_tutorial.py [--group arm] [--hand gripper] [--box-z 0.113]
"""

import argparse
import copy
import sys
import time

import geometry_msgs.msg
import moveit_commander
import moveit_msgs.msg
import rospy
from moveit_commander.conversions import pose_to_list


def all_close(goal, actual, tolerance):
    """True when every value of goal and actual (lists, Pose or PoseStamped) is within tolerance."""
    if isinstance(goal, geometry_msgs.msg.PoseStamped):
        return all_close(goal.pose, actual.pose, tolerance)
    if isinstance(goal, geometry_msgs.msg.Pose):
        goal, actual = pose_to_list(goal)[:3], pose_to_list(actual)[:3]
    return all(abs(g - a) <= tolerance for g, a in zip(goal, actual, strict=True))


class Tutorial:
    def __init__(self, group_name, hand_group, box_z):
        self.robot = moveit_commander.RobotCommander()
        self.scene = moveit_commander.PlanningSceneInterface()
        self.move_group = moveit_commander.MoveGroupCommander(group_name)
        self.move_group.set_max_velocity_scaling_factor(0.5)
        self.move_group.set_max_acceleration_scaling_factor(0.5)
        self.display_trajectory_publisher = rospy.Publisher(
            "/move_group/display_planned_path", moveit_msgs.msg.DisplayTrajectory, queue_size=20
        )
        self.hand_group = hand_group
        self.box_z = box_z
        self.box_name = "tutorial_box"
        self.eef_link = self.move_group.get_end_effector_link()
        print("planning frame:", self.move_group.get_planning_frame())
        print("end effector link:", self.eef_link)
        print("groups:", self.robot.get_group_names())

    def go_to_joint_state(self):
        joint_goal = self.move_group.get_current_joint_values()
        joint_goal[0] += 0.3
        self.move_group.go(joint_goal, wait=True)
        self.move_group.stop()
        return all_close(joint_goal, self.move_group.get_current_joint_values(), 0.01)

    def go_to_pose_goal(self):
        pose_goal = self.move_group.get_current_pose().pose
        pose_goal.position.z -= 0.05
        self.move_group.set_pose_target(pose_goal)
        success = self.move_group.go(wait=True)
        self.move_group.stop()
        self.move_group.clear_pose_targets()
        return success and all_close(pose_goal, self.move_group.get_current_pose().pose, 0.01)

    def plan_cartesian_path(self, scale=1.0):
        waypoints = []
        wpose = self.move_group.get_current_pose().pose
        wpose.position.z += scale * 0.05
        wpose.position.y += scale * 0.05
        waypoints.append(copy.deepcopy(wpose))
        wpose.position.x -= scale * 0.05
        waypoints.append(copy.deepcopy(wpose))
        wpose.position.y -= scale * 0.05
        waypoints.append(copy.deepcopy(wpose))
        (plan, fraction) = self.move_group.compute_cartesian_path(waypoints, 0.01)
        return plan, fraction

    def display_trajectory(self, plan):
        display_trajectory = moveit_msgs.msg.DisplayTrajectory()
        display_trajectory.trajectory_start = self.robot.get_current_state()
        display_trajectory.trajectory.append(plan)
        self.display_trajectory_publisher.publish(display_trajectory)

    def execute_plan(self, plan):
        return self.move_group.execute(plan, wait=True)

    def wait_for_state_update(self, box_is_known=False, box_is_attached=False, timeout=10):
        start = time.time()
        while time.time() - start < timeout and not rospy.is_shutdown():
            attached_objects = self.scene.get_attached_objects([self.box_name])
            is_attached = len(attached_objects.keys()) > 0
            is_known = self.box_name in self.scene.get_known_object_names()
            if box_is_attached == is_attached and box_is_known == is_known:
                return True
            rospy.sleep(0.1)
        return False

    def add_box(self):
        box_pose = geometry_msgs.msg.PoseStamped()
        box_pose.header.frame_id = self.eef_link
        box_pose.pose.orientation.w = 1.0
        box_pose.pose.position.z = self.box_z
        self.scene.add_box(self.box_name, box_pose, size=(0.02, 0.02, 0.02))
        return self.wait_for_state_update(box_is_known=True)

    def attach_box(self):
        touch_links = self.robot.get_link_names(group=self.hand_group)
        self.scene.attach_box(self.eef_link, self.box_name, touch_links=touch_links)
        return self.wait_for_state_update(box_is_attached=True, box_is_known=False)

    def detach_box(self):
        self.scene.remove_attached_object(self.eef_link, name=self.box_name)
        return self.wait_for_state_update(box_is_known=True, box_is_attached=False)

    def remove_box(self):
        self.scene.remove_world_object(self.box_name)
        return self.wait_for_state_update(box_is_attached=False, box_is_known=False)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--group", default="arm", help="planning group to move")
    parser.add_argument("--hand", default="gripper", help="group whose links may touch the attached box")
    parser.add_argument("--box-z", type=float, default=0.113, help="box offset along the end-effector link's z (m)")
    args = parser.parse_args(rospy.myargv()[1:])
    moveit_commander.roscpp_initialize(sys.argv)
    rospy.init_node("moveit_tutorial", anonymous=True)
    tutorial = Tutorial(args.group, args.hand, args.box_z)
    failed = []

    def check(name, ok):
        print(f"{name}: {'ok' if ok else 'FAILED'}")
        if not ok:
            failed.append(name)

    check("joint goal", tutorial.go_to_joint_state())
    check("pose goal", tutorial.go_to_pose_goal())
    plan, fraction = tutorial.plan_cartesian_path()
    check(f"Cartesian path ({fraction * 100:.1f}% achieved)", fraction == 1.0)
    tutorial.display_trajectory(plan)
    check("execute", tutorial.execute_plan(plan))
    check("add box", tutorial.add_box())
    check("attach box", tutorial.attach_box())
    check("detach box", tutorial.detach_box())
    check("remove box", tutorial.remove_box())
    moveit_commander.roscpp_shutdown()
    print("tutorial:", "FAILED " + ", ".join(failed) if failed else "all steps succeeded")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
