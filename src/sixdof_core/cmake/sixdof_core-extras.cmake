# sixdof_core_MODEL_LIBRARY: the model layer alone (libsixdof_core_model: the robot model, shapes, mesh files,
# trajectory points and splines; urdfdom, tinyxml2, assimp, Eigen), for dependents that need no collision checking
# or planning (sixdof_sim's world, sixdof_rviz's logic). sixdof_core_LIBRARIES lists all three layers.
set(sixdof_core_MODEL_LIBRARY "")
foreach(sixdof_core_library ${sixdof_core_LIBRARIES})
  if(sixdof_core_library MATCHES "sixdof_core_model")
    set(sixdof_core_MODEL_LIBRARY ${sixdof_core_library})
  endif()
endforeach()
if(NOT sixdof_core_MODEL_LIBRARY)
  message(FATAL_ERROR "sixdof_core: the model library (sixdof_core_model) is not in sixdof_core_LIBRARIES")
endif()
