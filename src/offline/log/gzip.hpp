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

/// True when `path` ends in ".gz" (the writers compress such files).
bool has_gzip_suffix(std::string_view path);

}  // namespace tpf::offline
