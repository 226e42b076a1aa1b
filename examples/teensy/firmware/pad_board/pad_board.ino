// Teensy 4.0 pad board: 16 pneumatic skin pads (Honeywell HSC…005PGAA3, 0–5 psi gauge, analog,
// ratiometric) through a CD74HC4067 multiplexer into A7; first-order filter per pad; one framed
// sample every 1 ms over USB serial (COBS + CRC-16/CCITT-FALSE, 0x00 delimiter; pad_frame.hpp).
//
// Wiring: mux S0..S3 on pins 22, 23, 1, 2; mux common (SIG) on A7; sensors powered from 3.3 V.
// Teensy 4.0 pins are NOT 5 V tolerant: a 5 V "…AA5" sensor needs a divider on its output and a
// second divider reading the supply so the conversion stays ratiometric (hardware.md §4).
// Host commands (one byte): 'z' re-captures the zero offsets.
#include <Arduino.h>

#include "pad_frame.hpp"

namespace {

constexpr int kPads = 16;
constexpr uint8_t kMuxSelect[4] = {22, 23, 1, 2};  // S0..S3
constexpr uint8_t kAdcPin = A7;
constexpr uint32_t kPeriodUs = 1000;       // 1 kHz frames
constexpr unsigned kSettleUs = 4;          // mux + ADC input settling
constexpr float kAlpha = 0.125f;           // y += α(x − y): τ = dt/α ≈ 8 ms, f_c ≈ 20 Hz
constexpr float kFullScale = 4095.0f;      // 12-bit ADC
constexpr float kKpaPerPsi = 6.894757f;
constexpr float kContactOnKpa = 0.5f;      // contact hysteresis
constexpr float kContactOffKpa = 0.3f;
constexpr int kZeroFrames = 500;           // 0.5 s of averaging for the zero offsets

float filtered[kPads];
float zero_kpa[kPads];
float zero_sum[kPads];
int zero_left = kZeroFrames;
uint32_t contact_mask = 0;
uint16_t seq = 0;
uint8_t pending_flags = 0;
elapsedMicros since_frame;

/// Ratiometric HSC transfer function A (10–90 %): P[psi] = 6.25·(Vout/Vsupply) − 0.625.
float counts_to_kpa(float counts) { return (6.25f * counts / kFullScale - 0.625f) * kKpaPerPsi; }

void select_channel(int k) {
  for (int b = 0; b < 4; ++b) digitalWriteFast(kMuxSelect[b], (k >> b) & 1);
}

void start_zeroing() {
  for (int k = 0; k < kPads; ++k) zero_sum[k] = 0.0f;
  zero_left = kZeroFrames;
  pending_flags |= tpf::pad::kFlagOffsetReset;
}

}  // namespace

void setup() {
  for (uint8_t pin : kMuxSelect) pinMode(pin, OUTPUT);
  analogReadResolution(12);
  analogReadAveraging(4);
  Serial.begin(0);  // USB CDC: always native USB speed, the baud argument is ignored
  for (int k = 0; k < kPads; ++k) {
    select_channel(k);
    delayMicroseconds(kSettleUs);
    filtered[k] = analogRead(kAdcPin);
  }
  start_zeroing();
}

void loop() {
  if (Serial.available() > 0 && Serial.read() == 'z') start_zeroing();
  if (since_frame < kPeriodUs) return;
  since_frame -= kPeriodUs;

  tpf::pad::PadFrame frame;
  frame.seq = seq++;
  frame.t_us = micros();
  frame.n = kPads;
  frame.flags = pending_flags;
  for (int k = 0; k < kPads; ++k) {
    select_channel(k);
    delayMicroseconds(kSettleUs);
    const int counts = analogRead(kAdcPin);
    if (counts <= 2 || counts >= 4093) frame.flags |= tpf::pad::kFlagSaturated;
    filtered[k] += kAlpha * (counts - filtered[k]);
    const float kpa = counts_to_kpa(filtered[k]);
    if (zero_left > 0) zero_sum[k] += kpa;
    frame.kpa[k] = kpa - zero_kpa[k];
    const float on = (contact_mask >> k) & 1u ? kContactOffKpa : kContactOnKpa;
    if (frame.kpa[k] > on) contact_mask |= 1u << k;
    else contact_mask &= ~(1u << k);
  }
  if (zero_left > 0 && --zero_left == 0)
    for (int k = 0; k < kPads; ++k) zero_kpa[k] = zero_sum[k] / kZeroFrames;
  frame.contact_mask = contact_mask;

  uint8_t wire[tpf::pad::kMaxWireBytes];
  const size_t n = tpf::pad::encode_frame(frame, wire);
  // Never block: if the host stopped reading, drop the frame (the host counts the seq gap).
  if (Serial.availableForWrite() >= static_cast<int>(n)) {
    Serial.write(wire, n);
    pending_flags = 0;
  }
}
