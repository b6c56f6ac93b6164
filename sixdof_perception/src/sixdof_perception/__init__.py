"""sixdof_perception: objects on the table from an RGB-D camera's organized depth cloud (detection.py, pure
numpy), stable ids across frames (tracking.py) and what the simulator's world tells (world.py)."""
