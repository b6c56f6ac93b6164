"""sixdof_rviz's Python side: screenshots of rviz and the colours its displays draw (sixdof_rviz.screenshots)."""
