#include "clients/audio/synthesis/synth_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "clients/audio/synthesis/contact_pulse.hpp"

namespace thx::audio {

static_assert(kMaxPointNodes == 10, "a Point event carries a Tet10's nodes (ModalBody::Weights)");

SynthScene::SynthScene(std::vector<SoundingBody> bodies, double sample_rate_hz, std::size_t max_block,
                       std::uint32_t generation, std::shared_ptr<const RoughnessProfile> roughness)
    : roughness_(std::move(roughness)), sample_rate_hz_(sample_rate_hz), scratch_(max_block, 0.0f), generation_(generation) {
  voices_.reserve(bodies.size());
  for (SoundingBody& b : bodies) {
    const std::size_t m = b.frequency_hz.size();
    if (std::size_t(b.shapes.cols()) != m || b.shapes.rows() % 3 != 0)
      throw std::logic_error("sounding body '" + b.name + "': " + std::to_string(m) + " modes but a shape matrix of " +
                                  std::to_string(b.shapes.rows()) + " x " + std::to_string(b.shapes.cols()));
    Voice v{b.name, ResonatorBank(sample_rate_hz, m), {}, std::vector<double>(m, 0.0), std::size_t(b.shapes.rows() / 3), {}};
    for (double f : b.frequency_hz) v.omega.push_back(2.0 * std::numbers::pi * f);
    if (!v.bank.setModes(b.frequency_hz, b.decay_per_s))
      throw std::logic_error("sounding body '" + b.name + "': a mode frequency outside (0, Nyquist) or a negative decay");
    v.shapes.resize(std::size_t(b.shapes.rows()) * m);
    for (Eigen::Index r = 0; r < b.shapes.rows(); ++r)
      for (std::size_t k = 0; k < m; ++k) v.shapes[std::size_t(r) * m + k] = b.shapes(r, Eigen::Index(k));
    modes_ += m;
    voices_.push_back(std::move(v));
  }
}

void SynthScene::strikeNode(Voice& v, std::int32_t node, const double (&j)[3]) {
  const std::size_t m = v.g.size();
  const double* row = v.shapes.data() + std::size_t(3 * node) * m;
  for (std::size_t k = 0; k < m; ++k) v.g[k] = row[k] * j[0] + row[m + k] * j[1] + row[2 * m + k] * j[2];
  v.bank.strike(v.g);
}

bool SynthScene::validPoint(const Voice& v, const std::int32_t* nodes, std::int32_t count) const {
  if (count <= 0 || count > kMaxPointNodes) return false;
  for (int c = 0; c < count; ++c)
    if (nodes[c] < 0 || std::size_t(nodes[c]) >= v.nodes) return false;
  return true;
}

void SynthScene::pointGains(Voice& v, const std::int32_t* nodes, const double* weights, std::int32_t count,
                            const double (&j)[3]) {
  const std::size_t m = v.g.size();
  std::fill(v.g.begin(), v.g.end(), 0.0);
  // The sum of ModalBody::gainsAt, in its order.
  for (int c = 0; c < count; ++c) {
    const double* row = v.shapes.data() + std::size_t(3 * nodes[c]) * m;
    const double w = weights[c];
    for (std::size_t k = 0; k < m; ++k) v.g[k] += w * (row[k] * j[0] + row[m + k] * j[1] + row[2 * m + k] * j[2]);
  }
}

bool SynthScene::strike(const ExcitationEvent& e, std::int64_t micro_samples) {
  if (e.body >= voices_.size()) return false;
  Voice& v = voices_[e.body];
  switch (e.kind) {
    case ExcitationKind::Impulse:
      if (e.node < 0 || std::size_t(e.node) >= v.nodes) return false;
      strikeNode(v, e.node, e.impulse);
      return true;
    case ExcitationKind::Point: {
      if (!validPoint(v, e.point_nodes, e.point_count)) return false;
      pointGains(v, e.point_nodes, e.point_weights, e.point_count, e.impulse);
      const std::size_t m = v.g.size();
      if (e.pulse_s > 0)
        for (std::size_t k = 0; k < m; ++k) v.g[k] *= halfSinePulseFactor(v.omega[k], e.pulse_s);
      v.bank.strike(v.g);
      return true;
    }
    case ExcitationKind::Micro: {
      if (!roughness_ || segment_count_ >= kMaxSegments) return false;
      if (e.point_count > 0 ? !validPoint(v, e.point_nodes, e.point_count) : (e.node < 0 || std::size_t(e.node) >= v.nodes))
        return false;
      const std::int64_t count =
          micro_samples >= 0 ? micro_samples : std::llround(double(e.end_ns - e.time_ns) * 1e-9 * sample_rate_hz_);
      if (count <= 0) return true;  // no sample after the start's up to the end's
      Segment& s = segments_[segment_count_++];
      s.body = e.body;
      s.node = e.node;
      s.point_count = e.point_count;
      for (int c = 0; c < e.point_count; ++c) {
        s.point_nodes[c] = e.point_nodes[c];
        s.point_weights[c] = e.point_weights[c];
      }
      for (int i = 0; i < 3; ++i) s.direction[i] = e.impulse[i];
      s.wait = 1;  // the segment owns the samples after this one
      s.n = 0;
      s.count = std::size_t(count);
      s.s0 = e.s0, s.s1 = e.s1, s.f0 = e.f0, s.f1 = e.f1;
      s.level = microLevel(*roughness_, s.s0, s.s1, s.count);
      return true;
    }
  }
  return false;
}

void SynthScene::renderVoices(std::span<float> out) {
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

void SynthScene::render(std::span<float> out) {
  std::size_t i = 0;
  while (i < out.size() && segment_count_ > 0) {
    // A sample with force segments running: each strikes its force / fs, then the sample.
    for (std::size_t k = 0; k < segment_count_;) {
      Segment& s = segments_[k];
      if (s.wait > 0) {
        --s.wait;
        ++k;
        continue;
      }
      const double j = microForceAt(*roughness_, s.level, s.s0, s.s1, s.f0, s.f1, s.n, s.count) / sample_rate_hz_;
      if (j != 0.0) {
        const double impulse[3] = {s.direction[0] * j, s.direction[1] * j, s.direction[2] * j};
        Voice& v = voices_[s.body];
        if (s.point_count > 0) {
          pointGains(v, s.point_nodes, s.point_weights, s.point_count, impulse);
          v.bank.strike(v.g);
        } else {
          strikeNode(v, s.node, impulse);
        }
      }
      if (++s.n == s.count)
        segments_[k] = segments_[--segment_count_];  // done (order does not matter: strikes add)
      else
        ++k;
    }
    renderVoices(out.subspan(i, 1));
    ++i;
  }
  if (i < out.size()) renderVoices(out.subspan(i));
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
