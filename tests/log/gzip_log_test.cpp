// .csv.gz logs: read identically to the plain text, written compressed, corrupt data named.
#include <gtest/gtest.h>

#include "log_test_files.hpp"
#include "offline/log/gzip.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/read_log.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

using test::read_text;
using test::TempDir;
using test::write_text;

std::string small_log_text() {
  std::string text = "# tpf-log: 1\n# rate_hz: 100\nt,q1,dq1,i1,tau_sensor1\n";
  for (int r = 0; r < 500; ++r)
    text += std::to_string(0.01 * r) + "," + std::to_string(0.001 * r) + ",0.1," +
            (r == 7 ? "" : std::to_string(r % 13 - 6)) + ",0.5\n";
  return text;
}

std::string error_of(const std::filesystem::path& path) {
  try {
    read_log(path);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << path;
  return {};
}

TEST(GzipLog, ReadsIdenticallyToThePlainFile) {
  TempDir dir("gz_same");
  const std::string text = small_log_text();
  write_text(dir / "a.csv", text);
  write_text(dir / "a.csv.gz", gzip(text));
  // Two members (as `cat a.gz b.gz` makes) are one text.
  write_text(dir / "two.csv.gz", gzip(text.substr(0, 1000)) + gzip(text.substr(1000)));
  const Log plain = read_log(dir / "a.csv");
  for (const char* name : {"a.csv.gz", "two.csv.gz"}) {
    const Log packed = read_log(dir / name);
    EXPECT_EQ(packed.columns, plain.columns);
    EXPECT_EQ(packed.meta.entries, plain.meta.entries);
    ASSERT_EQ(packed.values.rows(), 500);
    EXPECT_TRUE(packed.values.cwiseEqual(plain.values).count() + 1 == packed.values.size())
        << "every value but the missing one (NaN) equal";
    EXPECT_TRUE(std::isnan(packed.col("i1")[7]));
    EXPECT_EQ(packed.quality.missing_per_column, plain.quality.missing_per_column);
  }
}

TEST(GzipLog, WriteLogCompressesAGzPath) {
  TempDir dir("gz_write");
  write_text(dir / "a.csv", small_log_text());
  const Log plain = read_log(dir / "a.csv");
  write_log(dir / "b.csv.gz", plain);
  const std::string bytes = read_text(dir / "b.csv.gz");
  EXPECT_TRUE(is_gzip(bytes));
  EXPECT_LT(bytes.size(), read_text(dir / "a.csv").size() / 3);
  write_log(dir / "plain.csv", plain);
  EXPECT_TRUE(gunzip(bytes, "b") == read_text(dir / "plain.csv"))
      << "the same text the plain writer writes";
  write_log(dir / "c.csv.gz", plain);
  EXPECT_EQ(read_text(dir / "c.csv.gz"), bytes);  // deterministic bytes
}

TEST(GzipLog, StreamingWriterCompressesAsTheRowsCome) {
  TempDir dir("gz_stream");
  write_text(dir / "a.csv", small_log_text());
  const Log plain = read_log(dir / "a.csv");
  write_log(dir / "plain.csv", plain);
  {
    LogWriter writer(dir / "s.csv.gz", plain.meta, plain.columns);
    std::vector<double> row(static_cast<std::size_t>(plain.values.cols()));
    for (Eigen::Index r = 0; r < plain.rows(); ++r) {
      for (Eigen::Index c = 0; c < plain.values.cols(); ++c)
        row[static_cast<std::size_t>(c)] = plain.values(r, c);
      writer.write_row(row);
    }
    writer.close();
  }
  const std::string bytes = read_text(dir / "s.csv.gz");
  EXPECT_TRUE(is_gzip(bytes));
  EXPECT_TRUE(gunzip(bytes, "s") == read_text(dir / "plain.csv"));
  // Pieces through GzipStream are one member with the whole text.
  GzipStream stream;
  const std::string text = read_text(dir / "plain.csv");
  std::string packed;
  for (std::size_t at = 0; at < text.size(); at += 1000)
    packed.append(stream.write(std::string_view(text).substr(at, 1000)));
  packed.append(stream.finish());
  EXPECT_TRUE(gunzip(packed, "pieces") == text);
}

TEST(GzipLog, CorruptOrTruncatedDataNamesTheFile) {
  TempDir dir("gz_bad");
  std::string packed = gzip(small_log_text());
  std::string corrupt = packed;
  for (std::size_t k = 20; k < 60; ++k)
    corrupt[k] = static_cast<char>(corrupt[k] ^ 0x5a);
  write_text(dir / "corrupt.csv.gz", corrupt);
  std::string message = error_of(dir / "corrupt.csv.gz");
  EXPECT_NE(message.find("corrupt.csv.gz: gzip: corrupt compressed data"), std::string::npos)
      << message;
  write_text(dir / "cut.csv.gz", packed.substr(0, packed.size() / 2));
  message = error_of(dir / "cut.csv.gz");
  EXPECT_NE(message.find("cut.csv.gz: gzip: the compressed data ends early"), std::string::npos)
      << message;
  write_text(dir / "tail.csv.gz", packed + "junk");
  message = error_of(dir / "tail.csv.gz");
  EXPECT_NE(message.find("tail.csv.gz: gzip: 4 bytes of garbage"), std::string::npos) << message;
}

TEST(GzipLog, ACutLastRowInsideAGzFileIsSkippedAndSaid) {
  // Complete gzip data around a text cut inside its last row (a cut CSV compressed afterwards):
  // the row is skipped as in a plain file (a gzip stream cut short is an error, above).
  TempDir dir("gz_cut_row");
  write_text(dir / "cut.csv.gz", gzip("t,q1,dq1\n0,1,2\n0.1,1,3"));
  const Log log = read_log(dir / "cut.csv.gz");
  ASSERT_EQ(log.rows(), 1);
  EXPECT_EQ(log.col("dq1")[0], 2.0);
  EXPECT_EQ(log.quality.skipped_rows, 1u);
  EXPECT_EQ(log.quality.notes,
            std::vector<std::string>{(dir / "cut.csv.gz").string() +
                                     ":3: the file ends without a newline, inside this row: a "
                                     "cut file? The row is skipped, its last field may be cut "
                                     "short"});
}

TEST(GzipLog, ParseErrorsInsideAGzFileNameLineAndColumn) {
  TempDir dir("gz_line");
  write_text(dir / "bad.csv.gz", gzip("t,q1,dq1\n0,1,2\n0.1,x,3\n"));
  const std::string message = error_of(dir / "bad.csv.gz");
  EXPECT_NE(message.find("bad.csv.gz:3: q1: 'x' is not a number"), std::string::npos) << message;
}

}  // namespace
}  // namespace tpf::offline
