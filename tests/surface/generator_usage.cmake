# texture_generator given an option where its output folder belongs: exit code 2 with the usage,
# and no folder named after the option (it once wrote four textures into ./--help).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
execute_process(COMMAND "${GENERATOR}" --help WORKING_DIRECTORY "${WORK_DIR}"
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "texture_generator --help exited with '${rc}', expected 2")
endif()
if(NOT err MATCHES "usage: .*<out_dir>")
  message(FATAL_ERROR "texture_generator --help did not print its usage: '${err}'")
endif()
if(EXISTS "${WORK_DIR}/--help")
  message(FATAL_ERROR "texture_generator --help wrote ${WORK_DIR}/--help")
endif()
