# Target helpers of the C++ packages: sixdof_core includes this file, and its CMake config brings it to every
# package that finds sixdof_core (CFG_EXTRAS), so the tests, benchmarks and tools of all of them are declared alike.

# sixdof_add_executables(<prefix> SOURCES <dir/name.cpp>... LIBRARIES <library>...): one executable per source,
# target <prefix><name>, file <name>, installed to the package's lib directory (rosrun <package> <name>).
function(sixdof_add_executables prefix)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES" ${ARGN})
  foreach(src ${ARG_SOURCES})
    get_filename_component(name ${src} NAME_WE)
    add_executable(${prefix}${name} ${src})
    set_target_properties(${prefix}${name} PROPERTIES OUTPUT_NAME ${name})
    target_link_libraries(${prefix}${name} ${ARG_LIBRARIES})
    install(TARGETS ${prefix}${name} RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
  endforeach()
endfunction()

# sixdof_add_gtests(SOURCES <test/test_name.cpp>... LIBRARIES <library>... [DEFINITIONS <NAME="value">...]): one
# plain gtest (no roscore) per source, named after it. GTest's own main runs the tests: the sources have none.
function(sixdof_add_gtests)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES;DEFINITIONS" ${ARGN})
  foreach(src ${ARG_SOURCES})
    get_filename_component(name ${src} NAME_WE)
    catkin_add_gtest(${name} ${src})
    target_link_libraries(${name} ${ARG_LIBRARIES} GTest::gtest_main)
    target_compile_definitions(${name} PRIVATE ${ARG_DEFINITIONS})
  endforeach()
endfunction()

# sixdof_package_share_dir(<package> <variable>): the folder of <package>'s installed files (share/<package>), for
# tests that read a package's files (sixdof_description's URDF), found through its CMake config: <package> must be
# a dependency. In a catkin devel space, whose share/ holds no files, the package's source folder as catkin records it.
function(sixdof_package_share_dir package variable)
  find_package(${package} REQUIRED)
  if(${package}_SOURCE_PREFIX)
    set(${variable} ${${package}_SOURCE_PREFIX} PARENT_SCOPE)
  else()
    set(${variable} ${${package}_PREFIX}/share/${package} PARENT_SCOPE)
  endif()
endfunction()

# sixdof_add_rostests(<glob>): one rostest per launch file matching the pattern (e.g. test/*.test).
function(sixdof_add_rostests pattern)
  find_package(rostest REQUIRED)
  file(GLOB rostest_files CONFIGURE_DEPENDS ${pattern})
  foreach(t ${rostest_files})
    add_rostest(${t})
  endforeach()
endfunction()
