# One layer of the core each, for dependents that need no collision checking or planning:
#   sixdof_core_MODEL_LIBRARY    libsixdof_core_model: the robot model, shapes, mesh files, trajectory points, splines
#                                and the trajectory sampler; urdfdom, tinyxml2, assimp, Eigen (sixdof_sim's world,
#                                sixdof_rviz's logic)
#   sixdof_core_CONTROL_LIBRARY  libsixdof_core_control: the trajectory and gripper controllers, on the model layer
#                                (sixdof_sim's node, sixdof_control)
# sixdof_core_LIBRARIES lists every layer.
foreach(sixdof_core_layer MODEL CONTROL)
  string(TOLOWER ${sixdof_core_layer} sixdof_core_layer_name)
  set(sixdof_core_${sixdof_core_layer}_LIBRARY "")
  foreach(sixdof_core_library ${sixdof_core_LIBRARIES})
    if(sixdof_core_library MATCHES "sixdof_core_${sixdof_core_layer_name}")
      set(sixdof_core_${sixdof_core_layer}_LIBRARY ${sixdof_core_library})
    endif()
  endforeach()
  if(NOT sixdof_core_${sixdof_core_layer}_LIBRARY)
    message(FATAL_ERROR "sixdof_core: the library sixdof_core_${sixdof_core_layer_name} is not in sixdof_core_LIBRARIES")
  endif()
endforeach()
