# texture_generator given an option where its output folder belongs: exit code 2 naming the
# missing folder, and no folder named after the option (it once wrote four textures into
# ./--help); --help itself prints the usage with the folder on stdout and exits 0, writing nothing.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
execute_process(COMMAND "${GENERATOR}" --only wooden_board WORKING_DIRECTORY "${WORK_DIR}"
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "texture_generator --only wooden_board exited with '${rc}', expected 2")
endif()
if(NOT err MATCHES "out_dir")
  message(FATAL_ERROR "texture_generator --only wooden_board did not name the missing out_dir: '${err}'")
endif()
execute_process(COMMAND "${GENERATOR}" --help WORKING_DIRECTORY "${WORK_DIR}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "texture_generator --help exited with '${rc}', expected 0")
endif()
if(NOT out MATCHES "Usage: .*out_dir")
  message(FATAL_ERROR "texture_generator --help did not print its usage: '${out}'")
endif()
file(GLOB written "${WORK_DIR}/*")
if(written)
  message(FATAL_ERROR "texture_generator wrote ${written}")
endif()
