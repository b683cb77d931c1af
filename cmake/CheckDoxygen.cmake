# Runs doxygen with the build's Doxyfile (docs/Doxyfile.in, configured by CMake) into WORK_DIR and fails
# if doxygen fails or prints any warning, listing them. Run as:
#   cmake -DDOXYGEN=<doxygen> -DDOXYFILE=<build>/Doxyfile -DWORK_DIR=<dir> -P CheckDoxygen.cmake
# The build's own doc target is left alone: the check writes its output and warning log to WORK_DIR.
cmake_minimum_required(VERSION 3.16)

foreach(variable DOXYGEN DOXYFILE WORK_DIR)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "CheckDoxygen.cmake: -D${variable}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
# Later settings override earlier ones in a Doxyfile.
file(READ "${DOXYFILE}" config)
string(APPEND config "\n# Overrides of cmake/CheckDoxygen.cmake\n"
                     "OUTPUT_DIRECTORY = \"${WORK_DIR}\"\n"
                     "WARN_LOGFILE = \"${WORK_DIR}/warnings.log\"\n"
                     "WARN_AS_ERROR = NO\n"
                     "QUIET = YES\n")
file(WRITE "${WORK_DIR}/Doxyfile" "${config}")

execute_process(COMMAND "${DOXYGEN}" "${WORK_DIR}/Doxyfile"
                WORKING_DIRECTORY "${WORK_DIR}"
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "doxygen failed (${result}):\n${output}${errors}")
endif()

set(warnings "")
if(EXISTS "${WORK_DIR}/warnings.log")
  file(READ "${WORK_DIR}/warnings.log" warnings)
endif()
# Anything doxygen still printed on stderr (errors that bypass the log) counts too.
string(APPEND warnings "${errors}")
string(STRIP "${warnings}" warnings)
if(NOT warnings STREQUAL "")
  string(REGEX MATCHALL ": warning: " found "${warnings}")
  list(LENGTH found count)
  message("${warnings}")  # as doxygen wrote them (FATAL_ERROR would re-wrap the lines)
  message(FATAL_ERROR "doxygen printed ${count} warning(s), listed above")
endif()
message(STATUS "doxygen: no warnings (${WORK_DIR}/html/index.html)")
