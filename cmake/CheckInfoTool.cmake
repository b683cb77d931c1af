# Runs pcl_sparse_info on a small mesh, small clouds, bad input and (when present) on the shared Fandisk and
# three shared scans, and checks the output lines, the JSON keys and the exit codes.
# Run as: cmake -DTOOL=<pcl_sparse_info> -DWORK_DIR=<dir> [-DSHARED_MESHES=<dir>] [-DSHARED_CLOUDS=<dir>] -P
cmake_minimum_required(VERSION 3.16)

file(MAKE_DIRECTORY "${WORK_DIR}")
set(off "${WORK_DIR}/tetrahedron.off")
file(WRITE "${off}" "OFF\n4 4 0\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n")

function(expect_output args)
  execute_process(COMMAND "${TOOL}" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pcl_sparse_info ${args}: exit ${rc}: ${err}")
  endif()
  foreach(pattern ${ARGN})
    if(NOT out MATCHES "${pattern}")
      message(FATAL_ERROR "pcl_sparse_info ${args}: output lacks '${pattern}':\n${out}")
    endif()
  endforeach()
endfunction()

function(expect_refusal args name)
  execute_process(COMMAND "${TOOL}" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" err)
  string(FIND "${err}" "${name}" name_at)
  if(rc EQUAL 0 OR err STREQUAL "" OR err MATCHES "\n" OR name_at EQUAL -1)
    message(FATAL_ERROR "pcl_sparse_info ${args}: expected exit 1 and one error line naming '${name}', "
                        "got exit ${rc}, stderr '${err}'")
  endif()
endfunction()

expect_output("${off}" "(^|\n)vertices: 4\n" "\nfaces: 4\n" "\nedges: 6\n" "\ngenus: 0\n" "\nclosed: yes\n")
expect_output("${off};--json" "^{.*}\n$" "\"vertices\": 4," "\"faces\": 4," "\"components\": 1,"
              "\"boundary_edges\": 0," "\"nonmanifold_edges\": 0," "\"genus\": 0," "\"bbox_diagonal\": 3.464"
              "\"seconds\": ")
# The JSON parses (string(JSON) needs CMake 3.19) and holds the right values.
if(NOT CMAKE_VERSION VERSION_LESS 3.19)
  execute_process(COMMAND "${TOOL}" "${off}" --json OUTPUT_VARIABLE json RESULT_VARIABLE rc)
  foreach(check "vertices=4" "faces=4" "edges=6" "components=1" "boundary_loops=0" "nonmanifold_vertices=0"
                "genus=0" "closed=ON" "manifold=ON")
    string(REPLACE "=" ";" check "${check}")
    list(GET check 0 key)
    list(GET check 1 expected)
    string(JSON value ERROR_VARIABLE json_error GET "${json}" "${key}")
    if(json_error OR NOT value STREQUAL expected)
      message(FATAL_ERROR "pcl_sparse_info --json: ${key} is '${value}' (${json_error}), expected ${expected}:\n${json}")
    endif()
  endforeach()
endif()

# Point clouds: a PLY without faces and a PCD are reported with faces: 0 and no genus.
file(WRITE "${WORK_DIR}/points.ply" "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
           "property float z\nend_header\n0 0 0\n3 4 0\n1 1 1\n")
expect_output("${WORK_DIR}/points.ply" "\nvertices: 3\n" "\nfaces: 0\n" "\ngenus: unknown")
file(WRITE "${WORK_DIR}/points.pcd" "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\n"
           "HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n0 0 0\n3 4 0\n")
expect_output("${WORK_DIR}/points.pcd" "\nvertices: 2\n" "\nfaces: 0\n" "\nbbox_diagonal: 5\n")
# Scans (.pcd, .xyz, PLY without faces) also get the cleaning counts: NaN/Inf points, points at the sensor
# (here VIEWPOINT 0 0 0), exact duplicates; the grid shape and the fields.
expect_output("${WORK_DIR}/points.pcd" "\ninput_points: 2\n" "\nfinite_points: 2\n" "\ndropped_at_sensor_origin: 1\n"
              "\nkept_points: 1\n" "\norganized: no\n" "\nfields: x y z\n" "\nkept_bbox_diagonal: 0\n")
expect_output("${WORK_DIR}/points.ply" "\ninput_points: 3\n" "\ndropped_at_sensor_origin: 1\n" "\nkept_points: 2\n")
file(WRITE "${WORK_DIR}/grid.pcd" "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 2\n"
           "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\nnan nan nan\n1 2 3\n1 2 3\n0 0 0\n")
expect_output("${WORK_DIR}/grid.pcd" "\norganized: 2x2\n" "\nnon_finite_vertices: 1\n")
expect_output("${WORK_DIR}/grid.pcd;--json" "\"vertices\": 4," "\"input_points\": 4," "\"finite_points\": 3,"
              "\"dropped_non_finite\": 1," "\"dropped_at_sensor_origin\": 1," "\"dropped_duplicates\": 1,"
              "\"kept_points\": 1," "\"organized\": true," "\"width\": 2," "\"height\": 2," "\"fields\": \"x y z\",")
file(WRITE "${WORK_DIR}/points.xyz" "1 2 3 0 0 1\n1 2 3 0 0 1\n4 5 6 0 1 0\n")
expect_output("${WORK_DIR}/points.xyz" "\nvertices: 3\n" "\ndropped_duplicates: 1\n" "\nkept_points: 2\n"
              "\nfields: x y z nx ny nz\n")
# A PLY with faces is a mesh: no cloud keys, and a NaN vertex is refused unless --allow-non-finite.
file(WRITE "${WORK_DIR}/nan_mesh.ply" "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
           "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\nnan 1 0\n"
           "3 0 1 2\n")
expect_refusal("${WORK_DIR}/nan_mesh.ply" "nan_mesh.ply")
expect_output("${WORK_DIR}/nan_mesh.ply;--allow-non-finite" "\nfaces: 1\n" "\nnon_finite_vertices: 1\n")
execute_process(COMMAND "${TOOL}" "${WORK_DIR}/nan_mesh.ply" --allow-non-finite OUTPUT_VARIABLE out)
if(out MATCHES "kept_points")
  message(FATAL_ERROR "pcl_sparse_info: a PLY mesh was reported as a cloud:\n${out}")
endif()

expect_refusal("${WORK_DIR}/missing.off" "missing.off")
expect_refusal("${WORK_DIR}" "${WORK_DIR}")
expect_refusal("${off};--no-such-option" "--no-such-option")
expect_refusal("${WORK_DIR}/model.psm" "model.psm")

if(SHARED_MESHES AND EXISTS "${SHARED_MESHES}/fandisk.off")
  expect_output("${SHARED_MESHES}/fandisk.off" "\nvertices: 6475\n" "\nfaces: 12946\n" "\ngenus: 0\n")
endif()
if(SHARED_CLOUDS AND EXISTS "${SHARED_CLOUDS}/office1.pcd")
  # ../shared/clouds/README.md: 307,200 points, 52,744 NaN, 640 x 480; the Velodyne frame has 5,032 zeros.
  expect_output("${SHARED_CLOUDS}/office1.pcd" "\ninput_points: 307200\n" "\ndropped_non_finite: 52744\n"
                "\norganized: 640x480\n" "\nfields: x y z rgb\n")
  expect_output("${SHARED_CLOUDS}/fast_gicp_251370668.pcd" "\ndropped_at_sensor_origin: 5032\n" "\nkept_points: 64056\n")
  expect_output("${SHARED_CLOUDS}/bun000.ply" "\norganized: 512x400\n" "\nkept_points: 40256\n")
endif()
