// Linked into every benchmark program: the compiler and flags it was built with, printed in the
// benchmark context (console header and JSON "context"), so that every figure names its build.
#include <benchmark/benchmark.h>

namespace {

const bool kBuildContextAdded = [] {
  benchmark::AddCustomContext("compiler", __VERSION__);
  benchmark::AddCustomContext("build_flags", TPF_BENCH_BUILD_FLAGS);
  return true;
}();

}  // namespace
