// Code that runs once per command, file or report (the core's file loaders; the offline tools'
// text, JSON, HTML and SVG writers; the commands' option handling and printouts) is compiled
// without optimisation in the sanitized build:
// TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN after a file's includes, ..._END at its end or around
// such functions in a file that also computes. Their functions are long chains of string and JSON
// temporaries inlined into large bodies: optimised and instrumented they took a third of
// tpf_offline's compile there. Only the functions defined in between are affected (clang's
// `optimize off`); the templates they call (Eigen, the core, nlohmann-json) are compiled as
// everywhere else. Other builds are unchanged.
#pragma once

#if defined(__clang__) && defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN _Pragma("clang optimize off")
#define TPF_UNOPTIMISED_WHEN_SANITIZED_END _Pragma("clang optimize on")
#endif
#endif

#ifndef TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN
#define TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN
#define TPF_UNOPTIMISED_WHEN_SANITIZED_END
#endif
