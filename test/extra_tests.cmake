# Non-gtest checks: package.xml structure, the info tool's output and errors, and a separate project
# using the installed package. Included by test/CMakeLists.txt.

add_test(NAME package_xml_format3
  COMMAND ${CMAKE_COMMAND} -DPACKAGE_XML=${PROJECT_SOURCE_DIR}/package.xml -DEXPECTED_NAME=${PROJECT_NAME}
          -DEXPECTED_VERSION=${PROJECT_VERSION} -P ${PROJECT_SOURCE_DIR}/cmake/CheckPackageXml.cmake)

if(TARGET pcl_sparse_info)
  add_test(NAME pcl_sparse_info_tool
    COMMAND ${CMAKE_COMMAND} -DTOOL=$<TARGET_FILE:pcl_sparse_info> -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/info_tool
            -DSHARED_MESHES=${PCL_SPARSE_SHARED_MESHES} -DSHARED_CLOUDS=${PCL_SPARSE_SHARED_CLOUDS}
            -P ${PROJECT_SOURCE_DIR}/cmake/CheckInfoTool.cmake)
endif()

# The API reference builds without a single doxygen warning (docs/Doxyfile.in, CMakeLists.txt).
if(DOXYGEN_FOUND)
  add_test(NAME doxygen_clean
    COMMAND ${CMAKE_COMMAND} -DDOXYGEN=${DOXYGEN_EXECUTABLE} -DDOXYFILE=${PROJECT_BINARY_DIR}/Doxyfile
            -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/doxygen_clean -P ${PROJECT_SOURCE_DIR}/cmake/CheckDoxygen.cmake)
  set_tests_properties(doxygen_clean PROPERTIES TIMEOUT 300)
endif()

# Installs the whole build (so it needs every target built first, as scripts/test.sh does).
add_test(NAME consumer_project
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DBINARY_DIR=${PROJECT_BINARY_DIR}
          -DCXX_COMPILER=${CMAKE_CXX_COMPILER} -DCONFIG=$<CONFIG> -P ${PROJECT_SOURCE_DIR}/cmake/RunConsumerTest.cmake)
set_tests_properties(consumer_project PROPERTIES TIMEOUT 900 RUN_SERIAL TRUE)

# The tools' output files, byte for byte, against hashes recorded before the refactors of issue 11.
if(TARGET pcl_sparse_encode)
  add_test(NAME tool_outputs_unchanged
    COMMAND ${CMAKE_COMMAND} -DTOOLS_DIR=$<TARGET_FILE_DIR:pcl_sparse_encode> -DSHARED=${PCL_SPARSE_SHARED_MESHES}/..
            -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/tool_outputs -DCASES=${CMAKE_CURRENT_SOURCE_DIR}/golden/tool_outputs.cases
            -P ${PROJECT_SOURCE_DIR}/cmake/CheckToolOutputs.cmake)
  # Without ../shared the script compares nothing: ctest reports it skipped (with the reason), not passed.
  set_tests_properties(tool_outputs_unchanged PROPERTIES FAIL_REGULAR_EXPRESSION "differ|failed"
                       SKIP_REGULAR_EXPRESSION "SKIP: the shared meshes are not at" TIMEOUT 600)
endif()

# Layering (issue 11): no include cycle between the library's folders, no function in src/ over 120
# lines (scripts/check_layers.py; scripts/long_functions_allowed.txt lists exceptions).
if(EXISTS /usr/bin/python3)
  add_test(NAME layers_no_include_cycle
    COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/check_layers.py includes ${PROJECT_SOURCE_DIR})
  add_test(NAME functions_at_most_120_lines
    COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/check_layers.py functions ${PROJECT_SOURCE_DIR}
            --max 120 --allow ${PROJECT_SOURCE_DIR}/scripts/long_functions_allowed.txt)
else()
  message(STATUS "pcl_sparse: /usr/bin/python3 not found, skipping the layering checks")
endif()
