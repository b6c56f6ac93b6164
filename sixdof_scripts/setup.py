from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

# moveit_commander: MoveIt 1's Python API over sixdof_commander (moveit_msgs is the generated message package).
PACKAGES = ["sixdof_commander", "moveit_commander"]
setup(**generate_distutils_setup(packages=PACKAGES, package_dir={"": "src"}))
