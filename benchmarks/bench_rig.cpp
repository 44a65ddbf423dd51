#include "benchmarks/bench_rig.hpp"

#include <sys/utsname.h>

#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "scenes/scene_loader.hpp"
#include "server/scene_device.hpp"

namespace thx::bench {

std::string sourceDir() { return THX_SOURCE_DIR; }

SceneTexture loadSceneTexture(const std::string& scene_path, int size_override) {
  SceneTexture st;
  st.scene = scene::loadScene(scene_path);
  if (size_override > 0) {
    if (st.scene.surface.texture.kind != scene::TextureSource::Kind::Generator) {
      throw std::runtime_error(scene_path + ": a size override needs a generated texture");
    }
    st.scene.surface.texture.generator.size = size_override;
  }
  st.surface = scene::buildSceneSurface(st.scene);
  return st;
}

PlacedSurface::PlacedSurface(const scene::Scene& sc, const tex::TextureMap& map, bool relief)
    : surface(scene::placeOnScenePlane(sc, map, relief)) {}

namespace {
srv::ServoRigConfig hapticdWiring(const scene::Scene& sc, bool crease) {
  srv::ServoRigConfig c = srv::servoRigConfigFor(sc);
  c.renderer.crease_handling = crease;
  return c;
}
}  // namespace

ServerRig::ServerRig(const scene::Scene& sc, const tex::TextureMap& map, bool relief, bool crease,
                     dev::HapticDevice& device)
    : PlacedSurface(sc, map, relief), srv::ServoRig(device, surface, hapticdWiring(sc, crease)) {}

double Recording::contactFraction() const {
  if (in_contact.empty()) return 0.0;
  std::size_t n = 0;
  for (char c : in_contact) n += c ? 1 : 0;
  return double(n) / double(in_contact.size());
}

Recording recordRun(const scene::Scene& sc, const tex::TextureMap& map, bool relief, bool crease) {
  dev::SimPhantom device(srv::simConfigFor(sc, /*lockstep=*/true), srv::handScriptFor(sc));
  TapDevice tap(device);
  ServerRig rig(sc, map, relief, crease, tap);
  const double duration_s = device.script().duration() + 0.5;
  const std::size_t ticks = std::size_t(std::llround(duration_s * sc.rates.servo_hz));
  tap.states.reserve(ticks);
  tap.commands.reserve(ticks);
  Recording rec;
  rec.in_contact.reserve(ticks);
  tap.open();
  for (std::size_t k = 0; k < ticks; ++k) {
    const srv::TickRecord& r = rig.tick();
    rec.in_contact.push_back(r.in_contact ? 1 : 0);
    if ((k & 511) == 511) rig.drain();
  }
  tap.close();
  rec.states = std::move(tap.states);
  rec.commands = std::move(tap.commands);
  rec.first_contact = rec.in_contact.size();
  for (std::size_t k = 0; k < rec.in_contact.size(); ++k) {
    if (!rec.in_contact[k]) continue;
    if (rec.first_contact == rec.in_contact.size()) rec.first_contact = k;
    rec.last_contact = k;
  }
  if (rec.first_contact == rec.in_contact.size()) rec.first_contact = 1;  // never: last < first
  return rec;
}

void writeTextFile(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
  f.close();
  if (!f) throw std::runtime_error("cannot write " + path);
}

std::string fmt(const char* format, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, format);
  std::vsnprintf(buf, sizeof buf, format, ap);
  va_end(ap);
  return buf;
}

namespace {
std::string firstLineWith(const char* path, const std::string& key) {
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind(key, 0) == 0) {
      const auto colon = line.find(':');
      std::string v = colon == std::string::npos ? line : line.substr(colon + 1);
      while (!v.empty() && (v.front() == ' ' || v.front() == '\t')) v.erase(v.begin());
      return v;
    }
  }
  return "";
}
}  // namespace

std::string machineDescription() {
  // Cached at the first call (each benchmark calls it when it starts), so the load average
  // quoted is the one the measurements began under.
  static const std::string text = [] {
  utsname u{};
  uname(&u);
  std::string cpu = firstLineWith("/proc/cpuinfo", "model name");
  std::string clock;
  std::ifstream cs("/sys/devices/system/clocksource/clocksource0/current_clocksource");
  std::getline(cs, clock);
  const bool vm = !firstLineWith("/proc/cpuinfo", "flags").empty() &&
                  firstLineWith("/proc/cpuinfo", "flags").find("hypervisor") != std::string::npos;
  std::string load;
  std::ifstream la("/proc/loadavg");
  std::getline(la, load);
  load = load.substr(0, load.find(' ', load.find(' ', load.find(' ') + 1) + 1));
  return fmt("%s, %u CPUs%s, Linux %s (%s), clocksource %s; load average at start %s", cpu.c_str(),
             std::thread::hardware_concurrency(), vm ? " (virtual machine)" : "", u.release, u.version, clock.c_str(),
             load.c_str());
  }();
  return text;
}

std::string isoTimeNow() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

}  // namespace thx::bench
