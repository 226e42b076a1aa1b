# Warnings and sanitizers shared by every target of the project.
add_library(tpf_warnings INTERFACE)
target_compile_options(tpf_warnings INTERFACE -Wall -Wextra -Wpedantic)
if(TPF_SANITIZE)
  target_compile_options(tpf_warnings INTERFACE -fsanitize=${TPF_SANITIZE} -fno-omit-frame-pointer
                                                -fno-sanitize-recover=all)
  target_link_options(tpf_warnings INTERFACE -fsanitize=${TPF_SANITIZE})
endif()
# Fuzzing (tests/fuzz): coverage instrumentation for libFuzzer on every project target.
option(TPF_FUZZ "Build tests/fuzz as libFuzzer targets (needs clang)" OFF)
if(TPF_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "TPF_FUZZ needs clang (libFuzzer); use the 'sanitize' preset")
  endif()
  target_compile_options(tpf_warnings INTERFACE -fsanitize=fuzzer-no-link)
endif()

# Adds every immediate subfolder of the current source folder that has a CMakeLists.txt.
# Each concept (kinematics, nn, sim, ...) owns its folder; nothing central needs editing to add one.
function(tpf_add_subfolders)
  file(GLOB children LIST_DIRECTORIES true RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}
       ${CMAKE_CURRENT_SOURCE_DIR}/*)
  list(SORT children)
  foreach(child IN LISTS children)
    if(IS_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/${child}
       AND EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${child}/CMakeLists.txt)
      add_subdirectory(${child})
    endif()
  endforeach()
endfunction()
set_target_properties(tpf_warnings PROPERTIES EXPORT_NAME build_flags)
