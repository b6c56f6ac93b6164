#!/usr/bin/env bash
# Runs a command on its own virtual X display (rviz needs one; -a picks a free display number).
exec xvfb-run -a -s "-screen 0 1280x1024x24" "$@"
