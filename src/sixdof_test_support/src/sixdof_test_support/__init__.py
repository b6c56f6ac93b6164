"""Helpers the rostests of several packages share (sixdof_sim, sixdof_control, sixdof_planning, sixdof_tests)."""
