# Runs pcl_sparse_info on a small mesh, on bad input and (when present) on the shared Fandisk, and checks
# the output lines, the JSON keys and the exit codes.
# Run as: cmake -DTOOL=<pcl_sparse_info> -DWORK_DIR=<dir> [-DSHARED_MESHES=<dir>] -P
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

expect_refusal("${WORK_DIR}/missing.off" "missing.off")
expect_refusal("${WORK_DIR}" "${WORK_DIR}")
expect_refusal("${off};--no-such-option" "--no-such-option")
expect_refusal("${WORK_DIR}/model.psm" "model.psm")

if(SHARED_MESHES AND EXISTS "${SHARED_MESHES}/fandisk.off")
  expect_output("${SHARED_MESHES}/fandisk.off" "\nvertices: 6475\n" "\nfaces: 12946\n" "\ngenus: 0\n")
endif()
