#include "offline/log/gzip.hpp"

#include <zlib.h>

#include <algorithm>
#include <limits>

#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// zlib's total_in/avail_in are 32-bit: feed and drain it in pieces of at most this size.
constexpr std::size_t kChunk = std::size_t{1} << 30;

std::string zlib_message(const z_stream& stream, int code) {
  if (stream.msg != nullptr) return stream.msg;
  return code == Z_MEM_ERROR ? "out of memory" : "zlib error " + std::to_string(code);
}

}  // namespace

bool is_gzip(std::string_view bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

bool has_gzip_suffix(std::string_view path) {
  return path.size() > 3 && path.substr(path.size() - 3) == ".gz";
}

std::string gunzip(std::string_view compressed, std::string_view file) {
  std::string out;
  out.resize(std::max<std::size_t>(4 * compressed.size(), 1 << 16));
  std::size_t produced = 0, consumed = 0;
  while (consumed < compressed.size()) {  // one gzip member per pass
    z_stream stream{};
    if (inflateInit2(&stream, 15 + 16) != Z_OK)
      throw Error::at(file, 0, "", "gzip: cannot initialise zlib");
    int code = Z_OK;
    while (code != Z_STREAM_END) {
      if (produced == out.size()) out.resize(2 * out.size());
      const std::size_t in = std::min(compressed.size() - consumed, kChunk);
      const std::size_t room = std::min(out.size() - produced, kChunk);
      stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data() + consumed));
      stream.avail_in = static_cast<uInt>(in);
      stream.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
      stream.avail_out = static_cast<uInt>(room);
      code = inflate(&stream, Z_NO_FLUSH);
      consumed += in - stream.avail_in;
      produced += room - stream.avail_out;
      if (code == Z_BUF_ERROR && stream.avail_in == 0 && consumed == compressed.size()) {
        inflateEnd(&stream);
        throw Error::at(file, 0, "",
                        "gzip: the compressed data ends early (truncated file?) after " +
                            std::to_string(produced) + " bytes of text");
      }
      if (code != Z_OK && code != Z_STREAM_END && code != Z_BUF_ERROR) {
        const std::string message = zlib_message(stream, code);
        inflateEnd(&stream);
        throw Error::at(
            file, 0, "",
            "gzip: corrupt compressed data at byte " + std::to_string(consumed) + ": " + message);
      }
    }
    inflateEnd(&stream);
    // Trailing zero padding after the last member (some tools add it) is not another member.
    if (std::all_of(compressed.begin() + static_cast<std::ptrdiff_t>(consumed), compressed.end(),
                    [](char c) { return c == 0; }))
      break;
    if (!is_gzip(compressed.substr(consumed)))
      throw Error::at(file, 0, "",
                      "gzip: " + std::to_string(compressed.size() - consumed) +
                          " bytes of garbage after the compressed data");
  }
  out.resize(produced);
  return out;
}

struct GzipStream::State {
  z_stream stream{};
};

GzipStream::GzipStream() : state_(new State) {
  if (deflateInit2(&state_->stream, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    delete state_;
    throw Error("gzip: cannot initialise zlib");
  }
}

GzipStream::~GzipStream() {
  deflateEnd(&state_->stream);
  delete state_;
}

std::string_view GzipStream::write(std::string_view text) {
  return run(text, false);
}

std::string_view GzipStream::finish() {
  return run({}, true);
}

std::string_view GzipStream::run(std::string_view text, bool last) {
  z_stream& stream = state_->stream;
  out_.clear();
  std::size_t consumed = 0;
  while (true) {
    const std::size_t in = std::min(text.size() - consumed, kChunk);
    const bool final_piece = last && consumed + in == text.size();
    std::size_t produced = out_.size();
    out_.resize(produced + std::max<std::size_t>(deflateBound(&stream, in), 1 << 16));
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data() + consumed));
    stream.avail_in = static_cast<uInt>(in);
    stream.next_out = reinterpret_cast<Bytef*>(out_.data() + produced);
    stream.avail_out = static_cast<uInt>(std::min(out_.size() - produced, kChunk));
    const uInt room = stream.avail_out;
    const int code = deflate(&stream, final_piece ? Z_FINISH : Z_NO_FLUSH);
    if (code == Z_STREAM_ERROR) throw Error("gzip: zlib failed to compress");
    consumed += in - stream.avail_in;
    produced += room - stream.avail_out;
    out_.resize(produced);
    if (final_piece ? code == Z_STREAM_END : consumed == text.size() && stream.avail_out > 0)
      return out_;
  }
}

std::string gzip(std::string_view text) {
  GzipStream stream;
  std::string out(stream.write(text));
  out.append(stream.finish());
  return out;
}

}  // namespace tpf::offline
