// A log truncated by another program while it is mapped: reported with the file's name, never a
// SIGBUS; a SIGBUS elsewhere still ends the process.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdlib>
#include <memory>
#include <numeric>
#include <vector>

#include "log_test_files.hpp"
#include "offline/log/file_text.hpp"
#include "offline/log/truncation_guard.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

using test::TempDir;
using test::write_text;

/// Three pages and a bit of digits: long enough that a truncation leaves whole pages unbacked.
std::string three_pages() {
  std::string text;
  for (int i = 0; text.size() < 3 * 4096 + 100; ++i)
    text += std::to_string(i % 10);
  return text;
}

long byte_sum(std::string_view text) {
  return std::accumulate(text.begin(), text.end(), 0L,
                         [](long sum, char c) { return sum + static_cast<unsigned char>(c); });
}

TEST(TruncatedFile, ReadsZerosPastTheNewEndAndNamesTheFile) {
  TempDir dir("truncated");
  const std::string text = three_pages();
  write_text(dir / "log.csv", text);
  const FileText file(dir / "log.csv");
  ASSERT_EQ(file.text().size(), text.size());
  std::filesystem::resize_file(dir / "log.csv", 100);
  // Without the guard this read ends the process with SIGBUS at the second page.
  EXPECT_EQ(byte_sum(file.text()), byte_sum(std::string_view(text).substr(0, 100)));
  try {
    file.check_complete();
    ADD_FAILURE() << "no error for a truncated file";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((dir / "log.csv").string()), std::string::npos) << message;
    EXPECT_NE(message.find("shrank from " + std::to_string(text.size()) + " to 100 bytes"),
              std::string::npos)
        << message;
  }
}

TEST(TruncatedFile, AnUntouchedFileIsComplete) {
  TempDir dir("untouched");
  const std::string text = three_pages();
  write_text(dir / "log.csv", text);
  const FileText file(dir / "log.csv");
  EXPECT_EQ(file.text(), text);
  EXPECT_NO_THROW(file.check_complete());
}

TEST(TruncatedFile, MoreFilesThanWatchesAreReadInstead) {
  TempDir dir("many");
  const std::string text = three_pages();
  write_text(dir / "log.csv", text);
  std::vector<std::unique_ptr<FileText>> files;
  for (int i = 0; i < TruncationGuard::kMaxWatched + 3; ++i)
    files.push_back(std::make_unique<FileText>(dir / "log.csv"));
  for (const auto& file : files)
    EXPECT_EQ(file->text(), text);
  files.clear();  // every watch is free again: a truncation is caught as before
  const FileText again(dir / "log.csv");
  std::filesystem::resize_file(dir / "log.csv", 10);
  EXPECT_EQ(byte_sum(again.text()), byte_sum(std::string_view(text).substr(0, 10)));
  EXPECT_THROW(again.check_complete(), Error);
}

/// Maps `path` (not watched), truncates it and reads past its new end.
void read_unwatched_truncated(const std::filesystem::path& path, std::size_t bytes) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  const auto* mapped =
      static_cast<const volatile char*>(::mmap(nullptr, bytes, PROT_READ, MAP_PRIVATE, fd, 0));
  std::filesystem::resize_file(path, 10);
  long sum = 0;
  for (std::size_t i = 0; i < bytes; ++i)
    sum += mapped[i];
  (void)sum;
  std::exit(0);  // not reached: the (volatile) read past the end raises SIGBUS
}

TEST(TruncatedFileDeathTest, AnotherSigbusStillEndsTheProcess) {
  TempDir dir("other");
  const std::string text = three_pages();
  write_text(dir / "watched.csv", text);
  write_text(dir / "other.csv", text);
  const FileText watched(dir / "watched.csv");  // installs the handler
  // Killed by SIGBUS; under AddressSanitizer (CI), whose handler was there before, its report
  // and exit code 1.
  EXPECT_DEATH(read_unwatched_truncated(dir / "other.csv", text.size()), "");
}

}  // namespace
}  // namespace tpf::offline
