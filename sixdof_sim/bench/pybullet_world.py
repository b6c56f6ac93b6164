#!/usr/bin/env python3
"""Repeats a sim_bench run in PyBullet and prints its timings as JSON (benchmark only, never a runtime part).

    pybullet_world.py SCENARIO.json [--sleep]

SCENARIO.json is what `sim_bench --scenario` writes: the URDF, the physics settings, every object, the joints
and their sinusoids, the number of steps. The same work in PyBullet, driven as its users drive it: the URDF
through loadURDF (inertias from the file, fixed links merged into their parent, as the simulator does), the
objects as maximal-coordinate bodies (btRigidBody, as ours), and every step one setJointMotorControlArray call
(POSITION_CONTROL: the same btMultiBodyJointMotor servo, gains and effort bounds as the simulator's) and one
stepSimulation. Physics settings the simulator sets (src/world/world_robot.cpp, world_objects.cpp) are given to
PyBullet where it has them; --sleep also lets resting objects sleep (PyBullet's default keeps them awake).

Runs in the benchmark venv that scripts/bench.sh makes (pybullet pinned in scripts/requirements-bench.txt)."""

import argparse
import functools
import json
import math
import re
import sys
import tempfile
import time
from importlib.metadata import version
from pathlib import Path

import pybullet as p

# The simulator's settings that are not in the scenario (src/world/world_impl.h, world_robot.cpp).
ERP = 0.2  # m_erp and m_erp2
SPLIT_IMPULSE_PENETRATION = -0.0005
RESIDUAL_THRESHOLD = 1e-7
ROUND_ROLLING_FRICTION = 1e-4  # cylinders, spheres and meshes
SPINNING_FRICTION = 1e-4
GEAR_ERP = 0.2
GEAR_MAX_FORCE = 1000.0


def resolve(uri: str, roots: list[str]) -> str:
    """A mesh URI as the simulator resolves it: package://<pkg>/<path> is <root>/<pkg>/<path>, or <root>/<path>
    when the root is the package directory itself; the first that exists."""
    if not uri.startswith("package://"):
        return uri.removeprefix("file://")
    package, _, rest = uri[len("package://") :].partition("/")
    for root in map(Path, roots):
        for candidate in (root / package / rest, root / rest if root.name == package else None):
            if candidate is not None and candidate.is_file():
                return str(candidate)
    raise FileNotFoundError(f"{uri} not found under {roots}")


def pybullet_urdf(scenario: dict) -> str:
    """The URDF with package:// resolved, and links without <inertial> given a massless one: the simulator treats
    them as massless, PyBullet would give each 1 kg."""
    text = Path(scenario["urdf"]).read_text()
    text = re.sub(r'filename="([^"]+)"', lambda m: f'filename="{resolve(m.group(1), scenario["package_roots"])}"', text)
    massless = '<inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>'
    text = re.sub(r'<link name="([^"]+)"\s*/>', rf'<link name="\1">{massless}</link>', text)

    def add_inertial(match: re.Match) -> str:
        body = match.group(2)
        return match.group(0) if "<inertial>" in body else f"{match.group(1)}{body}{massless}</link>"

    text = re.sub(r'(<link name="[^"]+">)(.*?)</link>', add_inertial, text, flags=re.DOTALL)
    out = tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False)
    out.write(text)
    out.close()
    return out.name


def collision_shape(obj: dict, roots: list[str]) -> int:
    if obj["shape"] == "box":
        return p.createCollisionShape(p.GEOM_BOX, halfExtents=[s / 2.0 for s in obj["size"]])
    if obj["shape"] == "cylinder":
        return p.createCollisionShape(p.GEOM_CYLINDER, radius=obj["radius"], height=obj["length"])
    if obj["shape"] == "sphere":
        return p.createCollisionShape(p.GEOM_SPHERE, radius=obj["radius"])
    return p.createCollisionShape(p.GEOM_MESH, fileName=resolve(obj["mesh"], roots), meshScale=obj["scale"])


def build(scenario: dict, sleep: bool) -> tuple[int, list[int], list[dict]]:
    """The world in PyBullet; returns the robot, its actuated joint indices and their commands (scenario joints)."""
    dt = scenario["time_step"]
    p.setPhysicsEngineParameter(
        fixedTimeStep=dt,
        numSubSteps=0,
        numSolverIterations=scenario["solver_iterations"],
        solverResidualThreshold=RESIDUAL_THRESHOLD,
        useSplitImpulse=1,
        splitImpulsePenetrationThreshold=SPLIT_IMPULSE_PENETRATION,
        erp=ERP,
        contactERP=ERP,
        frictionERP=ERP,
        globalCFM=0.0,
        enableConeFriction=0,
        deterministicOverlappingPairs=1,
    )
    p.setGravity(*scenario["gravity"])
    flags = p.URDF_USE_INERTIA_FROM_FILE | p.URDF_MERGE_FIXED_LINKS
    robot = p.loadURDF(pybullet_urdf(scenario), useFixedBase=True, flags=flags)
    index = {p.getJointInfo(robot, j)[1].decode(): j for j in range(p.getNumJoints(robot))}
    joints = scenario["joints"]
    for joint in joints:
        if joint["mimic_of"]:
            gear = p.createConstraint(
                robot,
                index[joint["mimic_of"]],
                robot,
                index[joint["name"]],
                p.JOINT_GEAR,
                [0, 0, 0],
                [0, 0, 0],
                [0, 0, 0],
            )
            p.changeConstraint(
                gear,
                gearRatio=-joint["mimic_multiplier"],
                relativePositionTarget=joint["mimic_offset"],
                erp=GEAR_ERP,
                maxForce=GEAR_MAX_FORCE,
            )
    ground = scenario["ground"]
    if ground["enabled"]:
        plane = p.createMultiBody(0, p.createCollisionShape(p.GEOM_PLANE), basePosition=[0, 0, ground["z"]])
        p.changeDynamics(plane, -1, lateralFriction=ground["friction"], restitution=ground["restitution"])
    for obj in scenario["objects"]:
        if not obj["collision"]:
            continue  # a visual-only marker: no collision shape, nothing for the simulator to do either
        mass = 0.0 if obj["static"] else obj["mass"]
        body = p.createMultiBody(
            mass,
            collision_shape(obj, scenario["package_roots"]),
            basePosition=obj["position"],
            baseOrientation=obj["quaternion"],
            useMaximalCoordinates=True,
        )
        rolling = 0.0 if obj["shape"] == "box" else ROUND_ROLLING_FRICTION
        p.changeDynamics(
            body,
            -1,
            lateralFriction=obj["friction"],
            restitution=obj["restitution"],
            rollingFriction=rolling,
            spinningFriction=SPINNING_FRICTION,
        )
        if sleep and not obj["static"]:
            p.changeDynamics(body, -1, activationState=p.ACTIVATION_STATE_ENABLE_SLEEPING)
    return robot, [index[j["name"]] for j in joints], joints


def commands(scenario: dict, joints: list[dict]) -> list[tuple[list[float], list[float]]]:
    """Targets and target velocities of every actuated joint at every step, computed before the timed loop (the
    simulator computes them in C++ at a negligible cost): the swings, mimic joints following their master."""
    out = []
    for i in range(scenario["steps"]):
        t = i * scenario["time_step"]
        position, velocity = {}, {}
        for s in scenario["swings"]:
            phase = s["omega"] * t + s["phase"]
            position[s["joint"]] = s["centre"] + s["amplitude"] * math.sin(phase)
            velocity[s["joint"]] = s["amplitude"] * s["omega"] * math.cos(phase)
        for j in joints:
            if j["mimic_of"]:
                position[j["name"]] = j["mimic_multiplier"] * position[j["mimic_of"]] + j["mimic_offset"]
                velocity[j["name"]] = j["mimic_multiplier"] * velocity[j["mimic_of"]]
        out.append(([position[j["name"]] for j in joints], [velocity[j["name"]] for j in joints]))
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", type=Path)
    parser.add_argument("--sleep", action="store_true", help="let resting objects sleep")
    args = parser.parse_args()
    try:
        scenario = json.loads(args.scenario.read_text())
    except (OSError, ValueError) as err:
        print(f"pybullet_world.py: {err}", file=sys.stderr)
        return 2
    p.connect(p.DIRECT)
    robot, indices, joints = build(scenario, args.sleep)
    by_name = {j["name"]: j for j in joints}
    forces = [
        min(j["max_effort"], by_name[j["mimic_of"]]["max_effort"]) if j["mimic_of"] else j["max_effort"] for j in joints
    ]
    kp = [scenario["position_gain"] * scenario["time_step"]] * len(joints)
    # One call sets every joint's servo (functools.partial is C code: no Python frame per call).
    control = functools.partial(
        p.setJointMotorControlArray,
        robot,
        indices,
        p.POSITION_CONTROL,
        forces=forces,
        positionGains=kp,
        velocityGains=[1.0] * len(joints),
    )
    targets = commands(scenario, joints)
    wall0, cpu0 = time.perf_counter(), time.process_time()
    for target, target_velocity in targets:
        control(targetPositions=target, targetVelocities=target_velocity)
        p.stepSimulation()
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    # The control call alone (no step): how much of a PyBullet step is its Python API.
    calls = 5000
    call0 = time.perf_counter()
    for _ in range(calls):
        control(targetPositions=target, targetVelocities=target_velocity)
    control_call = (time.perf_counter() - call0) / calls
    print(
        json.dumps(
            {
                "pybullet": version("pybullet"),
                "steps": len(targets),
                "wall": wall,
                "cpu": cpu,
                "control_call": control_call,
            }
        )
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
