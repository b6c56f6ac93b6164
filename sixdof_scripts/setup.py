from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

# moveit_commander and moveit_msgs: MoveIt 1's Python names over sixdof_commander and sixdof_msgs.
PACKAGES = ["sixdof_commander", "moveit_commander", "moveit_msgs", "moveit_msgs.msg", "moveit_msgs.srv"]
setup(**generate_distutils_setup(packages=PACKAGES, package_dir={"": "src"}))
