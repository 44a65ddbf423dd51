#include "clients/audio/synth_scene.hpp"

#include <algorithm>
#include <stdexcept>

namespace thx::audio {

SynthScene::SynthScene(std::vector<SoundingBody> bodies, double sample_rate_hz, std::size_t max_block,
                       std::uint32_t generation)
    : scratch_(max_block, 0.0f), generation_(generation) {
  voices_.reserve(bodies.size());
  for (SoundingBody& b : bodies) {
    const std::size_t m = b.frequency_hz.size();
    if (std::size_t(b.shapes.cols()) != m || b.shapes.rows() % 3 != 0)
      throw std::invalid_argument("sounding body '" + b.name + "': " + std::to_string(m) + " modes but a shape matrix of " +
                                  std::to_string(b.shapes.rows()) + " x " + std::to_string(b.shapes.cols()));
    Voice v{b.name, ResonatorBank(sample_rate_hz, m), {}, std::vector<double>(m, 0.0), std::size_t(b.shapes.rows() / 3)};
    if (!v.bank.setModes(b.frequency_hz, b.decay_per_s))
      throw std::invalid_argument("sounding body '" + b.name + "': a mode frequency outside (0, Nyquist) or a negative decay");
    v.shapes.resize(std::size_t(b.shapes.rows()) * m);
    for (Eigen::Index r = 0; r < b.shapes.rows(); ++r)
      for (std::size_t k = 0; k < m; ++k) v.shapes[std::size_t(r) * m + k] = b.shapes(r, Eigen::Index(k));
    modes_ += m;
    voices_.push_back(std::move(v));
  }
}

bool SynthScene::strike(const ExcitationEvent& e) {
  if (e.body >= voices_.size()) return false;
  Voice& v = voices_[e.body];
  if (e.node < 0 || std::size_t(e.node) >= v.nodes) return false;
  const std::size_t m = v.g.size();
  const double* row = v.shapes.data() + std::size_t(3 * e.node) * m;
  for (std::size_t k = 0; k < m; ++k)
    v.g[k] = row[k] * e.impulse[0] + row[m + k] * e.impulse[1] + row[2 * m + k] * e.impulse[2];
  v.bank.strike(v.g);
  return true;
}

void SynthScene::render(std::span<float> out) {
  if (voices_.empty()) {
    std::fill(out.begin(), out.end(), 0.0f);
    return;
  }
  voices_.front().bank.render(out);
  for (std::size_t b = 1; b < voices_.size(); ++b) {
    for (std::size_t done = 0; done < out.size(); done += scratch_.size()) {
      const std::size_t n = std::min(scratch_.size(), out.size() - done);
      std::span<float> part(scratch_.data(), n);
      voices_[b].bank.render(part);
      for (std::size_t i = 0; i < n; ++i) out[done + i] += part[i];
    }
  }
}

void SynthScene::setBudget(std::size_t total) {
  if (modes_ == 0) return;
  for (Voice& v : voices_) v.bank.setBudget(v.bank.size() * std::min(total, modes_) / modes_);
}

std::size_t SynthScene::renderedModes() const {
  std::size_t n = 0;
  for (const Voice& v : voices_) n += v.bank.lastRenderedModes();
  return n;
}

}  // namespace thx::audio
