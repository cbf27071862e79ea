# Per-target flags, never global (a dependency's code must not be built with our warnings).
# Every target of ours calls sas_target_flags().
function(sas_target_flags target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wconversion -Werror)
  # GCC 12 at -O3 (the Release configuration) inlines std::string's insert-at-front from
  # `"text" + std::string(...)` and then reports impossible overlapping memcpys under -Wrestrict
  # (gpio, atomic_file, ... : every such concatenation is a candidate). A known false positive of
  # that compiler (later GCC releases fixed it); -O2 builds keep the warning.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:-Wno-restrict>)
  endif()
  if(SAS_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=all)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(SAS_FUZZ)
    # Coverage instrumentation for libFuzzer in every library of ours; the fuzz executables add
    # -fsanitize=fuzzer (tests/fuzz/CMakeLists.txt).
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link,address,undefined
                                             -fno-omit-frame-pointer -fno-sanitize-recover=all)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# The libraries whose loops every sounding test runs (contact solves, resonators, the output
# stage, loudness and sharpness meters, image filters): under the sanitizers they are built at -O1
# instead of the Debug build's -O0, which ASan's own guide recommends for speed. At -O0 those
# loops ran about ten times slower than the normal build and made the sanitizer suite the longest
# step of the test command; the instrumentation and its checks are the same at -O1. The other
# targets keep -O0 (their code is not hot, and the test files compile twice as slowly at -O1).
function(sas_sanitized_hot_path target)
  if(SAS_SANITIZE)
    target_compile_options(${target} PRIVATE -O1)
  endif()
endfunction()

# The audio path's code generation: the synth library, and contact_bench, which compiles the
# explicit reference the synth's schemes are timed against (with the same flags, so that its cost
# ratios compare the schemes, not the compilers' options).
# -O3 in the default configuration too (Release already is): the same output bit for bit
# (visitor_bench --checksum, all four textures: no fast-math, no contraction on x86-64), and
# visitor strokes cost ~6 % less of a core at the median. Debug and the sanitizer build keep their
# own levels.
# No errno from the maths (every build type): sqrt compiles to one instruction, without the branch
# to the library that only sets errno, which the audio path never reads. The same output bit for
# bit (sqrt is correctly rounded either way; visitor_bench --checksum), strokes ~1 % cheaper.
function(sas_audio_path_codegen target)
  target_compile_options(${target} PRIVATE $<$<CONFIG:RelWithDebInfo>:-O3> -fno-math-errno)
endfunction()
