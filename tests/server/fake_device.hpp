#pragma once
// A scripted test double for the servo: positions come from a function of the tick, timing from
// a virtual clock, and every write is kept. Only for unit tests of the servo's own logic; the
// product and the integration tests use the simulated PHANToM.
#include <functional>
#include <vector>

#include "device/device_specs.hpp"
#include "device/haptic_device.hpp"

namespace thx::test {

class FakeDevice final : public dev::HapticDevice {
 public:
  using Script = std::function<void(std::int64_t tick, dev::DeviceState& state)>;

  explicit FakeDevice(Script script, std::size_t reserve_writes = 100000,
                      const dev::DeviceSpec& spec = dev::phantomDesktopSpec())
      : script_(std::move(script)), spec_(spec) {
    writes_.reserve(reserve_writes);
    torque_writes_.reserve(reserve_writes);
  }

  const dev::DeviceSpec& spec() const override { return spec_; }
  dev::OutputMode outputMode() const override { return dev::OutputMode::Force; }
  void open() override {}
  void close() override {}
  dev::DeviceState read() override {
    dev::DeviceState s;
    s.timing.tick = tick_;
    s.timing.deadline_ns = tick_ * 1'000'000;
    s.timing.wake_ns = s.timing.deadline_ns;
    script_(tick_, s);
    if (s.timing.missed > 0) {  // as the pacer reports it: the tick index skips the missed ones
      tick_ += s.timing.missed;
      s.timing.tick = tick_;
      s.timing.deadline_ns = tick_ * 1'000'000;
      s.timing.wake_ns = s.timing.deadline_ns;
    }
    ++tick_;
    return s;
  }
  void write(const dev::DeviceCommand& command) override {
    if (writes_.size() < writes_.capacity()) writes_.push_back(command.force_world_n);
    if (torque_writes_.size() < torque_writes_.capacity()) torque_writes_.push_back(command.torque_world_nm);
  }

  const std::vector<Eigen::Vector3d>& writes() const { return writes_; }
  const std::vector<Eigen::Vector3d>& torqueWrites() const { return torque_writes_; }

 private:
  Script script_;
  dev::DeviceSpec spec_;
  std::int64_t tick_ = 0;
  std::vector<Eigen::Vector3d> writes_;
  std::vector<Eigen::Vector3d> torque_writes_;
};

}  // namespace thx::test
