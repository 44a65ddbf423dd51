// Speed against error for the physics client (issue 6, docs/design.md §6): time per step and memory
// for a sphere and a box on the same surface as a plain plane, a normal map, a relief map, a
// btHeightfieldTerrainShape and a btBvhTriangleMeshShape at 64² ... 1024² samples, with the
// outcome error of each against analytic answers:
//  - flat:  a ball rolling at 0.05 m/s keeps its speed (the timed run for the sphere); a ball and
//           a box left at rest stay at rest (the box's run is its timed run);
//  - slope: a uniform 10° slope: a ball rolls at a = 5/7 g sinθ cosθ horizontally (real slope) or
//           5/7 g tanθ (normal map: a virtual slope on a flat plane); a box with μ = 0.1 slides at
//           g (sinθ − μ cosθ) cosθ, or g (tanθ − μ) / (1 + μ tanθ) on the normal map;
//  - bump:  a 1 mm high, 3 cm wide cos² ridge: the rolling ball's escape speed is the energy
//           threshold sqrt(10/7 g H), found by bisection.
// Heightfield and mesh runs also repeat the flat sphere cases with gContactBreakingThreshold
// lowered from Bullet's 0.02 to 0.002 (the tuning of docs/design.md §7 fact 8).
//
// Usage: bench_physics [--sizes 64,128,...] [--reps N] [--json F] [--csv F] [--md F] [--png F]
// Progress goes to stderr. Takes about 2 minutes on the project's 2-core VM.
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <sys/utsname.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "base/cli_number.hpp"
#include "benchmarks/bench_help.hpp"
#include "benchmarks/bench_physics_grounds.hpp"
#include "benchmarks/bench_stamp.hpp"
#include "tools/report/plot.hpp"
#include "clients/physics/bullet_convert.hpp"

namespace thx::bench {
namespace {

constexpr double kDt = 1e-3, kG = 9.81, kPi = std::numbers::pi;
constexpr double kRadius = 0.01, kBallMass = 0.05, kBoxHalf = 0.01, kBoxMass = 0.05;
constexpr double kRollSpeed = 0.05;
constexpr double kSlopeDeg = 10.0, kBoxMu = 0.1, kBallMu = 0.5;
constexpr double kBumpH = 1e-3, kBumpW = 0.03;
constexpr double kTunedBreaking = 0.002;

double deg(double d) { return d * kPi / 180.0; }

constexpr int kMaxSize = 1024;             // --sizes' bound (the BVH mesh's, run())
constexpr int kEdgeUtilityMaxSize = 512;  // the edge map takes seconds to build beyond this
std::string groundLabel(const Ground& g) {
  return std::string(repName(g.rep())) + (g.internalEdges() ? " + edge utility" : "");
}

std::string fmt(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string fmt(const char* format, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, format);
  std::vsnprintf(buf, sizeof buf, format, ap);
  va_end(ap);
  return buf;
}

std::string firstLineWith(const char* path, const char* key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(colon + 2);
    }
  return "";
}

std::string machineDescription() {
  utsname u{};
  uname(&u);
  const std::string flags = firstLineWith("/proc/cpuinfo", "flags");
  std::string load;
  std::ifstream la("/proc/loadavg");
  std::getline(la, load);
  load = load.substr(0, load.find(' ', load.find(' ', load.find(' ') + 1) + 1));
  return fmt("%s, %u CPUs%s, Linux %s; load average at start %s", firstLineWith("/proc/cpuinfo", "model name").c_str(),
             std::thread::hardware_concurrency(), flags.find("hypervisor") != std::string::npos ? " (virtual machine)" : "",
             u.release, load.c_str());
}

std::string isoTimeNow() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t k = std::min(v.size() - 1, std::size_t(p * double(v.size() - 1) + 0.5));
  return v[k];
}

// Temporarily sets Bullet's global contact breaking threshold (read when manifolds are made).
struct BreakingThreshold {
  btScalar saved;
  explicit BreakingThreshold(double value) : saved(gContactBreakingThreshold) {
    gContactBreakingThreshold = static_cast<btScalar>(value);
  }
  ~BreakingThreshold() { gContactBreakingThreshold = saved; }
};

// ---------------------------------------------------------------------------------------------
// Surfaces.

SurfaceSpec flatSurface() { return {"flat", 0.5, [](double, double) { return 0.0; }, 0.0, true}; }
SurfaceSpec slopeSurface() {
  const double t = std::tan(deg(kSlopeDeg));
  return {"slope", 0.5, [t](double x, double) { return -t * x; }, kSlopeDeg, false};
}
SurfaceSpec bumpSurface() {
  return {"bump", 0.5,
          [](double x, double) {
            return std::fabs(x) < 0.5 * kBumpW ? kBumpH * std::pow(std::cos(kPi * x / kBumpW), 2) : 0.0;
          },
          0.0, false};
}

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(x, y, z);
  return t;
}

// Where the ground's surface is for a body resting on it (world z of the surface under x): the
// normal map's plane is flat at 0; the others follow h.
double groundZ(const Ground& g, const SurfaceSpec& s, double x) {
  return g.rep() == Rep::Normal ? 0.0 : s.height(x, 0.0);
}

// ---------------------------------------------------------------------------------------------
// Results.

struct Timing {
  std::string rep, shape;
  int size = 0;                  // samples per side (0: the plain plane, size-independent)
  double breaking = 0.02;        // gContactBreakingThreshold during the run
  int steps = 0;
  double median_us = 0, p90_us = 0, cpu_mean_us = 0;  // median over repetitions of each repetition's value
  double median_lo_us = 0, median_hi_us = 0;           // range of the per-repetition medians
  int reps = 1;
  double contacts = 0;           // mean contact points per step
  double manifold_threshold_m = 0;
};

struct Accuracy {
  std::string rep, case_name, shape, unit;
  int size = 0;
  double breaking = 0.02;
  double expected = 0, measured = 0;
  double error = 0;       // measured - expected (in unit)
  double rel_error = 0;   // error / expected (NaN where expected is 0)
  std::string note;
};

struct GroundInfo {
  std::string rep;
  int size = 0;
  double build_ms = 0;
  long long rss_bytes = 0, source_bytes = 0, triangles = 0;
};

struct Results {
  std::vector<Timing> timing;
  std::vector<Accuracy> accuracy;
  std::vector<GroundInfo> grounds;
  std::map<std::string, std::string> thresholds;
};

// ---------------------------------------------------------------------------------------------
// Runs.

struct StepStats {
  std::vector<double> step_us;
  double cpu_s = 0;
  double contacts = 0;
};

// Steps `steps` times, timing every step (wall clock) and the block (thread CPU time).
StepStats timedSteps(Sim& sim, int steps, const std::function<void(int)>& after = nullptr) {
  StepStats s;
  s.step_us.reserve(std::size_t(steps));
  long long contacts = 0;
  const double cpu0 = threadCpuSeconds();
  for (int k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    sim.world.step(kDt);
    const auto t1 = std::chrono::steady_clock::now();
    s.step_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    contacts += sim.contactPoints();
    if (after) after(k);
  }
  s.cpu_s = threadCpuSeconds() - cpu0;
  s.contacts = double(contacts) / std::max(1, steps);
  return s;
}

Timing toTiming(const Ground& g, const char* shape, double breaking, const std::vector<StepStats>& reps, Sim& sim) {
  Timing t;
  t.rep = groundLabel(g);
  t.shape = shape;
  t.size = g.rep() == Rep::Plain ? 0 : g.samples();
  t.breaking = breaking;
  t.reps = int(reps.size());
  std::vector<double> med, p90, cpu;
  for (const StepStats& s : reps) {
    med.push_back(percentile(s.step_us, 0.5));
    p90.push_back(percentile(s.step_us, 0.9));
    cpu.push_back(1e6 * s.cpu_s / double(std::max<std::size_t>(1, s.step_us.size())));
    t.contacts += s.contacts / double(reps.size());
  }
  t.steps = reps.empty() ? 0 : int(reps.front().step_us.size());
  t.median_us = percentile(med, 0.5);
  t.median_lo_us = *std::min_element(med.begin(), med.end());
  t.median_hi_us = *std::max_element(med.begin(), med.end());
  t.p90_us = percentile(p90, 0.5);
  t.cpu_mean_us = percentile(cpu, 0.5);
  t.manifold_threshold_m = sim.manifoldBreakingThreshold();
  return t;
}

Accuracy accuracy(const Ground& g, const char* case_name, const char* shape, const char* unit, double breaking,
                  double expected, double measured, std::string note = {}) {
  Accuracy a;
  a.rep = groundLabel(g);
  a.size = g.rep() == Rep::Plain ? 0 : g.samples();
  a.case_name = case_name;
  a.shape = shape;
  a.unit = unit;
  a.breaking = breaking;
  a.expected = expected;
  a.measured = measured;
  a.error = measured - expected;
  a.rel_error = expected != 0.0 ? a.error / expected : std::nan("");
  a.note = std::move(note);
  return a;
}

btRigidBody& addBall(Sim& sim, const Eigen::Isometry3d& pose, double mu = kBallMu) {
  sim.object = &sim.world.addSphere(kRadius, kBallMass, pose, {mu, 0.0, 0.0});
  return *sim.object;
}
btRigidBody& addBox(Sim& sim, const Eigen::Isometry3d& pose, double mu) {
  sim.object = &sim.world.addBox({kBoxHalf, kBoxHalf, kBoxHalf}, kBoxMass, pose, {mu, 0.0, 0.0});
  return *sim.object;
}
void setRolling(btRigidBody& ball, double v) { phys::setVelocity(ball, {v, 0, 0}, {0, v / kRadius, 0}); }

int g_reps = 3;  // timed repetitions (--reps)

// Flat: rolling ball (timed, g_reps repetitions; the outcome from the first) and ball at rest.
void flatSphereCases(const Ground& g, const SurfaceSpec& s, double breaking, bool timed, Results& r) {
  const BreakingThreshold guard(breaking);
  {
    std::vector<StepStats> reps;
    std::unique_ptr<Sim> last;
    for (int rep = 0; rep < (timed ? g_reps : 1); ++rep) {
      auto sim = std::make_unique<Sim>(g);
      btRigidBody& ball = addBall(*sim, at(-0.1, 0, groundZ(g, s, -0.1) + kRadius));
      setRolling(ball, kRollSpeed);
      for (int k = 0; k < 200; ++k) sim->world.step(kDt);
      double max_dev = 0.0, max_sink = 0.0;
      reps.push_back(timedSteps(*sim, 2000, [&](int) {
        max_dev = std::max(max_dev, std::fabs(phys::velocityOf(ball).head<2>().norm() - kRollSpeed));
        max_sink = std::max(max_sink, groundZ(g, s, 0.0) + kRadius - phys::positionOf(ball).z());
      }));
      if (rep == 0)
        r.accuracy.push_back(accuracy(g, "rolling 0.05 m/s on flat, speed after 2.2 s", "sphere", "m/s", breaking,
                                      kRollSpeed, phys::velocityOf(ball).head<2>().norm(),
                                      fmt("max |Δv| %.2g m/s", max_dev)));
      if (rep == 0)
        r.accuracy.push_back(accuracy(g, "rolling 0.05 m/s on flat, max sink of the centre", "sphere", "mm", breaking, 0.0,
                                      1e3 * max_sink, "how far the centre went below r over the surface"));
      last = std::move(sim);
    }
    if (timed) r.timing.push_back(toTiming(g, "sphere", breaking, reps, *last));
  }
  {
    Sim sim(g);
    btRigidBody& ball = addBall(sim, at(0.013, 0.007, groundZ(g, s, 0.013) + kRadius));
    double max_speed = 0.0;
    for (int k = 1; k <= 1000; ++k) {
      sim.world.step(kDt);
      if (k > 50) max_speed = std::max(max_speed, phys::velocityOf(ball).head<2>().norm());
    }
    r.accuracy.push_back(accuracy(g, "at rest on flat, max speed over 1 s", "sphere", "m/s", breaking, 0.0, max_speed,
                                  fmt("moved %.2g m", (phys::positionOf(ball).head<2>() - Eigen::Vector2d(0.013, 0.007)).norm())));
  }
}

// Flat: box at rest (timed, g_reps repetitions; the outcome from the first).
void flatBoxCase(const Ground& g, const SurfaceSpec& s, Results& r) {
  std::vector<StepStats> reps;
  std::unique_ptr<Sim> last;
  for (int rep = 0; rep < g_reps; ++rep) {
    auto sim = std::make_unique<Sim>(g);
    btRigidBody& box = addBox(*sim, at(0.013, 0.007, groundZ(g, s, 0.013) + kBoxHalf), 0.5);
    for (int k = 0; k < 200; ++k) sim->world.step(kDt);
    double max_speed = 0.0;
    reps.push_back(timedSteps(*sim, 800, [&](int) {
      max_speed = std::max(max_speed, phys::velocityOf(box).head<2>().norm());
    }));
    if (rep == 0)
      r.accuracy.push_back(accuracy(g, "at rest on flat, max speed over 0.8 s", "box", "m/s", 0.02, 0.0, max_speed));
    last = std::move(sim);
  }
  r.timing.push_back(toTiming(g, "box", 0.02, reps, *last));
}

// Slope: horizontal acceleration between 0.1 and 0.4 s from rest.
void slopeCases(const Ground& g, const SurfaceSpec& s, Results& r) {
  const double th = deg(kSlopeDeg);
  const bool virtual_slope = g.rep() == Rep::Normal;
  auto accelX = [](Sim& sim, btRigidBody& body) {
    double v1 = 0.0;
    for (int k = 1; k <= 400; ++k) {
      sim.world.step(kDt);
      if (k == 100) v1 = phys::velocityOf(body).x();
    }
    return (phys::velocityOf(body).x() - v1) / 0.3;
  };
  const double x0 = -0.15;
  {
    Sim sim(g);
    const double z = virtual_slope ? kRadius : s.height(x0, 0) + kRadius / std::cos(th);
    btRigidBody& ball = addBall(sim, at(x0, 0, z));
    const double a = accelX(sim, ball);
    const double expected = virtual_slope ? 5.0 / 7.0 * kG * std::tan(th) : 5.0 / 7.0 * kG * std::sin(th) * std::cos(th);
    r.accuracy.push_back(accuracy(g, "rolling down 10°, horizontal a", "sphere", "m/s²", 0.02, expected, a,
                                  virtual_slope ? "virtual slope: 5/7 g tanθ" : "5/7 g sinθ cosθ"));
  }
  {
    Sim sim(g);
    Eigen::Isometry3d pose;
    if (virtual_slope) {
      pose = at(x0, 0, kBoxHalf);
    } else {
      pose = at(x0, 0, s.height(x0, 0) + kBoxHalf / std::cos(th));
      pose.linear() = Eigen::AngleAxisd(th, Eigen::Vector3d::UnitY()).toRotationMatrix();  // face on the slope
    }
    btRigidBody& box = addBox(sim, pose, kBoxMu);
    const double a = accelX(sim, box);
    const double t = std::tan(th);
    const double expected = virtual_slope ? kG * (t - kBoxMu) / (1.0 + kBoxMu * t)
                                          : kG * (std::sin(th) - kBoxMu * std::cos(th)) * std::cos(th);
    r.accuracy.push_back(accuracy(g, "sliding down 10°, μ 0.1, horizontal a", "box", "m/s²", 0.02, expected, a,
                                  virtual_slope ? "virtual slope: g (tanθ − μ)/(1 + μ tanθ)" : "g (sinθ − μ cosθ) cosθ"));
  }
}

// Bump: escape speed by bisection (7 launches after the bracket check).
void bumpCase(const Ground& g, const SurfaceSpec& s, Results& r) {
  const double x0 = -0.5 * kBumpW - 0.012, escape_x = 0.5 * kBumpW + 0.004;
  auto escapes = [&](double v) {
    Sim sim(g);
    btRigidBody& ball = addBall(sim, at(x0, 0, groundZ(g, s, x0) + kRadius), 0.8);
    setRolling(ball, v);
    for (int k = 0; k < 1200; ++k) {
      sim.world.step(kDt);
      const Eigen::Vector3d p = phys::positionOf(ball);
      if (p.x() > escape_x) return true;
      if (phys::velocityOf(ball).x() < 0.0 && p.x() < x0) return false;
    }
    return false;
  };
  const double expected = std::sqrt(10.0 / 7.0 * kG * kBumpH);
  double lo = 0.6 * expected, hi = 1.4 * expected;
  std::string note;
  if (escapes(lo)) note = "escapes even at 0.6 v_c";
  else if (!escapes(hi)) note = "trapped even at 1.4 v_c";
  if (!note.empty()) {
    r.accuracy.push_back(accuracy(g, "escape speed over a 1 mm bump", "sphere", "m/s", 0.02, expected, std::nan(""), note));
    return;
  }
  for (int i = 0; i < 6; ++i) {
    const double mid = 0.5 * (lo + hi);
    (escapes(mid) ? hi : lo) = mid;
  }
  r.accuracy.push_back(accuracy(g, "escape speed over a 1 mm bump", "sphere", "m/s", 0.02, expected, 0.5 * (lo + hi),
                                fmt("bisection ±%.2f %%", 100.0 * 0.5 * (hi - lo) / expected)));
}

// ---------------------------------------------------------------------------------------------
// Output.

std::string jsonNumber(double v) { return std::isfinite(v) ? fmt("%.6g", v) : "null"; }
std::string jsonString(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    o += c;
  }
  return o + "\"";
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

const Timing* findTiming(const Results& r, const std::string& rep, int size, const std::string& shape, double breaking = 0.02) {
  for (const Timing& t : r.timing)
    if (t.rep == rep && t.size == size && t.shape == shape && t.breaking == breaking) return &t;
  return nullptr;
}
const Accuracy* findAccuracy(const Results& r, const std::string& rep, int size, const std::string& case_prefix,
                             double breaking = 0.02) {
  for (const Accuracy& a : r.accuracy)
    if (a.rep == rep && a.size == size && a.breaking == breaking && a.case_name.rfind(case_prefix, 0) == 0) return &a;
  return nullptr;
}
const GroundInfo* findGround(const Results& r, const std::string& rep, int size) {
  for (const GroundInfo& g : r.grounds)
    if (g.rep == rep && g.size == size) return &g;
  return nullptr;
}

std::string us(double v) { return v < 10 ? fmt("%.2f", v) : v < 100 ? fmt("%.1f", v) : fmt("%.0f", v); }
std::string mib(long long b) { return fmt("%.2f", double(b) / (1024.0 * 1024.0)); }
std::string sizeLabel(int n, double extent) {
  return n == 0 ? "—" : fmt("%d² (%.2f mm)", n, 1e3 * extent / n);
}

std::string errorCell(const Accuracy* a) {
  if (!a) return "—";
  if (!std::isfinite(a->measured)) return a->note;
  if ((a->unit == "m/s" || a->unit == "mm") && a->expected == 0.0) return fmt("%.2g", a->measured);
  if (a->case_name.rfind("rolling 0.05 m/s on flat, speed", 0) == 0) return fmt("%+.2g", a->error);
  return fmt("%+.2f %%", 100.0 * a->rel_error);
}

struct Goals {
  std::string text_md;
  std::string json;
};

std::string markdown(const Results& r, const std::vector<int>& sizes, const std::string& machine,
                     const std::string& when, Goals& goals) {
  const std::string hf = repName(Rep::Heightfield), mesh = repName(Rep::Mesh);
  const std::vector<std::string> reps = {repName(Rep::Normal), repName(Rep::Relief), hf, hf + " + edge utility",
                                         mesh, mesh + " + edge utility"};
  std::ostringstream md;
  md << "Machine: " << machine << "; measured " << when << ".\n\n";
  md << "One body per world, `PhysicsWorld::step(1 ms)` (one internal step, 10 solver iterations, float Bullet 3.24); "
        "sphere r = 1 cm, 0.05 kg, rolling at 0.05 m/s on the flat surface (200 warm-up + 2000 timed steps); box "
        "2 cm, 0.05 kg, 0.5 mm margin, resting (200 + 800 steps); "
     << g_reps
     << " repetitions each. Surface 0.5 × 0.5 m; N² = samples per side (texels of the normal/relief map, vertices of "
        "the heightfield and the mesh: the same points). Median = per-step wall clock, median of the repetitions' "
        "medians [their range]; p90 likewise; mean = thread CPU time of the timed block per step (it includes ~0.1 µs "
        "of the benchmark's own per-step bookkeeping). Memory: resident-set growth when the ground is built "
        "(texture; height array; mesh arrays + BVH; + edge map), build = its construction time.\n\n";

  // Timing table.
  md << "| ground | N² (spacing) | sphere median µs [range] | p90 | mean | box median µs [range] | p90 | mean | "
        "contacts (sphere / box) | memory MiB | build ms |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto timingRow = [&](const std::string& rep, int n) {
    const Timing* s = findTiming(r, rep, n, "sphere");
    const Timing* b = findTiming(r, rep, n, "box");
    const GroundInfo* g = findGround(r, rep, n);
    if (!s && !b) return;
    auto cells = [&](const Timing* t) {
      if (!t) return std::string("— | — | —");
      return us(t->median_us) + " [" + us(t->median_lo_us) + "–" + us(t->median_hi_us) + "] | " + us(t->p90_us) +
             " | " + us(t->cpu_mean_us);
    };
    md << "| " << rep << " | " << sizeLabel(n, 0.5) << " | " << cells(s) << " | " << cells(b) << " | " << (s ? fmt("%.1f", s->contacts) : "—") << " / "
       << (b ? fmt("%.1f", b->contacts) : "—") << " | " << (g ? mib(g->rss_bytes) : "—") << " | "
       << (g ? fmt("%.1f", g->build_ms) : "—") << " |\n";
  };
  timingRow(repName(Rep::Plain), 0);
  for (const std::string& rep : reps)
    for (int n : sizes) timingRow(rep, n);

  // Accuracy table.
  md << "\nOutcome error against the analytic answers (flat: measured value, expected 0 / 0.05 m/s; slope and bump: "
        "relative error). Slope 10°: ball a = 5/7 g sinθ cosθ = "
     << fmt("%.4f", 5.0 / 7.0 * kG * std::sin(deg(kSlopeDeg)) * std::cos(deg(kSlopeDeg)))
     << " m/s² horizontally on a real slope, 5/7 g tanθ = " << fmt("%.4f", 5.0 / 7.0 * kG * std::tan(deg(kSlopeDeg)))
     << " on the normal map's virtual slope; box μ = 0.1: g (sinθ − μ cosθ) cosθ = "
     << fmt("%.4f", kG * (std::sin(deg(kSlopeDeg)) - kBoxMu * std::cos(deg(kSlopeDeg))) * std::cos(deg(kSlopeDeg)))
     << ", virtual g (tanθ − μ)/(1 + μ tanθ) = "
     << fmt("%.4f", kG * (std::tan(deg(kSlopeDeg)) - kBoxMu) / (1.0 + kBoxMu * std::tan(deg(kSlopeDeg))))
     << ". Bump: 1 mm × 3 cm cos² ridge, escape speed sqrt(10/7 g H) = " << fmt("%.4f", std::sqrt(10.0 / 7.0 * kG * kBumpH))
     << " m/s (bisection ±0.6 %).\n\n";
  md << "| ground | N² | rolling ball: speed − 0.05 m/s after 2.2 s | rolling ball: max sink mm | ball at rest: max m/s "
        "| box at rest: max m/s | ball down slope: a error | box down slope: a error | escape speed error |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  auto accuracyRow = [&](const std::string& rep, int n, double breaking, const std::string& label) {
    const Accuracy* roll = findAccuracy(r, rep, n, "rolling 0.05 m/s on flat, speed", breaking);
    if (!roll) return;
    md << "| " << label << " | " << sizeLabel(n, 0.5) << " | " << errorCell(roll) << " | "
       << errorCell(findAccuracy(r, rep, n, "rolling 0.05 m/s on flat, max sink", breaking)) << " | "
       << errorCell(findAccuracy(r, rep, n, "at rest on flat, max speed over 1 s", breaking)) << " | "
       << errorCell(findAccuracy(r, rep, n, "at rest on flat, max speed over 0.8", breaking)) << " | "
       << errorCell(findAccuracy(r, rep, n, "rolling down", breaking)) << " | "
       << errorCell(findAccuracy(r, rep, n, "sliding down", breaking)) << " | "
       << errorCell(findAccuracy(r, rep, n, "escape", breaking)) << " |\n";
  };
  accuracyRow(repName(Rep::Plain), 0, 0.02, repName(Rep::Plain));
  for (const std::string& rep : reps)
    for (int n : sizes) accuracyRow(rep, n, 0.02, rep);
  for (const std::string& rep : {hf, mesh})
    for (int n : sizes) accuracyRow(rep, n, kTunedBreaking, rep + ", gContactBreakingThreshold 0.002");

  // Thresholds.
  md << "\nThresholds and margins used: ";
  bool first = true;
  for (const auto& [k, v] : r.thresholds) {
    md << (first ? "" : "; ") << k << " " << v;
    first = false;
  }
  md << ".\n\n";

  // Goals.
  std::ostringstream g, gj;
  const Timing* plain_s = findTiming(r, repName(Rep::Plain), 0, "sphere");
  const Timing* plain_b = findTiming(r, repName(Rep::Plain), 0, "box");
  md << "| goal (issue 6) | measured | verdict |\n|---|---|---|\n";
  gj << "{";
  {
    // Normal-map overhead per contact, over all sizes (median of the per-size overheads).
    std::vector<double> per_s, per_b;
    for (int n : sizes) {
      const Timing* s = findTiming(r, repName(Rep::Normal), n, "sphere");
      const Timing* b = findTiming(r, repName(Rep::Normal), n, "box");
      if (s && plain_s && s->contacts > 0) per_s.push_back((s->median_us - plain_s->median_us) / s->contacts);
      if (b && plain_b && b->contacts > 0) per_b.push_back((b->median_us - plain_b->median_us) / b->contacts);
    }
    const double os = percentile(per_s, 0.5), ob = percentile(per_b, 0.5);
    const bool met = std::isfinite(os) && std::isfinite(ob) && os <= 1.0 && ob <= 1.0;
    md << "| normal-map overhead ≤ 1 µs per contact over the plain plane step | sphere "
       << fmt("%+.2f", os) << " µs/contact (plane " << (plain_s ? us(plain_s->median_us) : "?") << " µs/step), box "
       << fmt("%+.2f", ob) << " µs/contact (plane " << (plain_b ? us(plain_b->median_us) : "?")
       << " µs/step); median over the sizes | " << (met ? "**met**" : "**missed**") << " |\n";
    gj << "\"normal_overhead_us_per_contact\":{\"sphere\":" << jsonNumber(os) << ",\"box\":" << jsonNumber(ob)
       << ",\"met\":" << (met ? "true" : "false") << "},";
  }
  {
    const Timing* rs = findTiming(r, repName(Rep::Relief), 512, "sphere");
    const bool met = rs && rs->median_us <= 10.0;
    md << "| relief sphere ≤ 10 µs per step at 1 mm texels (512² over 0.5 m = 0.98 mm) | "
       << (rs ? us(rs->median_us) + " µs (CPU " + us(rs->cpu_mean_us) + ")" : "not run") << " | "
       << (rs ? (met ? "**met**" : "**missed**") : "—") << " |\n";
    gj << "\"relief_sphere_512_us\":" << jsonNumber(rs ? rs->median_us : std::nan("")) << ",";
  }
  {
    // Far below heightfield and mesh on the same surface: the smallest ratio over sizes.
    double min_ratio_n = 1e30, min_ratio_r = 1e30;
    for (int n : sizes)
      for (const char* shape : {"sphere", "box"}) {
        const Timing* nm = findTiming(r, repName(Rep::Normal), n, shape);
        const Timing* rl = findTiming(r, repName(Rep::Relief), n, shape);
        for (Rep other : {Rep::Heightfield, Rep::Mesh}) {
          const Timing* o = findTiming(r, repName(other), n, shape);
          if (!o) continue;
          if (nm) min_ratio_n = std::min(min_ratio_n, o->cpu_mean_us / nm->cpu_mean_us);
          if (rl) min_ratio_r = std::min(min_ratio_r, o->cpu_mean_us / rl->cpu_mean_us);
        }
      }
    md << "| both far below heightfield and mesh on the same surface | heightfield/mesh cost at least "
       << fmt("%.1f", min_ratio_n) << "× the normal map's and " << fmt("%.1f", min_ratio_r)
       << "× the relief map's (mean CPU per step; smallest ratio over sizes and shapes, same N) | "
       << (min_ratio_n >= 3.0 && min_ratio_r >= 1.5 ? "**met**" : "see the table") << " |\n";
    gj << "\"min_ratio_bullet_over_normal\":" << jsonNumber(min_ratio_n) << ",\"min_ratio_bullet_over_relief\":"
       << jsonNumber(min_ratio_r);
  }
  gj << "}";

  // Paper Table 1 as ratios.
  md << "\nThe source paper's Table 1 (physics column) as ratios to the normal map. The paper's scene and machine "
        "differ; here coarse mesh = 64², fine mesh = the finest size run, relief = 512² (1 mm texels); mean CPU µs "
        "per step (heightfield and mesh boxes have bimodal step times, so medians understate them):\n\n";
  md << "| | paper | paper ratio | here, sphere | ratio | here, box | ratio |\n|---|---|---|---|---|---|---|\n";
  const int finest = sizes.empty() ? 0 : sizes.back();
  struct Row { const char* name; double paper_us; std::string rep; int n; };
  const Row rows[] = {{"normal map", 175.0, repName(Rep::Normal), 512},
                      {"relief map", 2200.0, repName(Rep::Relief), 512},
                      {"coarse mesh", 3000.0, repName(Rep::Mesh), 64},
                      {"fine mesh", 4900.0, repName(Rep::Mesh), finest}};
  const Timing* ns = findTiming(r, repName(Rep::Normal), 512, "sphere");
  const Timing* nb = findTiming(r, repName(Rep::Normal), 512, "box");
  for (const Row& row : rows) {
    const Timing* s = findTiming(r, row.rep, row.n, "sphere");
    const Timing* b = findTiming(r, row.rep, row.n, "box");
    md << "| " << row.name << (row.n ? fmt(" (%d²)", row.n) : "") << " | " << fmt("%.0f µs", row.paper_us) << " | "
       << fmt("%.1f×", row.paper_us / 175.0) << " | " << (s ? us(s->cpu_mean_us) + " µs" : "—") << " | "
       << (s && ns ? fmt("%.1f×", s->cpu_mean_us / ns->cpu_mean_us) : "—") << " | "
       << (b ? us(b->cpu_mean_us) + " µs" : "—") << " | "
       << (b && nb ? fmt("%.1f×", b->cpu_mean_us / nb->cpu_mean_us) : "—") << " |\n";
  }
  goals.json = gj.str();
  return md.str();
}

std::string csv(const Results& r) {
  std::ostringstream o;
  o << "kind,representation,size,shape,case,breaking_threshold,steps,median_us,p90_us,cpu_mean_us,contacts,"
       "manifold_breaking_m,expected,measured,unit,error,rel_error,rss_bytes,source_bytes,triangles,build_ms,note\n";
  for (const Timing& t : r.timing)
    o << "timing," << t.rep << "," << t.size << "," << t.shape << ",," << t.breaking << "," << t.steps << ","
      << t.median_us << "," << t.p90_us << "," << t.cpu_mean_us << "," << t.contacts << "," << t.manifold_threshold_m
      << ",,,,,,,,,,\n";
  for (const Accuracy& a : r.accuracy)
    o << "accuracy," << a.rep << "," << a.size << "," << a.shape << ",\"" << a.case_name << "\"," << a.breaking
      << ",,,,,,," << a.expected << "," << a.measured << "," << a.unit << "," << a.error << "," << a.rel_error
      << ",,,,,\"" << a.note << "\"\n";
  for (const GroundInfo& g : r.grounds)
    o << "ground," << g.rep << "," << g.size << ",,,,,,,,,,,,,,," << g.rss_bytes << "," << g.source_bytes << ","
      << g.triangles << "," << g.build_ms << ",\n";
  return o.str();
}

std::string json(const Results& r, const std::string& machine, const std::string& when, const Goals& goals) {
  std::ostringstream o;
  o << "{\n\"benchmark\":\"bench_physics\",\"machine\":" << jsonString(machine) << ",\"measured\":" << jsonString(when)
    << ",\"build_type\":" << jsonString(thx::bench::buildType())
    << ",\n\"settings\":{\"dt_s\":" << kDt << ",\"extent_m\":0.5,\"sphere_radius_m\":" << kRadius
    << ",\"sphere_mass_kg\":" << kBallMass << ",\"box_half_m\":" << kBoxHalf << ",\"box_mass_kg\":" << kBoxMass
    << ",\"roll_speed_m_per_s\":" << kRollSpeed << ",\"slope_deg\":" << kSlopeDeg << ",\"box_mu\":" << kBoxMu
    << ",\"bump_height_m\":" << kBumpH << ",\"bump_width_m\":" << kBumpW << "},\n\"thresholds\":{";
  bool first = true;
  for (const auto& [k, v] : r.thresholds) {
    o << (first ? "" : ",") << jsonString(k) << ":" << jsonString(v);
    first = false;
  }
  o << "},\n\"goals\":" << goals.json << ",\n\"timing\":[\n";
  for (std::size_t i = 0; i < r.timing.size(); ++i) {
    const Timing& t = r.timing[i];
    o << " {\"representation\":" << jsonString(t.rep) << ",\"size\":" << t.size << ",\"shape\":" << jsonString(t.shape)
      << ",\"breaking_threshold\":" << t.breaking << ",\"steps\":" << t.steps << ",\"repetitions\":" << t.reps
      << ",\"median_us\":" << jsonNumber(t.median_us) << ",\"median_min_us\":" << jsonNumber(t.median_lo_us)
      << ",\"median_max_us\":" << jsonNumber(t.median_hi_us) << ",\"p90_us\":" << jsonNumber(t.p90_us) << ",\"cpu_mean_us\":"
      << jsonNumber(t.cpu_mean_us) << ",\"contacts_per_step\":" << jsonNumber(t.contacts)
      << ",\"manifold_breaking_m\":" << jsonNumber(t.manifold_threshold_m) << "}"
      << (i + 1 < r.timing.size() ? ",\n" : "\n");
  }
  o << "],\n\"accuracy\":[\n";
  for (std::size_t i = 0; i < r.accuracy.size(); ++i) {
    const Accuracy& a = r.accuracy[i];
    o << " {\"representation\":" << jsonString(a.rep) << ",\"size\":" << a.size << ",\"case\":"
      << jsonString(a.case_name) << ",\"shape\":" << jsonString(a.shape) << ",\"breaking_threshold\":" << a.breaking
      << ",\"unit\":" << jsonString(a.unit) << ",\"expected\":" << jsonNumber(a.expected) << ",\"measured\":"
      << jsonNumber(a.measured) << ",\"error\":" << jsonNumber(a.error) << ",\"rel_error\":" << jsonNumber(a.rel_error)
      << ",\"note\":" << jsonString(a.note) << "}" << (i + 1 < r.accuracy.size() ? ",\n" : "\n");
  }
  o << "],\n\"grounds\":[\n";
  for (std::size_t i = 0; i < r.grounds.size(); ++i) {
    const GroundInfo& g = r.grounds[i];
    o << " {\"representation\":" << jsonString(g.rep) << ",\"size\":" << g.size << ",\"rss_bytes\":" << g.rss_bytes
      << ",\"source_bytes\":" << g.source_bytes << ",\"triangles\":" << g.triangles << ",\"build_ms\":"
      << jsonNumber(g.build_ms) << "}" << (i + 1 < r.grounds.size() ? ",\n" : "\n");
  }
  o << "]\n}\n";
  return o.str();
}

void plot(const Results& r, const std::vector<int>& sizes, const std::string& path) {
  const Rgb colors[] = {{31, 119, 180}, {44, 160, 44}, {255, 127, 14}, {214, 39, 40}};
  const Rep reps[] = {Rep::Normal, Rep::Relief, Rep::Heightfield, Rep::Mesh};
  const Marker markers[] = {Marker::Circle, Marker::Square, Marker::Triangle, Marker::Circle};
  std::vector<PlotPanel> panels;
  for (const char* shape : {"sphere", "box"}) {
    PlotPanel p;
    p.title = std::string(shape) + ": time per step";
    p.x_label = "samples per side";
    p.y_label = "mean CPU us per step";
    p.x_min = 48;
    p.x_max = 1400;
    p.y_min = 0.5;
    p.y_max = 1e4;
    for (int k = 0; k < 4; ++k) {
      PlotSeries s;
      s.label = repName(reps[k]);
      s.color = colors[k];
      s.marker = markers[k];
      s.filled = k != 3;
      for (int n : sizes)
        if (const Timing* t = findTiming(r, repName(reps[k]), n, shape)) {
          s.x.push_back(n);
          s.y.push_back(std::max(p.y_min, t->cpu_mean_us));
        }
      p.series.push_back(s);
    }
    if (const Timing* t = findTiming(r, repName(Rep::Plain), 0, shape)) {
      PlotSeries s;
      s.label = "plain plane";
      s.color = {127, 127, 127};
      s.marker = Marker::Square;
      s.filled = false;
      s.x = {double(sizes.front()), double(sizes.back())};
      s.y = {t->cpu_mean_us, t->cpu_mean_us};
      p.series.push_back(s);
    }
    panels.push_back(p);
  }
  {
    PlotPanel p;
    p.title = "ball rolling down 10 deg: |error| vs cost (floor 0.01 %)";
    p.x_label = "sphere mean CPU us per step (flat run)";
    p.y_label = "|relative error of a| (%)";
    p.x_min = 0.5;
    p.x_max = 1e4;
    p.y_min = 0.01;
    p.y_max = 100;
    for (int k = 0; k < 4; ++k) {
      PlotSeries s;
      s.label = repName(reps[k]);
      s.color = colors[k];
      s.marker = markers[k];
      s.filled = k != 3;
      for (int n : sizes) {
        const Timing* t = findTiming(r, repName(reps[k]), n, "sphere");
        const Accuracy* a = findAccuracy(r, repName(reps[k]), n, "rolling down");
        if (!t || !a || !std::isfinite(a->rel_error)) continue;
        s.x.push_back(t->cpu_mean_us);
        s.y.push_back(std::clamp(100.0 * std::fabs(a->rel_error), p.y_min, p.y_max));
        s.point_labels.push_back(std::to_string(n));
      }
      p.series.push_back(s);
    }
    panels.push_back(p);
  }
  writePlotPng(path, panels, "bench_physics: cost and error of the same surface in five representations", 560, 480);
}

constexpr const char* kHelp = R"(usage: bench_physics [--sizes 64,128,...] [--reps N] [--json F] [--csv F] [--md F] [--png F]

Cost and error of the same surface in five physics representations (docs/benchmarks.md part 6).
benchmarks/run.sh BUILD_DIR physics runs it as the docs show.
--sizes: texels a side, each 2 to 1024 (default 64,128,256,512,1024). --reps: 1 to 1000.
)";

int run(int argc, char** argv) {
  std::vector<int> sizes = {64, 128, 256, 512, 1024};
  std::string json_path, csv_path, md_path, png_path;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "usage: bench_physics [--sizes 64,128,...] [--reps N] [--json F] [--csv F] [--md F] [--png F]\n");
      return 2;
    }
    const std::string v = argv[++i];
    if (a == "--json") json_path = v;
    else if (a == "--csv") csv_path = v;
    else if (a == "--md") md_path = v;
    else if (a == "--png") png_path = v;
    else if (a == "--reps") g_reps = int(thx::cli::parseInteger(a, v, 1, 1000));
    else if (a == "--sizes") {
      // Beyond 1024 texels a side the BVH mesh (two triangles a texel) passes the 2^21 triangles
      // a quantized Bullet BVH can index (21 bits of triangle index): runs at 2048 and 4096 crashed walking it.
      sizes = thx::cli::parseIntegerList(a, v, 2, kMaxSize);
      std::sort(sizes.begin(), sizes.end());
    } else {
      std::fprintf(stderr, "bench_physics: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  const std::string machine = machineDescription();
  const std::string when = isoTimeNow();
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto progress = [&](const std::string& what) { std::fprintf(stderr, "[bench_physics %6.1f s] %s\n", elapsed(), what.c_str()); };

  Results r;
  r.thresholds["gContactBreakingThreshold"] = fmt("%.3g (Bullet's default; 0.002 in the rows marked so)",
                                                  double(gContactBreakingThreshold));
  const SurfaceSpec flat = flatSurface(), slope = slopeSurface(), bump = bumpSurface();

  // Plain plane: size-independent.
  {
    progress("plain plane: flat + slope");
    Ground g(flat, Rep::Plain, 64);
    flatSphereCases(g, flat, 0.02, true, r);
    flatBoxCase(g, flat, r);
    Ground gs(slope, Rep::Plain, 64);
    slopeCases(gs, slope, r);
  }
  installEdgeCallback();
  struct Variant { Rep rep; bool edges; };
  const Variant variants[] = {{Rep::Normal, false},     {Rep::Relief, false}, {Rep::Heightfield, false},
                              {Rep::Heightfield, true}, {Rep::Mesh, false},   {Rep::Mesh, true}};
  for (int n : sizes) {
    for (const Variant v : variants) {
      if (v.edges && n > kEdgeUtilityMaxSize) continue;
      const double t0 = elapsed();
      std::string label;
      {
        const long long rss0 = residentBytes();
        Ground g(flat, v.rep, n, v.edges);
        label = groundLabel(g);
        GroundInfo info{label, n, g.buildMs(), residentBytes() - rss0, g.sourceBytes(), g.triangles()};
        r.grounds.push_back(info);
        flatSphereCases(g, flat, 0.02, true, r);
        flatBoxCase(g, flat, r);
        if ((v.rep == Rep::Heightfield || v.rep == Rep::Mesh) && !v.edges) flatSphereCases(g, flat, kTunedBreaking, false, r);
        if (const btCollisionShape* shape = g.sharedShape())
          r.thresholds[std::string(repName(v.rep)) + " collision margin"] = fmt("%.3g m (Bullet's default)", double(shape->getMargin()));
        if (v.edges && n == kEdgeUtilityMaxSize)
          r.thresholds["edge utility"] = fmt("btTriangleInfoMap with m_equalVertexThreshold = m_zeroAreaThreshold = 1e-16, "
                                             "m_edgeDistanceThreshold = 0.1 × spacing (Bullet's defaults leave the map empty "
                                             "at mm scale); %lld entries at %d²", g.edgeMapEntries(), n);
      }
      {
        Ground g(slope, v.rep, n, v.edges);
        slopeCases(g, slope, r);
      }
      {
        Ground g(bump, v.rep, n, v.edges);
        bumpCase(g, bump, r);
      }
      const Timing* ts = findTiming(r, label, n, "sphere");
      const Timing* tb = findTiming(r, label, n, "box");
      progress(fmt("%s %d²: sphere %s µs, box %s µs per step (%.1f s)", label.c_str(), n,
                   ts ? us(ts->median_us).c_str() : "?", tb ? us(tb->median_us).c_str() : "?", elapsed() - t0));
    }
  }
  // Thresholds the manifolds really used (Bullet takes the smaller of the two shapes' values).
  {
    std::map<std::string, std::vector<std::string>> by_value;
    for (const Timing& t : r.timing)
      if (t.manifold_threshold_m > 0.0) {
        std::vector<std::string>& who = by_value[fmt("%.3g mm", 1e3 * t.manifold_threshold_m)];
        const std::string key = t.shape;
        if (std::find(who.begin(), who.end(), key) == who.end()) who.push_back(key);
      }
    std::string text;
    for (const auto& [value, who] : by_value) {
      text += (text.empty() ? "" : ", ") + value + " (";
      for (std::size_t i = 0; i < who.size(); ++i) text += (i ? " and " : "") + who[i];
      text += ")";
    }
    r.thresholds["manifold breaking threshold, every ground"] =
        text + fmt("; %.3g mm with gContactBreakingThreshold 0.002", 1e3 * 0.1 * r.timing.front().manifold_threshold_m);
  }
  r.thresholds["box convex margin"] = "0.5 mm (PhysicsWorld default; sphere: its radius, Bullet's rule)";
  r.thresholds["solver"] = "10 iterations, erp 0.2, split impulse on (threshold −0.04 m), warm starting 0.85; "
                           "ContactSolver (friction released with its normal impulse)";
  r.thresholds["normal map"] = "max tilt 75°, height hold on; relief: candidates below the manifold's breaking "
                               "threshold, ≤ 4 contacts, manifold cleared every step";

  Goals goals;
  const std::string md = markdown(r, sizes, machine, when, goals);
  if (!md_path.empty()) writeFile(md_path, md);
  if (!csv_path.empty()) writeFile(csv_path, csv(r));
  if (!json_path.empty()) writeFile(json_path, json(r, machine, when, goals));
  if (!png_path.empty()) plot(r, sizes, png_path);
  if (md_path.empty()) std::fputs(md.c_str(), stdout);
  progress("done");
  return 0;
}

}  // namespace
}  // namespace thx::bench

int main(int argc, char** argv) { return thx::bench::benchMain(argc, argv, thx::bench::kHelp, "bench_physics", thx::bench::run); }
