"""urdf/sixdof.urdf of the designed arm."""

from __future__ import annotations

from sixdof_description.formatting import HEADER, exact, fmt, vec
from sixdof_description.robot_design import ARM_JOINTS, JOINT_LINKS, ROOT_LINK, Robot

PACKAGE = "sixdof_description"

# The paper's gazebo_grasp_fix settings: the URDF's plugin block and the setup assistant's answers (grasping.yaml).
GRASP_FIX = {"palm_link": "link6", "gripper_links": ["finger1", "finger2"], "forces_angle_tolerance": 100,
             "update_rate": 4, "grip_count_threshold": 4, "max_grip_count": 8, "release_tolerance": 0.005,
             "disable_collisions_on_attach": False}

_GRIPPER_LINKS = "".join(f"        <gripper_link>{link}</gripper_link>\n" for link in GRASP_FIX["gripper_links"])
GRASP_FIX_BLOCK = f"""  <gazebo>
    <plugin name="gazebo_grasp_fix" filename="libgazebo_grasp_fix.so">
      <arm>
        <arm_name>arm</arm_name>
        <palm_link>{GRASP_FIX["palm_link"]}</palm_link>
{_GRIPPER_LINKS}      </arm>
      <forces_angle_tolerance>{GRASP_FIX["forces_angle_tolerance"]}</forces_angle_tolerance>
      <update_rate>{GRASP_FIX["update_rate"]}</update_rate>
      <grip_count_threshold>{GRASP_FIX["grip_count_threshold"]}</grip_count_threshold>
      <max_grip_count>{GRASP_FIX["max_grip_count"]}</max_grip_count>
      <release_tolerance>{GRASP_FIX["release_tolerance"]}</release_tolerance>
      <disable_collisions_on_attach>{str(GRASP_FIX["disable_collisions_on_attach"]).lower()}</disable_collisions_on_attach>
      <contact_topic>__default_topic__</contact_topic>
    </plugin>
  </gazebo>
"""


def _material_name(rgba) -> str:
    return "rgba_" + "_".join(f"{int(round(c * 100)):03d}" for c in rgba)


def render_urdf(robot: Robot, meshes: bool = True) -> str:
    """The URDF; without meshes (no <visual>, no <collision>) it is the kinematic and inertial model alone, which
    sixdof_core reads before the meshes are written (core_model.py)."""
    d = robot.design
    colours = d["colours"]
    out = ['<?xml version="1.0"?>', f"<!-- {HEADER} -->", f'<robot name="{robot.name}">']
    materials = []
    for name in robot.link_names:
        mat = _material_name(colours[name])
        if mat not in materials:
            materials.append(mat)
            out.append(f'  <material name="{mat}"><color rgba="{vec(colours[name])}"/></material>')
    for name in robot.link_names:
        link = robot.links[name]
        i = link.inertia
        mat = _material_name(colours[name])
        # The root link is fixed to the world: no <inertial> (KDL cannot use one there and warns, as every
        # robot_state_publisher would), as MoveIt users write their root links.
        inertial = [] if name == ROOT_LINK else [
            "    <inertial>",
            f'      <origin xyz="{vec(link.com)}" rpy="0 0 0"/>',
            f'      <mass value="{fmt(link.mass)}"/>',
            f'      <inertia ixx="{fmt(i[0, 0])}" ixy="{fmt(i[0, 1])}" ixz="{fmt(i[0, 2])}" '
            f'iyy="{fmt(i[1, 1])}" iyz="{fmt(i[1, 2])}" izz="{fmt(i[2, 2])}"/>',
            "    </inertial>",
        ]
        geometry = [
            "    <visual>",
            '      <origin xyz="0 0 0" rpy="0 0 0"/>',
            f'      <geometry><mesh filename="package://{PACKAGE}/meshes/visual/{name}.stl"/></geometry>',
            f'      <material name="{mat}"/>',
            "    </visual>",
            "    <collision>",
            '      <origin xyz="0 0 0" rpy="0 0 0"/>',
            f'      <geometry><mesh filename="package://{PACKAGE}/meshes/collision/{name}.stl"/></geometry>',
            "    </collision>",
        ]
        out += [f'  <link name="{name}">', *(geometry if meshes else []), *inertial, "  </link>"]
    out.append('  <link name="tcp"/>')
    for spec in robot.joints:
        parent, child = JOINT_LINKS[spec.name]
        out.append(f'  <joint name="{spec.name}" type="{spec.joint_type}">')
        out.append(f'    <parent link="{parent}"/>')
        out.append(f'    <child link="{child}"/>')
        out.append(f'    <origin xyz="{vec(spec.xyz, exact)}" rpy="{vec(spec.rpy, exact)}"/>')
        if spec.joint_type != "fixed":
            p = robot.joint_params[spec.name]
            out.append(f'    <axis xyz="{vec(spec.axis, exact)}"/>')
            out.append(f'    <limit lower="{exact(spec.lower)}" upper="{exact(spec.upper)}" '
                       f'velocity="{fmt(p["velocity"])}" effort="{fmt(p["effort"])}"/>')
            out.append(f'    <dynamics damping="{fmt(p["damping"])}" friction="{fmt(p["friction"])}"/>')
        if spec.name == "finger2_joint":
            out.append('    <mimic joint="finger1_joint" multiplier="1" offset="0"/>')
        out.append("  </joint>")
    for name in (*ARM_JOINTS, *robot.tool_joints):
        out += [
            f'  <transmission name="{name}_transmission">',
            "    <type>transmission_interface/SimpleTransmission</type>",
            f'    <joint name="{name}"><hardwareInterface>hardware_interface/PositionJointInterface'
            "</hardwareInterface></joint>",
            f'    <actuator name="{name}_motor"><mechanicalReduction>1</mechanicalReduction></actuator>',
            "  </transmission>",
        ]
    friction = d["friction"]
    for name in robot.link_names:
        f = friction.get(name, friction["default"])
        out.append(f'  <gazebo reference="{name}"><mu1>{fmt(f["mu1"])}</mu1><mu2>{fmt(f["mu2"])}</mu2></gazebo>')
    if robot.tool_joints:  # the suction cup's simulator settings are its grasping.yaml's `suction`
        out.append(GRASP_FIX_BLOCK.rstrip("\n"))
    out.append("</robot>")
    return "\n".join(out) + "\n"
