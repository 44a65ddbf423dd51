#include "server/scene_switcher.hpp"

#include <chrono>
#include <cstdio>
#include <exception>

#include "base/error.hpp"
#include "scenes/scene_lookup.hpp"

namespace thx::srv {

namespace {
// While a swap is in the servo's hands the worker looks every millisecond whether it is done (the
// servo cannot signal: it never makes a system call other than the device's).
constexpr auto kReclaimPoll = std::chrono::milliseconds(1);
}  // namespace

SceneSwitcher::SceneSwitcher(std::vector<rt::Handoff<const SurfaceSwap>*> handoffs, scene::Scene running,
                             std::vector<dev::DeviceSpec> specs, std::unique_ptr<PreparedScene> first,
                             SceneSwitcherOptions options)
    : handoffs_(std::move(handoffs)),
      running_(std::move(running)),
      specs_(std::move(specs)),
      options_(std::move(options)),
      current_(std::move(first)),
      reclaimed_(handoffs_.size(), false) {
  if (handoffs_.size() != specs_.size() || handoffs_.empty() ||
      (current_ && current_->devices.size() != handoffs_.size()))
    throw thx::Error(thx::Error::Kind::Config, "SceneSwitcher: one handoff, one spec and one prepared device per device");
  worker_ = std::thread([this] { work(); });
}

SceneSwitcher::~SceneSwitcher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

std::optional<std::string> SceneSwitcher::begin(const std::string& name) {
  if (!scene::isValidSceneName(name)) {
    return "invalid scene name '" + name +
           "': expected 1 to 100 characters of [A-Za-z0-9_.-], not starting with '.' (a scene file's name without "
           ".yaml)";
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (loading_ || job_) return "a scene switch is already under way; ask again once it is answered";
    job_ = name;
    outcome_.reset();
  }
  wake_.notify_all();
  return std::nullopt;
}

std::optional<SceneLoads::Outcome> SceneSwitcher::poll() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<Outcome> o = std::move(outcome_);
  outcome_.reset();
  return o;
}

std::uint32_t SceneSwitcher::switchesOffered() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return offers_;
}

void SceneSwitcher::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (offered_) {
      wake_.wait_for(lock, kReclaimPoll);
      reclaim(lock);
    } else {
      wake_.wait(lock, [this] { return stop_ || job_.has_value(); });
    }
    if (stop_) return;
    if (!job_ || offered_) continue;  // the previous swap first
    const std::string name = std::move(*job_);
    job_.reset();
    loading_ = true;
    lock.unlock();
    load(name);  // ends the load (loading_ false) under the lock that publishes its outcome
    lock.lock();
  }
}

// Runs without the lock: loading a large texture takes a while and must not hold up poll().
void SceneSwitcher::load(const std::string& name) {
  Outcome outcome;
  std::unique_ptr<PreparedScene> next;
  try {
    const std::string path = scene::resolveSceneName(name, options_.scenes_dir);
    if (!options_.quiet) std::fprintf(stderr, "hapticd: loading scene '%s' (%s)\n", name.c_str(), path.c_str());
    next = prepareSwitch(path, running_, specs_, options_.policy);
  } catch (const thx::Error& e) {
    outcome.error = e.what();
  } catch (const std::exception& e) {  // e.g. out of memory for a huge texture: still only a refusal
    outcome.error = "scene '" + name + "': " + e.what();
  }
  std::unique_lock<std::mutex> lock(mutex_);
  if (next) {
    for (const std::string& w : next->warnings) std::fprintf(stderr, "hapticd: warning: %s\n", w.c_str());
    if (options_.verbose) {
      for (const PreparedDevice& d : next->devices) {
        for (const std::string& line : budgetReport(d.budget))
          std::fprintf(stderr, "hapticd: stability budget: %s\n", line.c_str());
      }
    }
    outcome.ok = true;
    outcome.scene_name = next->surface.scene_name;
    outcome.fingerprint = next->fingerprint;
    offered_ = std::move(next);
    // Each is Idle: the last swap was reclaimed from every device before this job began.
    for (std::size_t i = 0; i < handoffs_.size(); ++i) handoffs_[i]->offer(&offered_->devices[i].swap);
    reclaimed_.assign(handoffs_.size(), false);
    outcome.swap = ++offers_;
  }
  // The outcome and the end of the load under one lock: a client answered by poll() may ask
  // again at once, and begin() must not find this load still under way.
  outcome_ = std::move(outcome);
  loading_ = false;
}

void SceneSwitcher::reclaim(std::unique_lock<std::mutex>& lock) {
  if (!offered_) return;
  bool all = true;
  for (std::size_t i = 0; i < handoffs_.size(); ++i) {
    if (!reclaimed_[i]) reclaimed_[i] = handoffs_[i]->reclaim();
    all = all && reclaimed_[i];
  }
  if (!all) return;
  std::unique_ptr<PreparedScene> old = std::move(current_);
  current_ = std::move(offered_);
  lock.unlock();
  old.reset();  // the servo renders current_ now; the old surface's memory goes back here
  lock.lock();
}

}  // namespace thx::srv
