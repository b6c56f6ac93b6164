from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

# sixdof_core: the Python bindings' package (the extension module _sixdof_core is built by CMake, its stubs and
# py.typed ship as package data).
setup(**generate_distutils_setup(packages=["sixdof_core"], package_dir={"": "python"},
                                 package_data={"sixdof_core": ["py.typed", "*.pyi"]}))
