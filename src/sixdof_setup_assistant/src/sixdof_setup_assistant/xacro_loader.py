"""Robot descriptions from .urdf or .xacro files.

PyPI's xacro (2.x) resolves ``$(find pkg)`` through ROS 2's ament index only; this module supplies the ROS 1
resolution (rospkg over ROS_PACKAGE_PATH) and nothing else.
"""

from __future__ import annotations

import os
import shlex
import xml.dom.minidom

import rospkg


class DescriptionError(Exception):
    """A robot description that cannot be read or expanded; the message names the file."""


def is_xacro(path: str) -> bool:
    return path.endswith(".xacro")


def parse_xacro_args(text: str) -> dict[str, str]:
    """``"name:=value other:=value"`` -> mapping; raises DescriptionError on an item without ``:=``."""
    mappings: dict[str, str] = {}
    for item in shlex.split(text or ""):
        name, sep, value = item.partition(":=")
        if not sep or not name:
            raise DescriptionError(f"--xacro-args: '{item}' is not of the form name:=value")
        mappings[name] = value
    return mappings


def _install_ros1_find(rospack: rospkg.RosPack) -> None:
    import xacro.substitution_args as substitution_args

    def find(package: str) -> str:
        try:
            return rospack.get_path(package)
        except rospkg.ResourceNotFound:
            raise substitution_args.SubstitutionException(
                f"$(find {package}): no package '{package}' on ROS_PACKAGE_PATH") from None

    # `_find` looks the helper up by name at call time; ${find(...)} expressions use the eval table.
    substitution_args._eval_find = find
    substitution_args._eval_dict["find"] = find


def expand_xacro(path: str, mappings: dict[str, str] | None = None) -> str:
    """The URDF a xacro file expands to. Raises DescriptionError naming the file on any xacro error."""
    import xacro

    if not os.path.isfile(path):
        raise DescriptionError(f"{path}: no such file")
    _install_ros1_find(rospkg.RosPack())
    try:
        doc = xacro.process_file(path, mappings=dict(mappings or {}))
    except Exception as error:  # xacro raises XacroException, SubstitutionException, XML and eval errors
        message = " ".join(str(error).split()) or type(error).__name__
        raise DescriptionError(f"{path}: xacro: {message}") from None
    return doc.toprettyxml(indent="  ")


def load_description(path: str, mappings: dict[str, str] | None = None) -> str:
    """The URDF text of a .urdf (read as it is) or a .xacro (expanded with `mappings`)."""
    if is_xacro(path):
        return expand_xacro(path, mappings)
    if mappings:
        raise DescriptionError(f"{path}: --xacro-args given, but the file is not a .xacro")
    try:
        with open(path, encoding="utf-8") as file:
            text = file.read()
    except OSError as error:
        raise DescriptionError(f"{path}: cannot read: {error.strerror}") from None
    try:
        xml.dom.minidom.parseString(text)
    except Exception as error:
        raise DescriptionError(f"{path}: not well-formed XML: {error}") from None
    return text
