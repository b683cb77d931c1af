# Checks package.xml against the parts of the ROS package format 3 (REP 149) that colcon, catkin tools
# and rosdep rely on. Run as: cmake -DPACKAGE_XML=<file> -DEXPECTED_NAME=<name> -DEXPECTED_VERSION=<x.y.z> -P
# A real schema check needs xmllint and network access to the XSD; these checks need neither.
cmake_minimum_required(VERSION 3.16)

file(READ "${PACKAGE_XML}" xml)
# Comments cannot hide or fake a tag.
string(REGEX REPLACE "<!--([^-]|-[^-])*-->" "" xml "${xml}")
set(problems "")

function(require regex what)
  if(NOT xml MATCHES "${regex}")
    set(problems ${problems} "${what}" PARENT_SCOPE)
  endif()
endfunction()

# Exactly one package element, format 3, closed at the end.
string(REGEX MATCHALL "<package[ >]" package_tags "${xml}")
list(LENGTH package_tags package_count)
if(NOT package_count EQUAL 1)
  list(APPEND problems "expected one <package> element, found ${package_count}")
endif()
require("^(<[?]xml [^>]*>[ \t\r\n]*)?(<[?]xml-model [^>]*>[ \t\r\n]*)?<package format=\"3\">" "root element must be <package format=\"3\">")
require("</package>[ \t\r\n]*$" "the file must end with </package>")

# Required children (REP 149): name, version, description, at least one maintainer with email, license.
require("<name>${EXPECTED_NAME}</name>" "<name> must be ${EXPECTED_NAME}")
if(xml MATCHES "<version>([^<]*)</version>")
  if(NOT CMAKE_MATCH_1 STREQUAL EXPECTED_VERSION)
    list(APPEND problems "<version> is ${CMAKE_MATCH_1}, the CMake project version is ${EXPECTED_VERSION}")
  endif()
else()
  list(APPEND problems "missing <version>")
endif()
require("<description>[ \t\r\n]*[^< \t\r\n][^<]*</description>" "missing or empty <description>")
require("<maintainer email=\"[^\"@ ]+@[^\"@ ]+\">[^<]+</maintainer>" "missing <maintainer email=\"...\">name</maintainer>")
require("<license>[^<]+</license>" "missing <license>")

# A plain CMake package: colcon and catkin tools pick the build type from here. In a ROS 1 environment
# (ROS_VERSION=1) it may be a catkin package instead (the node and nodelets in ros/); then the cmake build
# type must be conditional too, since catkin_pkg refuses two build types that both apply.
require("<buildtool_depend>cmake</buildtool_depend>" "missing <buildtool_depend>cmake</buildtool_depend>")
require("<export>[ \t\r\n]*(<[^>]*>[^<]*</[^>]*>[ \t\r\n]*)*<build_type( condition=\"[$]ROS_VERSION != 1\")?>cmake</build_type>"
        "missing <export><build_type>cmake</build_type>")
string(REGEX MATCHALL "<build_type[^>]*>[^<]*</build_type>" build_types "${xml}")
if(xml MATCHES "<build_type[^>]*>catkin</build_type>")
  set(ros1_build_types "<build_type condition=\"[$]ROS_VERSION == 1\">catkin</build_type>"
                       "<build_type condition=\"[$]ROS_VERSION != 1\">cmake</build_type>")
  foreach(expected ${ros1_build_types})
    if(NOT xml MATCHES "${expected}")
      list(APPEND problems "a catkin build type needs <build_type condition=\"$ROS_VERSION == 1\">catkin</build_type> and <build_type condition=\"$ROS_VERSION != 1\">cmake</build_type>")
      break()
    endif()
  endforeach()
  require("<buildtool_depend condition=\"[$]ROS_VERSION == 1\">catkin</buildtool_depend>"
          "a catkin build type needs <buildtool_depend condition=\"$ROS_VERSION == 1\">catkin</buildtool_depend>")
  set(max_build_types 2)
else()
  set(max_build_types 1)
endif()
list(LENGTH build_types build_type_count)
if(build_type_count GREATER max_build_types)
  list(APPEND problems "${build_type_count} <build_type> elements")
endif()
# Exported plugin descriptions (${prefix} is the package folder) must exist.
string(REGEX MATCHALL "plugin=\"[$][{]prefix[}]/[^\"]+\"" plugins "${xml}")
get_filename_component(package_dir "${PACKAGE_XML}" DIRECTORY)
foreach(plugin ${plugins})
  string(REGEX REPLACE "plugin=\"[$][{]prefix[}]/([^\"]+)\"" "\\1" plugin_file "${plugin}")
  if(NOT EXISTS "${package_dir}/${plugin_file}")
    list(APPEND problems "exported plugin file ${plugin_file} does not exist")
  endif()
endforeach()

# The rosdep keys of the dependencies.
foreach(key libpcl-all-dev eigen boost)
  require("<(build_|exec_|build_export_)?depend>${key}</(build_|exec_|build_export_)?depend>" "missing dependency key ${key}")
endforeach()
require("<test_depend>gtest</test_depend>" "missing <test_depend>gtest</test_depend>")

# Format 3 dropped format 1's run_depend.
if(xml MATCHES "<run_depend>")
  list(APPEND problems "<run_depend> is format 1; use exec_depend or depend")
endif()

if(problems)
  list(JOIN problems "; " message)
  message(FATAL_ERROR "${PACKAGE_XML}: ${message}")
endif()
message(STATUS "${PACKAGE_XML}: package format 3, ${EXPECTED_NAME} ${EXPECTED_VERSION}, ok")
