// wav-spectrogram: a sound file's spectrogram as a PNG (kHelp below).
#include <cstdio>
#include <string>
#include <vector>

#include "base/cli_number.hpp"
#include "base/error.hpp"
#include "clients/audio/spectrogram/spectrogram_image.hpp"
#include "clients/audio/spectrogram/stft.hpp"
#include "clients/audio/spectrogram/wav_file.hpp"
#include "base/program_main.hpp"

namespace {

using namespace thx::audio;

const char* const kHelp = R"(usage: wav-spectrogram IN.wav OUT.png [options]

The spectrogram of a sound file (WAV or anything libsndfile reads; channels are averaged) as a
PNG: short-time Fourier transform with a periodic Hann window, magnitude in dB relative to a
full-scale amplitude of 1 (a sine of amplitude A centred on a bin reads 20 log10(A/2)), time to the
right, frequency up on a linear axis labelled in kHz, a colour scale in dB. Each pixel shows the
loudest STFT cell it covers.

  --window N      STFT window in samples, a power of two (default 2048)
  --hop N         samples between windows (default 256)
  --range DB      colours span the loudest cell down to DB below it (default 90)
  --max-hz HZ     top of the frequency axis (default: the Nyquist frequency)
  --width PX      plot area width (default 1000); --height PX (default 420)
  --title TEXT    drawn above the plot (default: IN's file name)
  -h, --help      this text
)";

struct Options {
  std::string in, out, title;
  StftOptions stft{2048, 256};
  SpectrogramImageOptions image;
};

Options parse(const std::vector<std::string>& args) {
  Options o;
  std::vector<std::string> positional;
  bool titled = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw thx::UsageError(a + ": missing value");
      return args[++i];
    };
    if (a == "--window") o.stft.window = std::size_t(thx::cli::parseInteger(a, value(), 2, 1 << 20));
    else if (a == "--hop") o.stft.hop = std::size_t(thx::cli::parseInteger(a, value(), 1, 1 << 20));
    else if (a == "--range") o.image.range_db = thx::cli::parseNumber(a, value(), {1, 300, false, "dB"});
    else if (a == "--max-hz") o.image.max_hz = thx::cli::parseNumber(a, value(), {0, 1e6, true, "Hz"});
    else if (a == "--width") o.image.width = int(thx::cli::parseInteger(a, value(), 50, 8000));
    else if (a == "--height") o.image.height = int(thx::cli::parseInteger(a, value(), 50, 8000));
    else if (a == "--title") o.image.title = value(), titled = true;
    else if (!a.empty() && a[0] == '-') throw thx::UsageError("unknown option '" + a + "'");
    else positional.push_back(a);
  }
  if (positional.size() != 2) throw thx::UsageError("expected IN.wav and OUT.png, got " + std::to_string(positional.size()) + " file names");
  o.in = positional[0], o.out = positional[1];
  if (o.stft.window & (o.stft.window - 1))
    throw thx::UsageError("--window " + std::to_string(o.stft.window) + ": expected a power of two");
  if (!titled) o.image.title = o.in.substr(o.in.find_last_of('/') + 1);
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  return thx::runProgram("wav-spectrogram", kHelp, argc, argv, [](const std::vector<std::string>& args) {
    const Options o = parse(args);
    const MonoSound sound = readMonoSound(o.in);
    const Spectrogram s = stft(sound.samples, sound.sample_rate_hz, o.stft);
    writeSpectrogramPng(o.out, s, o.image);
    std::printf("wav-spectrogram: %s (%.2f s, %.0f Hz, %d channel%s): %zu frames x %zu bins -> %s\n", o.in.c_str(),
                double(sound.samples.size()) / sound.sample_rate_hz, sound.sample_rate_hz, sound.channels,
                sound.channels == 1 ? "" : "s", s.frames, s.bins, o.out.c_str());
    return 0;
  });
}
