# TPF_NATIVE=ON builds everything for the CPU of the build machine (-march=native: AVX2, AVX-512,
# FMA where it has them). A controller is usually built on, or for, the computer it runs on, and
# the TCN step is then about twice as fast (docs/performance.md). Off by default: the shipped
# programs run on any x86-64. The benchmarks print the flags they were built with.
option(TPF_NATIVE "Compile for the build machine's CPU (-march=native)" OFF)
set(TPF_NATIVE_FLAGS "")
if(TPF_NATIVE)
  set(TPF_NATIVE_FLAGS -march=native)
  add_compile_options(${TPF_NATIVE_FLAGS})
  # Two false positives of GCC 12 in its AVX-512 intrinsics as Eigen uses them: they start from
  # _mm512_undefined_ps/pd (`__m512 __Y = __Y;`), which -Wuninitialized reports inside Eigen's
  # pmax (GCC bug 105593); and -Warray-bounds reports the 512-bit loads in Eigen's vectorised
  # loops for vectors shorter than a register, in the branch that checks the size first and that
  # such vectors never take.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    add_compile_options(-Wno-uninitialized -Wno-maybe-uninitialized -Wno-array-bounds)
  endif()
endif()
