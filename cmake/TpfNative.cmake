# TPF_NATIVE=ON builds everything for the CPU of the build machine (-march=native: AVX2, AVX-512,
# FMA where it has them). A controller is usually built on, or for, the computer it runs on, and
# the TCN step is then about twice as fast (docs/performance.md). Off by default: the shipped
# programs run on any x86-64. The benchmarks print the flags they were built with.
option(TPF_NATIVE "Compile for the build machine's CPU (-march=native)" OFF)
set(TPF_NATIVE_FLAGS "")
if(TPF_NATIVE)
  set(TPF_NATIVE_FLAGS -march=native)
  add_compile_options(${TPF_NATIVE_FLAGS})
endif()
