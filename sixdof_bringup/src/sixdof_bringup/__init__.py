"""sixdof_bringup: helper logic of the bringup nodes (scene mirroring, trajectory plots)."""
