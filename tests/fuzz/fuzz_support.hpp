// Shared pieces of the fuzz targets: the input as a file, and the error contract every loader
// must keep on bad input (throw tpf::Error whose message starts with the file's path; nothing
// else).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "tpf/common/error.hpp"

namespace tpf::fuzz {

/// A private scratch folder for this process (under $TMPDIR), removed at exit.
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() /
                   ("tpf-fuzz-" + std::to_string(static_cast<long>(::getpid())));
    std::filesystem::create_directories(d);
    return d;
  }();
  static const struct Cleanup {
    ~Cleanup() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  } cleanup;
  return dir;
}

/// Writes `bytes` to `<scratch>/<name>` (replacing it) and returns the path.
inline std::filesystem::path write_input(std::span<const std::uint8_t> bytes,
                                         const std::string& name) {
  const auto path = scratch_dir() / name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size()) std::abort();
  std::fclose(f);
  return path;
}

/// Reports a broken contract and aborts, so libFuzzer saves the input.
[[noreturn]] inline void violation(std::string_view what, std::string_view detail) {
  std::fprintf(stderr, "tpf fuzz contract violated: %.*s: %.*s\n", static_cast<int>(what.size()),
               what.data(), static_cast<int>(detail.size()), detail.data());
  std::abort();
}

/// Runs `load()`; bad input may only end in a tpf::Error whose message starts with `file`
/// (the "file:line: field: reason" form). Any other exception is a contract violation.
template <typename Load>
void expect_clean_error(const std::string& file, Load&& load) {
  try {
    load();
  } catch (const tpf::Error& e) {
    const std::string_view message = e.what();
    if (!message.starts_with(file)) violation("tpf::Error does not name the file", message);
    if (message.find('\n') != std::string_view::npos)
      violation("tpf::Error is not one line", message);
  } catch (const std::exception& e) {
    violation("an exception other than tpf::Error escaped", e.what());
  }
}

}  // namespace tpf::fuzz
