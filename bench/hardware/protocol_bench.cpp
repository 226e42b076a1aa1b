// Per-cycle protocol work of the arm loop, without I/O: what the CPU adds to the bus time.
#include <benchmark/benchmark.h>

#include <array>
#include <vector>

#include "dynamixel/protocol/fast_sync_read.hpp"
#include "dynamixel/protocol/instructions.hpp"
#include "dynamixel/protocol/packet_receiver.hpp"
#include "teensy/host/pad_stream_parser.hpp"

namespace {

using namespace tpf;

const std::uint8_t kIds[] = {1, 2, 3, 4};

/// Build the Fast Sync Read 574/10 request for four motors.
void BM_BuildFastSyncRead(benchmark::State& state) {
  std::array<std::uint8_t, dxl::kMaxPacketBytes> out{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        dxl::build_sync_read(dxl::Instruction::fast_sync_read, 574, 10, kIds, out));
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_BuildFastSyncRead);

/// Receive (header scan + CRC) and split the 64-byte four-motor response.
void BM_ReceiveFastSyncReadResponse(benchmark::State& state) {
  std::array<std::uint8_t, 40> data{};
  for (std::size_t k = 0; k < data.size(); ++k)
    data[k] = static_cast<std::uint8_t>(k * 37);
  const std::array<dxl::StatusError, 4> errors{};
  std::array<std::uint8_t, dxl::kMaxPacketBytes> wire{};
  const std::size_t n = dxl::build_fast_sync_read(10, kIds, data, errors, wire);
  dxl::PacketReceiver rx(dxl::PacketReceiver::Accept::status);
  std::array<std::uint8_t, 40> out{};
  std::array<dxl::StatusError, 4> out_errors{};
  for (auto _ : state) {
    rx.clear();
    rx.feed(std::span(wire).first(n));
    if (rx.next() != dxl::RxEvent::packet) state.SkipWithError("no packet");
    benchmark::DoNotOptimize(dxl::parse_fast_sync_read(rx.packet(), 10, kIds, out, out_errors));
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * n));
}
BENCHMARK(BM_ReceiveFastSyncReadResponse);

/// Parse a stream of 16-pad frames (COBS decode + CRC-16/CCITT + fields), bytes per second.
void BM_PadStreamParser(benchmark::State& state) {
  std::vector<std::uint8_t> stream = {0x00};
  for (std::uint16_t s = 0; s < 100; ++s) {
    pad::PadFrame f;
    f.seq = s;
    f.n = 16;
    for (int k = 0; k < 16; ++k)
      f.kpa[k] = 0.1f * k;
    std::uint8_t wire[pad::kMaxWireBytes];
    const std::size_t n = pad::encode_frame(f, wire);
    stream.insert(stream.end(), wire, wire + n);
  }
  for (auto _ : state) {
    pad::PadStreamParser parser;
    std::size_t frames = 0;
    parser.feed(stream, [&](const pad::PadFrame&) { ++frames; });
    benchmark::DoNotOptimize(frames);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * stream.size()));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * 100));
}
BENCHMARK(BM_PadStreamParser);

}  // namespace
