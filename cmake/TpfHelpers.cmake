# Warnings and sanitizers shared by every target of the project.
add_library(tpf_warnings INTERFACE)
target_compile_options(tpf_warnings INTERFACE -Wall -Wextra -Wpedantic)
# TPF_SANITIZER_FLAGS: the compile flags of a sanitized build (tests/install builds its consumer
# with them). With AddressSanitizer on, UBSan's object-size check is left out: ASan's checks
# already cover what it finds (an access past the object), and its checks on every Eigen access
# block inlining, which made the sanitized twin 2× slower. With clang, UBSan also stays out of
# the functions Eigen's headers define (cmake/ubsan_outside_eigen.txt): the twin-scale tests ran
# 2–4× faster, all tests 855 → 394 CPU-s (docs/reliability.md, "CI time").
set(TPF_SANITIZER_FLAGS "")
if(TPF_SANITIZE)
  set(TPF_SANITIZER_FLAGS -fsanitize=${TPF_SANITIZE} -fno-omit-frame-pointer
                          -fno-sanitize-recover=all)
  if(TPF_SANITIZE MATCHES "address" AND TPF_SANITIZE MATCHES "undefined")
    list(APPEND TPF_SANITIZER_FLAGS -fno-sanitize=object-size)
  endif()
  if(TPF_SANITIZE MATCHES "undefined" AND CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    list(APPEND TPF_SANITIZER_FLAGS
         -fsanitize-ignorelist=${PROJECT_SOURCE_DIR}/cmake/ubsan_outside_eigen.txt)
  endif()
  target_compile_options(tpf_warnings INTERFACE ${TPF_SANITIZER_FLAGS})
  target_link_options(tpf_warnings INTERFACE -fsanitize=${TPF_SANITIZE})
endif()
# tpf_unoptimised_when_sanitized(<target>...): in a sanitized build (CI), compiles the targets
# that exist at -O0. For programs whose sanitized tests run in seconds, or that no test runs: -O1
# doubled their compile (docs/reliability.md, "CI time").
function(tpf_unoptimised_when_sanitized)
  if(NOT TPF_SANITIZE)
    return()
  endif()
  foreach(target IN LISTS ARGN)
    if(TARGET ${target})
      target_compile_options(${target} PRIVATE -O0)
    endif()
  endforeach()
endfunction()
# Fuzzing (tests/fuzz): libFuzzer targets; tests/fuzz adds the coverage instrumentation to the
# code the fuzzers reach, and only there.
option(TPF_FUZZ "Build tests/fuzz as libFuzzer targets (needs clang)" OFF)
if(TPF_FUZZ AND NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "TPF_FUZZ needs clang (libFuzzer); use the 'sanitize' preset")
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

# One program per concept folder: every immediate subfolder of the current source folder becomes
# the executable tpf_<folder>_<suffix> built from its *.cpp files and linked with the core (and the
# offline library where it is built), unless the folder brings its own CMakeLists.txt, which is
# added instead; folders named in the further arguments are skipped. The areas made are returned in
# <out_var>.
# tpf_add_area_programs(<suffix> <out_var> [skipped folder...])
function(tpf_add_area_programs suffix out_var)
  file(GLOB areas LIST_DIRECTORIES true RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}
       ${CMAKE_CURRENT_SOURCE_DIR}/*)
  list(SORT areas)
  set(made "")
  foreach(area IN LISTS areas)
    set(dir ${CMAKE_CURRENT_SOURCE_DIR}/${area})
    if(NOT IS_DIRECTORY ${dir} OR area IN_LIST ARGN)
      continue()
    endif()
    if(EXISTS ${dir}/CMakeLists.txt)
      add_subdirectory(${area})
      continue()
    endif()
    file(GLOB sources CONFIGURE_DEPENDS ${dir}/*.cpp)
    if(NOT sources)
      continue()
    endif()
    add_executable(tpf_${area}_${suffix} ${sources})
    target_link_libraries(tpf_${area}_${suffix} PRIVATE tpf::core tpf_warnings)
    if(TARGET tpf_offline)
      target_link_libraries(tpf_${area}_${suffix} PRIVATE tpf::offline)
    endif()
    list(APPEND made ${area})
  endforeach()
  set(${out_var} ${made} PARENT_SCOPE)
endfunction()

include(TpfNative)
