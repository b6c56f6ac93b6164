# sixdof_control_ACTIONS_LIBRARY: libsixdof_control_actions alone, the controllers' ROS interface
# (controller_actions.h, controller_params.h, controller_joints.h) without the control loop and pluginlib, for
# nodes that host the controllers themselves (sixdof_sim's node). sixdof_control_LIBRARIES lists every library.
set(sixdof_control_ACTIONS_LIBRARY "")
foreach(sixdof_control_library ${sixdof_control_LIBRARIES})
  if(sixdof_control_library MATCHES "sixdof_control_actions")
    set(sixdof_control_ACTIONS_LIBRARY ${sixdof_control_library})
  endif()
endforeach()
if(NOT sixdof_control_ACTIONS_LIBRARY)
  message(FATAL_ERROR "sixdof_control: the library sixdof_control_actions is not in sixdof_control_LIBRARIES")
endif()
