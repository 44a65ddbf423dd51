#include "clients/audio/live/audio_output.hpp"

#include <alsa/asoundlib.h>
#include <pthread.h>
#include <sched.h>
#include <sndfile.h>

#include <RtAudio.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/error.hpp"
#include "rt/clock.hpp"

namespace thx::audio {

// ---------------------------------------------------------------- TimerOutput

TimerOutput::TimerOutput(double sample_rate_hz, std::size_t block_frames, BlockCallback callback,
                         std::size_t capture_blocks)
    : sample_rate_hz_(sample_rate_hz),
      block_frames_(block_frames),
      callback_(std::move(callback)),
      block_(std::make_unique<AudioBlock>()) {
  if (block_frames < 1 || block_frames > kMaxBlockFrames)
    throw std::logic_error("block of " + std::to_string(block_frames) + " frames: expected 1.." +
                                std::to_string(kMaxBlockFrames));
  if (capture_blocks > 0) capture_ = std::make_unique<rt::SpscRing<AudioBlock>>(capture_blocks);
}

TimerOutput::~TimerOutput() { stop(); }

void TimerOutput::start() {
  if (running_.exchange(true)) return;
  thread_ = std::thread([this] { run(); });
}

void TimerOutput::stop() {
  if (!running_.exchange(false)) return;
  if (thread_.joinable()) thread_.join();
}

void TimerOutput::run() {
  // Below hapticd's servo (SCHED_FIFO 80) and its publisher (40), above ordinary threads;
  // without the privilege it stays SCHED_OTHER.
  sched_param sp{};
  sp.sched_priority = 30;
  realtime_ = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp) == 0;
  rt::MonotonicClock clock;
  const double period_ns = double(block_frames_) * 1e9 / sample_rate_hz_;
  const std::int64_t t0 = clock.nowNs();
  std::span<float> out(block_->samples, block_frames_);
  for (std::uint64_t k = 0; running_.load(std::memory_order_relaxed); ++k) {
    const std::int64_t deadline = t0 + std::llround(double(k) * period_ns);
    clock.sleepUntilNs(deadline);
    const std::int64_t now = clock.nowNs();
    if (now - deadline > max_late_ns_.load(std::memory_order_relaxed))
      max_late_ns_.store(now - deadline, std::memory_order_relaxed);
    callback_(out, now);
    block_->frames = std::uint32_t(block_frames_);
    if (capture_) capture_->push(*block_);
    blocks_.store(blocks_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  }
}

// -------------------------------------------------------------- RtAudioOutput

struct RtAudioOutput::Impl {
  std::unique_ptr<RtAudio> dac;
  BlockCallback callback;
  double sample_rate_hz = 44100.0;
};

namespace {

int rtCallback(void* output, void* /*input*/, unsigned int frames, double /*stream_time*/, RtAudioStreamStatus /*status*/,
               void* user) {
  auto* impl = static_cast<RtAudioOutput::Impl*>(user);
  impl->callback(std::span<float>(static_cast<float*>(output), frames), rt::monotonicNowNs());
  return 0;
}

// alsa-lib prints its own lines on stderr when there is no card ("Invalid CTL default"); the
// one-line message below says it once.
void quietAlsa(const char*, int, const char*, int, const char*, ...) {}

const char* apiName(RtAudio::Api api) {
  switch (api) {
    case RtAudio::LINUX_ALSA: return "ALSA";
    case RtAudio::LINUX_PULSE: return "PulseAudio";
    case RtAudio::UNIX_JACK: return "JACK";
    default: return "other";
  }
}

}  // namespace

std::unique_ptr<RtAudioOutput> RtAudioOutput::open(double sample_rate_hz, std::size_t block_frames,
                                                   BlockCallback callback, const std::string& api, std::string& why) {
  std::vector<RtAudio::Api> apis;
  if (api.empty()) apis = {RtAudio::LINUX_ALSA, RtAudio::LINUX_PULSE};
  else if (api == "alsa") apis = {RtAudio::LINUX_ALSA};
  else if (api == "pulse") apis = {RtAudio::LINUX_PULSE};
  else if (api == "jack") apis = {RtAudio::UNIX_JACK};
  else throw UsageError("--audio-api: expected alsa, pulse or jack, got '" + api + "'");
  std::string tried;
  snd_lib_error_set_handler(&quietAlsa);
  for (RtAudio::Api a : apis) {
    auto out = std::unique_ptr<RtAudioOutput>(new RtAudioOutput);
    out->impl_ = std::make_unique<Impl>();
    out->impl_->callback = callback;
    out->impl_->sample_rate_hz = sample_rate_hz;
    try {
      out->impl_->dac = std::make_unique<RtAudio>(a);
      RtAudio& dac = *out->impl_->dac;
      dac.showWarnings(false);
      if (dac.getDeviceCount() == 0) {
        tried += std::string(tried.empty() ? "" : "; ") + apiName(a) + ": no device";
        continue;
      }
      RtAudio::StreamParameters p;
      p.deviceId = dac.getDefaultOutputDevice();
      p.nChannels = 1;
      unsigned int frames = unsigned(block_frames);
      dac.openStream(&p, nullptr, RTAUDIO_FLOAT32, unsigned(std::lround(sample_rate_hz)), &frames, &rtCallback,
                     out->impl_.get());
      out->block_frames_ = frames;
      out->description_ = std::string(apiName(a)) + " device '" + dac.getDeviceInfo(p.deviceId).name + "'";
      return out;
    } catch (const RtAudioError& e) {
      std::string m = e.getMessage();
      m.erase(std::remove(m.begin(), m.end(), '\n'), m.end());
      tried += std::string(tried.empty() ? "" : "; ") + apiName(a) + ": " + m;
    }
  }
  why = "no sound device (" + tried + ")";
  return nullptr;
}

RtAudioOutput::~RtAudioOutput() {
  if (!impl_ || !impl_->dac) return;
  try {
    if (impl_->dac->isStreamRunning()) impl_->dac->stopStream();
    if (impl_->dac->isStreamOpen()) impl_->dac->closeStream();
  } catch (const RtAudioError&) {
  }
}

void RtAudioOutput::start() { impl_->dac->startStream(); }
void RtAudioOutput::stop() {
  if (impl_->dac->isStreamRunning()) impl_->dac->stopStream();
}

double RtAudioOutput::deviceLatencyS() const {
  try {
    return double(impl_->dac->getStreamLatency()) / impl_->sample_rate_hz;
  } catch (const RtAudioError&) {
    return 0.0;
  }
}

// ------------------------------------------------------------------ WavWriter

WavWriter::WavWriter(const std::string& path, int sample_rate_hz) : path_(path) {
  SF_INFO info{};
  info.samplerate = sample_rate_hz;
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_FLOAT;
  file_ = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!file_) throw Error(Error::Kind::Io, path + ": cannot be written: " + sf_strerror(nullptr));
  // libsndfile's PEAK chunk of a float WAV carries the time of writing: without it, the same
  // samples give the same bytes.
  sf_command(file_, SFC_SET_ADD_PEAK_CHUNK, nullptr, SF_FALSE);
}

WavWriter::~WavWriter() {
  if (file_) sf_close(file_);
}

void WavWriter::write(std::span<const float> samples) {
  const sf_count_t n = sf_writef_float(file_, samples.data(), sf_count_t(samples.size()));
  if (n != sf_count_t(samples.size())) throw Error(Error::Kind::Io, path_ + ": write failed");
  frames_ += std::uint64_t(n);
}

}  // namespace thx::audio
