# Installs the current build into a temporary prefix, then configures, builds and runs test/consumer (a
# separate project doing find_package(pcl_sparse)) against it, and runs the installed pcl_sparse_info.
# Run as: cmake -DSOURCE_DIR=<src> -DBINARY_DIR=<build> -DCXX_COMPILER=<c++> [-DCONFIG=<cfg>] -P
cmake_minimum_required(VERSION 3.16)

set(prefix "${BINARY_DIR}/consumer-install")
set(consumer_build "${BINARY_DIR}/consumer-build")
file(REMOVE_RECURSE "${prefix}" "${consumer_build}")

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer test: ${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

set(config_args "")
if(CONFIG)
  set(config_args --config "${CONFIG}")
endif()
run("install" "${CMAKE_COMMAND}" --install "${BINARY_DIR}" --prefix "${prefix}" ${config_args})
foreach(file include/pcl_sparse/mesh/triangle_mesh.h share/pcl_sparse/package.xml share/doc/pcl_sparse/LICENSE
             share/doc/pcl_sparse/METHOD.md)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "consumer test: ${file} was not installed")
  endif()
endforeach()
file(GLOB_RECURSE config_files "${prefix}/*/pcl_sparseConfig.cmake" "${prefix}/*/pcl_sparseConfigVersion.cmake"
     "${prefix}/*/pcl_sparseTargets.cmake")
list(LENGTH config_files config_count)
if(config_count LESS 3)
  message(FATAL_ERROR "consumer test: package config files missing under ${prefix}: ${config_files}")
endif()

# The consumer must find the installed package through the prefix, not the build tree.
run("configure" "${CMAKE_COMMAND}" -S "${SOURCE_DIR}/test/consumer" -B "${consumer_build}"
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
file(STRINGS "${consumer_build}/CMakeCache.txt" found_dir REGEX "^pcl_sparse_DIR:")
if(NOT found_dir MATCHES "consumer-install")
  message(FATAL_ERROR "consumer test: pcl_sparse found outside the install prefix: ${found_dir}")
endif()
run("build" "${CMAKE_COMMAND}" --build "${consumer_build}" ${config_args})
find_program(consumer consumer PATHS "${consumer_build}" "${consumer_build}/Release" NO_DEFAULT_PATH)
run("run" "${consumer}")
message(STATUS "${last_output}")
if(NOT last_output MATCHES "consumer: ok")
  message(FATAL_ERROR "consumer test: unexpected output:\n${last_output}")
endif()

# The installed tool runs from the prefix (its RPATH finds the installed library).
set(off "${consumer_build}/tetrahedron.off")
file(WRITE "${off}" "OFF\n4 4 0\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n")
file(GLOB_RECURSE info_tool "${prefix}/bin/pcl_sparse_info*")
if(info_tool)
  run("installed pcl_sparse_info" ${info_tool} "${off}")
  if(NOT last_output MATCHES "\nvertices: 4\n" OR NOT last_output MATCHES "\ngenus: 0\n")
    message(FATAL_ERROR "consumer test: installed pcl_sparse_info printed:\n${last_output}")
  endif()
endif()
