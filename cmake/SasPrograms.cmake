# sas_add_programs_command_line_test(): one CTest test that runs every executable this build
# makes with --help (exit 0, the usage on stdout) and with an unknown flag (exit 2, the flag named
# on stderr): tests/e2e/programs_command_line.sh. The list is read from the build itself (every
# directory's BUILDSYSTEM_TARGETS, walked from the top), so a program added later is in it without
# anyone remembering to add it. Left out, because their command line is someone else's:
#   - the Catch2 test runners (they link sas_catch_main; Catch2's own flags and exit codes);
#   - the libFuzzer binaries of the SAS_FUZZ configuration (linked with -fsanitize=fuzzer: their
#     main is libFuzzer's, which takes -flag=value, answers -help=1 and only warns about an
#     unknown flag; tests/fuzz/run_fuzzers.sh relies on those). Their inputs are replayed by the
#     fuzz_*_replay programs, which are in the list.

function(_sas_collect_programs dir out)
  set(found "")
  get_property(targets DIRECTORY "${dir}" PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(NOT type STREQUAL "EXECUTABLE")
      continue()
    endif()
    get_target_property(libs ${target} LINK_LIBRARIES)
    get_target_property(link_options ${target} LINK_OPTIONS)
    if("sas_catch_main" IN_LIST libs OR "-fsanitize=fuzzer" IN_LIST link_options)
      continue()
    endif()
    list(APPEND found ${target})
  endforeach()
  get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    _sas_collect_programs("${sub}" sub_found)
    list(APPEND found ${sub_found})
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

function(sas_add_programs_command_line_test)
  _sas_collect_programs("${PROJECT_SOURCE_DIR}" programs)
  set(files "")
  foreach(program IN LISTS programs)
    list(APPEND files "$<TARGET_FILE:${program}>")
  endforeach()
  set(name "e2e: every program the build makes, Catch2 runners aside, answers --help with 0 and its usage on stdout, and an unknown flag with 2 naming it on stderr")
  add_test(NAME "${name}"
           COMMAND "${PROJECT_SOURCE_DIR}/tests/e2e/programs_command_line.sh" ${files})
  set_tests_properties("${name}" PROPERTIES LABELS e2e TIMEOUT 300)
endfunction()
