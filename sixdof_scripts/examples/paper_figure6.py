#!/usr/bin/env python3
"""The paper's figure 6 script: link6 to the home pose, then to the target pose, through ArmDriver."""

import sys

from sixdof_commander import ArmDriver

armDriver = ArmDriver()  # noqa: N816 (the paper's name)

xyz = [0.366, -0.000, 0.286]
rpy = armDriver.rad([-180.000, 0.688, 179.995])
home_ok = armDriver.moveto_xyzrpy(xyz + rpy)  # home pose

xyz = [-0.568, 0.058, 0.396]
rpy = armDriver.rad([-133.151, 35.219, 1.048])
target_ok = home_ok and armDriver.moveto_xyzrpy(xyz + rpy)  # target pose

print(f"home pose: {'ok' if home_ok else 'FAILED'}, target pose: {'ok' if target_ok else 'FAILED'}")
if not target_ok:
    print(armDriver.last_failure, file=sys.stderr)
sys.exit(0 if target_ok else 1)
