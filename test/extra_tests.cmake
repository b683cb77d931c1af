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

# Installs the whole build (so it needs every target built first, as scripts/test.sh does).
add_test(NAME consumer_project
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DBINARY_DIR=${PROJECT_BINARY_DIR}
          -DCXX_COMPILER=${CMAKE_CXX_COMPILER} -DCONFIG=$<CONFIG> -P ${PROJECT_SOURCE_DIR}/cmake/RunConsumerTest.cmake)
set_tests_properties(consumer_project PROPERTIES TIMEOUT 900 RUN_SERIAL TRUE)
