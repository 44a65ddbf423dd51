#include "clients/physics_client/pen_path.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <type_traits>
#include <variant>

namespace thx::physclient {

namespace {

std::string trim(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

[[noreturn]] void fail(const std::string& where, const std::string& field, const std::string& problem,
                       const std::string& expected, const std::string& got) {
  throw PenPathError(where + ": " + field + ": " + problem + "; expected " + expected + ", got '" + got + "'");
}

}  // namespace

std::vector<PenSample> parsePenCsv(const std::string& text, const std::string& source) {
  static const char* kFields[] = {"t_s", "x_m", "y_m", "z_m"};
  std::vector<PenSample> out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = source + ":" + std::to_string(number);
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    line = trim(line);
    if (line.empty()) continue;
    std::vector<std::string> cells;
    std::stringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) cells.push_back(trim(cell));
    if (out.empty() && number > 0 && !cells.empty() && lower(cells[0]) == "t_s") {
      std::string joined;
      for (const std::string& c : cells) joined += (joined.empty() ? "" : ", ") + lower(c);
      if (joined != "t_s, x_m, y_m, z_m") fail(where, "header", "unexpected header", "'t_s, x_m, y_m, z_m'", line);
      continue;
    }
    if (cells.size() != 4) fail(where, "row", "wrong number of values", "4 values: t_s, x_m, y_m, z_m", line);
    double v[4];
    for (int k = 0; k < 4; ++k) {
      const std::string& c = cells[std::size_t(k)];
      char* end = nullptr;
      v[k] = std::strtod(c.c_str(), &end);
      if (c.empty() || end == nullptr || *end != '\0')
        fail(where, kFields[k], "not a number", "a finite number", c);
      if (!std::isfinite(v[k])) fail(where, kFields[k], "not a finite number", "a finite number", c);
      if (k > 0 && std::fabs(v[k]) > 100.0) fail(where, kFields[k], "out of range", "a position in [-100, 100] m", c);
    }
    if (v[0] < 0) fail(where, "t_s", "negative time", "a time >= 0 s", cells[0]);
    if (!out.empty() && v[0] <= out.back().t_s)
      fail(where, "t_s", "time not increasing", "a time after " + std::to_string(out.back().t_s) + " s", cells[0]);
    PenSample s;
    s.t_s = v[0];
    s.p_world = {v[1], v[2], v[3]};
    out.push_back(s);
  }
  if (out.size() < 2)
    throw PenPathError(source + ": too few samples; expected at least 2 rows of t_s, x_m, y_m, z_m, got " +
                       std::to_string(out.size()));
  return out;
}

std::vector<PenSample> loadPenCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw PenPathError(path + ": cannot open the pen path; expected a readable CSV file of t_s, x_m, y_m, z_m");
  std::ostringstream text;
  text << in.rdbuf();
  return parsePenCsv(text.str(), path);
}

std::vector<PenSample> penPathFromScript(const PhysicsScene& scene, double dt_s) {
  if (scene.meshGround() != nullptr)
    throw PenPathError(scene.scene().source +
                       ": device.script: --pen-script follows the script on the plane; on a mesh surface (surface.mesh) "
                       "record hapticd's pen (`hapticd --lockstep --record FILE`) and pass --replay-log FILE");
  const tex::TexturedSurface& surface = scene.surface();
  std::vector<PenSample> out;
  double t = 0.0;
  std::optional<Eigen::Vector2d> at;
  std::optional<Eigen::Vector3d> lifted;  // where a move left the pen (off the surface)
  auto emit = [&](const Eigen::Vector2d& xy) {
    const tex::SurfacePoint sp = surface.at(xy.x(), xy.y());
    PenSample s;
    s.t_s = t;
    s.p_world = surface.toWorld(Eigen::Vector3d(xy.x(), xy.y(), sp.height_m));
    out.push_back(s);
  };
  for (const scene::ScriptStep& step : scene.scene().device.script) {
    std::visit(
        [&](const auto& s) {
          using T = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<T, scene::HoldStep>) {
            const auto here = [&] {
              if (lifted)
                out.push_back(PenSample{t, surface.toWorld(*lifted)});
              else if (at)
                emit(*at);
            };
            here();
            t += s.duration_s;
            here();
          } else if constexpr (std::is_same_v<T, scene::PressStep>) {
            at = s.position_m;
            emit(*at);
            t += s.duration_s;
            emit(*at);
          } else if constexpr (std::is_same_v<T, scene::StrokeStep>) {
            const double length = (s.to_m - s.from_m).norm();
            const double duration = length / s.speed_m_per_s;
            const int n = std::max(1, int(std::ceil(duration / dt_s)));
            for (int k = 0; k <= n; ++k) {
              const double a = double(k) / n;
              at = s.from_m + a * (s.to_m - s.from_m);
              emit(*at);
              if (k < n) t += duration / n;
            }
          } else if constexpr (std::is_same_v<T, scene::MoveStep>) {
            // From where the pen is (on the surface, or where the last move left it) straight to
            // the move's point, z its height above the plane.
            const Eigen::Vector3d from = lifted ? *lifted
                                         : at   ? Eigen::Vector3d(at->x(), at->y(), surface.at(at->x(), at->y()).height_m)
                                                : Eigen::Vector3d(s.to_m);
            const int n = std::max(1, int(std::ceil(s.duration_s / dt_s)));
            for (int k = 0; k <= n; ++k) {
              const Eigen::Vector3d p = from + (double(k) / n) * (s.to_m - from);
              out.push_back(PenSample{t, surface.toWorld(p)});
              if (k < n) t += s.duration_s / n;
            }
            lifted = s.to_m;
            at = Eigen::Vector2d(s.to_m.x(), s.to_m.y());
          } else {
            throw PenPathError(scene.scene().source +
                               ": device.script: path_file steps cannot be followed without hapticd; expected press, "
                               "stroke, hold and move steps (or run against hapticd, or --replay-log)");
          }
          if constexpr (!std::is_same_v<T, scene::MoveStep> && !std::is_same_v<T, scene::HoldStep>) lifted.reset();
          // Successive emits at the same time (a teleport) keep the times increasing.
          for (std::size_t i = 1; i < out.size(); ++i)
            if (out[i].t_s <= out[i - 1].t_s) out[i].t_s = out[i - 1].t_s + 1e-9;
        },
        step);
  }
  return out;
}

PenPath::PenPath(std::vector<PenSample> samples) : samples_(std::move(samples)) {
  if (samples_.empty()) throw PenPathError("pen path: no samples");
  for (std::size_t i = 1; i < samples_.size(); ++i)
    if (!(samples_[i].t_s > samples_[i - 1].t_s)) throw PenPathError("pen path: times not increasing");
}

std::size_t PenPath::indexAt(double t) const {
  if (hint_ >= samples_.size() || samples_[hint_].t_s > t) hint_ = 0;
  while (hint_ + 1 < samples_.size() && samples_[hint_ + 1].t_s <= t) ++hint_;
  return hint_;
}

PenPath::Bracket PenPath::bracketAt(double t) const {
  if (t <= samples_.front().t_s) return {&samples_.front(), &samples_.front(), 0.0};
  if (t >= samples_.back().t_s) return {&samples_.back(), &samples_.back(), 0.0};
  const std::size_t i = indexAt(t);
  const PenSample& a = samples_[i];
  const PenSample& b = samples_[i + 1];
  return {&a, &b, (t - a.t_s) / (b.t_s - a.t_s)};
}

Eigen::Vector3d PenPath::at(double t) const {
  const Bracket k = bracketAt(t);
  return k.a->p_world + k.w * (k.b->p_world - k.a->p_world);
}

Eigen::Quaterniond PenPath::orientationAt(double t) const {
  const Bracket k = bracketAt(t);
  return k.a->q_world.slerp(k.w, k.b->q_world);
}

std::int64_t PenPath::tickAt(double t) const {
  if (t < samples_.front().t_s) return -1;
  return samples_[indexAt(t)].tick;
}

}  // namespace thx::physclient
