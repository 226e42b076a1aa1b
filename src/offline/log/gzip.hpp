// gzip (RFC 1952) in memory, for logs stored as .csv.gz: every tool reads them, and the log
// writers write them when the path ends in ".gz".
#pragma once

#include <string>
#include <string_view>

namespace tpf::offline {

/// True when `bytes` begins with the gzip magic number (1f 8b).
bool is_gzip(std::string_view bytes);

/// The decompressed content of `compressed` (one or more gzip members, as `cat a.gz b.gz`
/// gives). Throws tpf::Error naming `file` when the data is corrupt or cut off.
std::string gunzip(std::string_view compressed, std::string_view file);

/// `text` as one gzip member (deflate level 6, no file name, time stamp 0: the same text gives
/// the same bytes on any machine).
std::string gzip(std::string_view text);

/// Streaming gzip: text in, compressed bytes out, one member (the same bytes as gzip() of all the
/// text together). For writers that cannot hold the whole text.
class GzipStream {
 public:
  GzipStream();
  GzipStream(const GzipStream&) = delete;
  GzipStream& operator=(const GzipStream&) = delete;
  ~GzipStream();
  /// Compresses `text`; returns the compressed bytes ready so far (valid until the next call).
  std::string_view write(std::string_view text);
  /// Ends the member; returns the last bytes. No write() after.
  std::string_view finish();

 private:
  std::string_view run(std::string_view text, bool last);
  struct State;
  State* state_;
  std::string out_;
};

/// True when `path` ends in ".gz" (the writers compress such files).
bool has_gzip_suffix(std::string_view path);

}  // namespace tpf::offline
