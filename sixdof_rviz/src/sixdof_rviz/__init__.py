"""sixdof_rviz's Python side: screenshots of rviz and the colours its displays draw (sixdof_rviz.screenshots),
and rviz as a child process that survives Mesa's start-up deaths (sixdof_rviz.rviz_process)."""
