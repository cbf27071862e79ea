# Runs the texture generator for one texture into a scratch folder and requires every file to be
# byte-identical to the committed one. Arguments: GENERATOR, TEXTURE, SOURCE_DIR, WORK_DIR.
set(out "${WORK_DIR}/${TEXTURE}")
file(REMOVE_RECURSE "${out}")
file(MAKE_DIRECTORY "${WORK_DIR}")
execute_process(COMMAND "${GENERATOR}" "${WORK_DIR}" --only "${TEXTURE}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "texture_generator failed for ${TEXTURE} (exit ${rc})")
endif()
foreach(name picture.png height.png texture.toml)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${SOURCE_DIR}/${TEXTURE}/${name}"
                          "${out}/${name}" RESULT_VARIABLE differs)
  if(NOT differs EQUAL 0)
    message(FATAL_ERROR "${TEXTURE}/${name}: regenerated file differs from the committed one")
  endif()
endforeach()
message(STATUS "${TEXTURE}: picture.png, height.png, texture.toml reproduced byte for byte")
