"""moveit_msgs for scripts written against MoveIt: a Python namespace over sixdof_msgs (one implementation).

`from moveit_msgs.msg import RobotTrajectory` gives sixdof_msgs.msg.RobotTrajectory itself, so the types
moveit_commander takes and returns, the topics (move_group/display_planned_path) and the services all agree.
Only the Python names exist: there is no moveit_msgs message package for C++ or for rostopic.
"""
