#pragma once
// Where the live client's blocks go (docs/audio.md, "Live audio"):
//  - RtAudioOutput: a sound device through RtAudio (ALSA, then PulseAudio; JACK on request). The
//    device's thread calls the callback; the device's own latency is what RtAudio reports.
//  - TimerOutput: a thread that calls the same callback at the block period on CLOCK_MONOTONIC
//    (absolute sleeps, no drift), standing in for a device where there is none (this machine),
//    for measurements and tests. Its blocks can be captured into a ring for a WAV writer.
//  - WavWriter: libsndfile, 32-bit float mono.
// The callback gets the block and the time its first sample is produced (CLOCK_MONOTONIC ns).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <thread>

#include "rt/spsc_ring.hpp"

struct sf_private_tag;

namespace thx::audio {

using BlockCallback = std::function<void(std::span<float> block, std::int64_t block_start_ns)>;

constexpr std::size_t kMaxBlockFrames = 4096;

struct AudioBlock {
  std::uint32_t frames = 0;
  float samples[kMaxBlockFrames];
};

class TimerOutput {
 public:
  // block_frames in [1, kMaxBlockFrames] (else std::logic_error: the command line checks --block);
  // capture_blocks > 0 keeps that many blocks for capture().
  TimerOutput(double sample_rate_hz, std::size_t block_frames, BlockCallback callback, std::size_t capture_blocks = 0);
  ~TimerOutput();  // stops
  void start();
  void stop();
  // Blocks produced, oldest first (a full ring drops the new block and counts it).
  rt::SpscRing<AudioBlock>* capture() { return capture_.get(); }
  std::uint64_t blocks() const { return blocks_.load(std::memory_order_relaxed); }
  // Wake-up lateness of the timer thread, the largest so far (ns).
  std::int64_t maxWakeLateNs() const { return max_late_ns_.load(std::memory_order_relaxed); }
  bool realtimePriority() const { return realtime_; }

 private:
  void run();
  double sample_rate_hz_;
  std::size_t block_frames_;
  BlockCallback callback_;
  std::unique_ptr<rt::SpscRing<AudioBlock>> capture_;
  std::unique_ptr<AudioBlock> block_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<std::uint64_t> blocks_{0};
  std::atomic<std::int64_t> max_late_ns_{0};
  bool realtime_ = false;
};

class RtAudioOutput {
 public:
  // The default output device of the first API that opens one, or nullptr and `why` (one line).
  // api: "" (ALSA, then PulseAudio), "alsa", "pulse" or "jack".
  static std::unique_ptr<RtAudioOutput> open(double sample_rate_hz, std::size_t block_frames, BlockCallback callback,
                                             const std::string& api, std::string& why);
  ~RtAudioOutput();
  void start();
  void stop();
  const std::string& description() const { return description_; }
  // The device's latency as RtAudio reports it (frames / sample rate); 0 when it reports none.
  double deviceLatencyS() const;
  std::size_t blockFrames() const { return block_frames_; }

  struct Impl;

 private:
  RtAudioOutput() = default;
  std::unique_ptr<Impl> impl_;
  std::string description_;
  std::size_t block_frames_ = 0;
};

class WavWriter {
 public:
  // Throws thx::Error (Io) naming the path.
  WavWriter(const std::string& path, int sample_rate_hz);
  ~WavWriter();
  WavWriter(const WavWriter&) = delete;
  WavWriter& operator=(const WavWriter&) = delete;
  void write(std::span<const float> samples);
  std::uint64_t frames() const { return frames_; }

 private:
  std::string path_;
  sf_private_tag* file_ = nullptr;
  std::uint64_t frames_ = 0;
};

}  // namespace thx::audio
