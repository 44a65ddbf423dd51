// `devices:` (issue 30): several devices in one scene, each named, and every way a list of them
// can be wrong refused at its line.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scenes/scene_loader.hpp"

namespace test_scene_devices {

namespace {

using namespace thx::scene;

std::string sceneWith(const std::string& rest) {
  return "version: 1\nname: d\nsurface:\n  size: [0.2, 0.2]\n  texture: {generator: bricks, size: 16}\n" + rest;
}

// The scene's error, with every part in it, at `line` and `field`.
void expectError(const std::string& text, int line, const std::string& field, const std::vector<std::string>& parts) {
  try {
    parseScene(text, "d.yaml", "");
    FAIL() << "loaded:\n" << text;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_EQ(e.where().line, line) << e.what();
    for (const std::string& part : parts)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << "'" << part << "' not in: " << e.what();
  }
}

}  // namespace

TEST(SceneDevices, AListGivesEveryDeviceInOrderWithItsName) {
  const Scene s = parseScene(sceneWith("devices:\n"
                                       "  - name: left\n"
                                       "    stiffness_fraction: 0.4\n"
                                       "    script:\n"
                                       "      - press: {position: [0.01, 0], force: 1, duration: 1}\n"
                                       "  - type: vrpn\n"
                                       "    model: premium_3_0\n"
                                       "    address: Phantom0@lab:3883\n"
                                       "  - {}\n"),
                             "d.yaml", "");
  ASSERT_EQ(deviceCount(s), 3u);
  EXPECT_EQ(deviceAt(s, 0).name, "left");
  EXPECT_DOUBLE_EQ(deviceAt(s, 0).stiffness_fraction, 0.4);
  EXPECT_EQ(deviceAt(s, 0).script.size(), 1u);
  EXPECT_EQ(&deviceAt(s, 0), &s.device);
  EXPECT_EQ(deviceAt(s, 1).name, "Phantom1");  // the default: its index
  EXPECT_EQ(deviceAt(s, 1).type, DeviceType::Vrpn);
  EXPECT_EQ(deviceAt(s, 1).model.name, "premium_3_0");
  EXPECT_EQ(deviceAt(s, 1).address, "Phantom0@lab:3883");
  EXPECT_EQ(deviceAt(s, 2).name, "Phantom2");
  EXPECT_EQ(deviceAt(s, 2).type, DeviceType::Sim);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(SceneDevices, OneDeviceSectionIsPhantom0AndAlone) {
  const Scene s = parseScene(sceneWith("device:\n  stiffness_fraction: 0.3\n"), "d.yaml", "");
  EXPECT_EQ(deviceCount(s), 1u);
  EXPECT_EQ(s.device.name, "Phantom0");
  EXPECT_TRUE(s.other_devices.empty());
  // `name` belongs to the list's entries only.
  expectError(sceneWith("device:\n  name: left\n"), 7, "device.name", {"unknown field 'name'"});
}

TEST(SceneDevices, TwoDevicesWithOneNameAreRefusedNamingBoth) {
  expectError(sceneWith("devices:\n  - name: pen\n  - {type: sim}\n  - name: pen\n"), 9, "devices[2].name",
              {"d.yaml:9:", "duplicate device name 'pen'", "also devices[0], line 7", "a name no other device uses"});
  // A written name against a default one.
  expectError(sceneWith("devices:\n  - {}\n  - name: Phantom0\n"), 8, "devices[1].name",
              {"duplicate device name 'Phantom0'"});
}

TEST(SceneDevices, OneVrpnAddressGivenTwiceIsRefused) {
  expectError(sceneWith("devices:\n"
                        "  - {type: vrpn, address: Phantom0@lab:3883}\n"
                        "  - {type: vrpn, address: Phantom0@lab:3883}\n"),
              8, "devices[1].address", {"VRPN address given twice (also devices[0])", "one device per address"});
  // Another device name on the same server is another device.
  const Scene s = parseScene(sceneWith("devices:\n"
                                       "  - {type: vrpn, address: Phantom0@lab:3883}\n"
                                       "  - {type: vrpn, address: Phantom1@lab:3883}\n"),
                             "d.yaml", "");
  EXPECT_EQ(deviceCount(s), 2u);
}

TEST(SceneDevices, MoreThanSixteenOrNoneOrBothSectionsAreRefused) {
  std::string many = "devices:\n";
  for (int i = 0; i < 17; ++i) many += "  - {}\n";
  expectError(sceneWith(many), 7, "devices", {"too many devices", "at most 16 (one servo clock's limit)", "got 17 devices"});
  std::string sixteen = "devices:\n";
  for (int i = 0; i < 16; ++i) sixteen += "  - {}\n";
  EXPECT_EQ(deviceCount(parseScene(sceneWith(sixteen), "d.yaml", "")), 16u);

  expectError(sceneWith("devices: []\n"), 6, "devices", {"no devices"});
  expectError(sceneWith("device: {}\ndevices:\n  - {}\n"), 8, "devices", {"both `device` and `devices`"});
}

TEST(SceneDevices, ANameVrpnCannotCarryIsRefused) {
  expectError(sceneWith("devices:\n  - name: left hand\n"), 7, "devices[0].name",
              {"not a device name", "letters, digits", "got 'left hand'"});
  expectError(sceneWith("devices:\n  - name: " + std::string(65, 'a') + "\n"), 7, "devices[0].name",
              {"not a device name"});
}

TEST(SceneDevices, EveryDeviceGetsTheWorkspaceAndRateWarnings) {
  const Scene s = parseScene(sceneWith("devices:\n"
                                       "  - {}\n"
                                       "  - model: touch\n"
                                       "    sim: {integration_hz: 12345}\n"
                                       "    script:\n"
                                       "      - press: {position: [0.09, 0.09], force: 0.4, duration: 1}\n"),
                             "d.yaml", "");
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_NE(s.warnings[0].find("devices[1].sim.integration_hz"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[1].find("devices[1].script"), std::string::npos) << s.warnings[1];
  EXPECT_NE(s.warnings[1].find("workspace radius"), std::string::npos) << s.warnings[1];
}

}  // namespace test_scene_devices
