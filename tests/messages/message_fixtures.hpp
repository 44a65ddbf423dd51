#pragma once
// Non-trivial values for every thx_msgs type, and field-by-field equality checks.
// make_*(k): k selects a distinct, deterministic set of values (no two fields share a value).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "thx_msgs/protocol.hpp"

namespace thx_test {

// A value that differs per (k, field) and is exactly representable: encode/decode is bitwise,
// so every comparison below is exact.
inline double val(int k, int field) { return -1.25 + 0.5 * k + 0.0078125 * field + (field % 3 == 0 ? -1e3 : 1e-3); }
inline std::int64_t ival(int k, int field) { return (std::int64_t(1) << 40) * (k + 1) + 977 * field - 5; }

template <std::size_t N>
void fill(double (&a)[N], int k, int field0) {
  for (std::size_t i = 0; i < N; ++i) a[i] = val(k, field0 + int(i));
}
template <std::size_t N>
void expect_array_eq(const double (&a)[N], const double (&b)[N], const char* what) {
  for (std::size_t i = 0; i < N; ++i) EXPECT_EQ(a[i], b[i]) << what << "[" << i << "]";
}

inline thx_msgs::device_state_t make_device_state(int k) {
  thx_msgs::device_state_t m{};
  m.utime = ival(k, 1);
  m.tick = ival(k, 2);
  fill(m.p_world, k, 10);
  fill(m.q_world, k, 20);
  fill(m.v_world, k, 30);
  fill(m.w_world, k, 40);
  m.buttons = 0x5 + k;
  fill(m.f_cmd_world, k, 50);
  fill(m.tau_cmd_world, k, 60);
  // LCM int32 constants are separate unnamed enums: C++20 deprecates FLAG_A | FLAG_B, so make
  // one operand an int32_t (docs/messages.md, "Decoding and using the types").
  using D = thx_msgs::device_state_t;
  m.flags = std::int32_t{D::FLAG_ENGAGED} | D::FLAG_SAFETY_CLAMP | D::FLAG_FAULT;
  m.fault_code = thx_msgs::device_state_t::FAULT_FORCE_BUDGET;
  m.fault_mask = (1 << D::FAULT_FORCE_BUDGET) | (1 << D::FAULT_MISSED_TICKS) | (k << 8);
  m.flags_seen = std::int32_t{D::FLAG_MISSED_TICK} | D::FLAG_FAULT | (k << 12);
  fill(m.proxy_world, k, 70);
  m.device = 3 + k;
  return m;
}
inline void expect_eq(const thx_msgs::device_state_t& a, const thx_msgs::device_state_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.tick, b.tick);
  expect_array_eq(a.p_world, b.p_world, "p_world");
  expect_array_eq(a.q_world, b.q_world, "q_world");
  expect_array_eq(a.v_world, b.v_world, "v_world");
  expect_array_eq(a.w_world, b.w_world, "w_world");
  EXPECT_EQ(a.buttons, b.buttons);
  expect_array_eq(a.f_cmd_world, b.f_cmd_world, "f_cmd_world");
  expect_array_eq(a.tau_cmd_world, b.tau_cmd_world, "tau_cmd_world");
  EXPECT_EQ(a.flags, b.flags);
  EXPECT_EQ(a.fault_code, b.fault_code);
  EXPECT_EQ(a.fault_mask, b.fault_mask);
  EXPECT_EQ(a.flags_seen, b.flags_seen);
  expect_array_eq(a.proxy_world, b.proxy_world, "proxy_world");
  EXPECT_EQ(a.device, b.device);
}

inline thx_msgs::contact_t make_contact(int k) {
  thx_msgs::contact_t m{};
  m.utime = ival(k, 1);
  m.tick = ival(k, 2);
  m.in_contact = (k % 2 == 0);
  m.num_planes = static_cast<std::int8_t>(1 + k % thx_msgs::contact_t::MAX_PLANES);
  m.surface_id = 3 + k;
  m.texel_i = 511 - k;
  m.texel_j = -7 + k;
  fill(m.p_proj_world, k, 10);
  fill(m.uv, k, 20);
  fill(m.n_geom_world, k, 30);
  fill(m.n_sampled_world, k, 40);
  m.depth = val(k, 50);
  m.relief_depth = val(k, 51);
  for (int p = 0; p < 4; ++p) fill(m.plane_n_world[p], k, 60 + 3 * p);
  fill(m.plane_d, k, 80);
  m.f_normal = val(k, 90);
  fill(m.f_normal_world, k, 91);
  fill(m.v_tangent_world, k, 95);
  m.triangle = std::int32_t(ival(k, 98) & 0x7fffffff);
  fill(m.barycentric, k, 99);
  fill(m.tangent_world, k, 102);
  fill(m.bitangent_world, k, 105);
  m.device = 5 + k;
  return m;
}
inline void expect_eq(const thx_msgs::contact_t& a, const thx_msgs::contact_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.tick, b.tick);
  EXPECT_EQ(a.in_contact, b.in_contact);
  EXPECT_EQ(a.num_planes, b.num_planes);
  EXPECT_EQ(a.surface_id, b.surface_id);
  EXPECT_EQ(a.texel_i, b.texel_i);
  EXPECT_EQ(a.texel_j, b.texel_j);
  expect_array_eq(a.p_proj_world, b.p_proj_world, "p_proj_world");
  expect_array_eq(a.uv, b.uv, "uv");
  expect_array_eq(a.n_geom_world, b.n_geom_world, "n_geom_world");
  expect_array_eq(a.n_sampled_world, b.n_sampled_world, "n_sampled_world");
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_EQ(a.relief_depth, b.relief_depth);
  for (int p = 0; p < 4; ++p) expect_array_eq(a.plane_n_world[p], b.plane_n_world[p], "plane_n_world");
  expect_array_eq(a.plane_d, b.plane_d, "plane_d");
  EXPECT_EQ(a.f_normal, b.f_normal);
  expect_array_eq(a.f_normal_world, b.f_normal_world, "f_normal_world");
  expect_array_eq(a.v_tangent_world, b.v_tangent_world, "v_tangent_world");
  EXPECT_EQ(a.triangle, b.triangle);
  expect_array_eq(a.barycentric, b.barycentric, "barycentric");
  expect_array_eq(a.tangent_world, b.tangent_world, "tangent_world");
  expect_array_eq(a.bitangent_world, b.bitangent_world, "bitangent_world");
  EXPECT_EQ(a.device, b.device);
}

inline thx_msgs::contact_batch_t make_contact_batch(int k, int num_samples) {
  thx_msgs::contact_batch_t m{};
  m.utime = ival(k, 1);
  m.seq = 17 + k;
  m.server_instance = ival(k, 3);
  m.next_tick = ival(k, 4);
  m.device = 2 + k;
  m.num_dropped = 2 + k;
  m.num_samples = num_samples;
  m.samples.reserve(std::size_t(num_samples));
  for (int i = 0; i < num_samples; ++i) m.samples.push_back(make_contact(k + i));
  return m;
}
inline void expect_eq(const thx_msgs::contact_batch_t& a, const thx_msgs::contact_batch_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.seq, b.seq);
  EXPECT_EQ(a.server_instance, b.server_instance);
  EXPECT_EQ(a.next_tick, b.next_tick);
  EXPECT_EQ(a.device, b.device);
  EXPECT_EQ(a.num_dropped, b.num_dropped);
  ASSERT_EQ(a.num_samples, b.num_samples);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    SCOPED_TRACE(testing::Message() << "sample " << i);
    expect_eq(a.samples[i], b.samples[i]);
  }
}

inline thx_msgs::servo_stats_t make_servo_stats(int k) {
  thx_msgs::servo_stats_t m{};
  m.utime = ival(k, 1);
  m.ticks = ival(k, 2);
  m.missed_ticks = 12 + k;
  m.window_ticks = 999 + k;
  m.window_missed_ticks = 1 + k;
  m.window_max_consecutive_missed = 2 + k;
  m.window_clamped_ticks = 40 + k;
  m.window_s = val(k, 10);
  m.rate_nominal_hz = 1000.0 + k;
  m.rate_hz = val(k, 11);
  m.compute_p50_us = val(k, 12);
  m.compute_p99_us = val(k, 13);
  m.compute_p999_us = val(k, 14);
  m.compute_max_us = val(k, 15);
  m.wake_p50_us = val(k, 16);
  m.wake_p99_us = val(k, 17);
  m.wake_p999_us = val(k, 18);
  m.wake_max_us = val(k, 19);
  m.f_max = val(k, 20);
  m.snapshots_dropped = ival(k, 21);
  m.rss_bytes = ival(k, 22);
  m.num_clients = 3 + k;
  m.num_subscriptions = 5 + k;
  m.fault_ticks = ival(k, 30);
  m.window_fault_ticks = 7 + k;
  m.window_fault_mask = 0x1a + (k << 8);
  m.device = 7 + k;
  return m;
}
inline void expect_eq(const thx_msgs::servo_stats_t& a, const thx_msgs::servo_stats_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.ticks, b.ticks);
  EXPECT_EQ(a.missed_ticks, b.missed_ticks);
  EXPECT_EQ(a.window_ticks, b.window_ticks);
  EXPECT_EQ(a.window_missed_ticks, b.window_missed_ticks);
  EXPECT_EQ(a.window_max_consecutive_missed, b.window_max_consecutive_missed);
  EXPECT_EQ(a.window_clamped_ticks, b.window_clamped_ticks);
  EXPECT_EQ(a.window_s, b.window_s);
  EXPECT_EQ(a.rate_nominal_hz, b.rate_nominal_hz);
  EXPECT_EQ(a.rate_hz, b.rate_hz);
  EXPECT_EQ(a.compute_p50_us, b.compute_p50_us);
  EXPECT_EQ(a.compute_p99_us, b.compute_p99_us);
  EXPECT_EQ(a.compute_p999_us, b.compute_p999_us);
  EXPECT_EQ(a.compute_max_us, b.compute_max_us);
  EXPECT_EQ(a.wake_p50_us, b.wake_p50_us);
  EXPECT_EQ(a.wake_p99_us, b.wake_p99_us);
  EXPECT_EQ(a.wake_p999_us, b.wake_p999_us);
  EXPECT_EQ(a.wake_max_us, b.wake_max_us);
  EXPECT_EQ(a.f_max, b.f_max);
  EXPECT_EQ(a.snapshots_dropped, b.snapshots_dropped);
  EXPECT_EQ(a.rss_bytes, b.rss_bytes);
  EXPECT_EQ(a.num_clients, b.num_clients);
  EXPECT_EQ(a.num_subscriptions, b.num_subscriptions);
  EXPECT_EQ(a.fault_ticks, b.fault_ticks);
  EXPECT_EQ(a.window_fault_ticks, b.window_fault_ticks);
  EXPECT_EQ(a.window_fault_mask, b.window_fault_mask);
  EXPECT_EQ(a.device, b.device);
}

inline thx_msgs::subscribe_request_t make_subscribe_request(int k) {
  thx_msgs::subscribe_request_t m{};
  m.utime = ival(k, 1);
  m.seq = 4 + k;
  m.client_id = "audio-client-" + std::to_string(k);
  m.stream = std::string(thx_msgs::kStreamContact);
  m.action = thx_msgs::subscribe_request_t::ACTION_SUBSCRIBE;
  m.rate_hz = val(k, 5);
  m.batch = 1;
  return m;
}
inline void expect_eq(const thx_msgs::subscribe_request_t& a, const thx_msgs::subscribe_request_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.seq, b.seq);
  EXPECT_EQ(a.client_id, b.client_id);
  EXPECT_EQ(a.stream, b.stream);
  EXPECT_EQ(a.action, b.action);
  EXPECT_EQ(a.rate_hz, b.rate_hz);
  EXPECT_EQ(a.batch, b.batch);
}

inline thx_msgs::subscribe_reply_t make_subscribe_reply(int k) {
  thx_msgs::subscribe_reply_t m{};
  m.utime = ival(k, 1);
  m.server_instance = ival(k, 2);
  m.request_seq = 4 + k;
  m.client_id = "audio-client-" + std::to_string(k);
  m.stream = std::string(thx_msgs::kStreamContact);
  m.action = thx_msgs::subscribe_request_t::ACTION_SUBSCRIBE;
  m.accepted = 1;
  m.reason = "rate reduced to the servo rate";
  m.rate_hz = val(k, 6);
  m.batch = 1;
  m.channel = thx_msgs::stream_channel(thx_msgs::kStreamContact, true, m.client_id);
  m.heartbeat_timeout_us = 500000 + k;
  m.data_url = "udpm://239.255.76.67:" + std::to_string(7669 + k) + "?ttl=1";
  return m;
}
inline void expect_eq(const thx_msgs::subscribe_reply_t& a, const thx_msgs::subscribe_reply_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.server_instance, b.server_instance);
  EXPECT_EQ(a.request_seq, b.request_seq);
  EXPECT_EQ(a.client_id, b.client_id);
  EXPECT_EQ(a.stream, b.stream);
  EXPECT_EQ(a.action, b.action);
  EXPECT_EQ(a.accepted, b.accepted);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.rate_hz, b.rate_hz);
  EXPECT_EQ(a.batch, b.batch);
  EXPECT_EQ(a.channel, b.channel);
  EXPECT_EQ(a.heartbeat_timeout_us, b.heartbeat_timeout_us);
  EXPECT_EQ(a.data_url, b.data_url);
}

inline thx_msgs::heartbeat_t make_heartbeat(int k) {
  thx_msgs::heartbeat_t m{};
  m.utime = ival(k, 1);
  m.seq = 100 + k;
  m.server_instance = ival(k, 3);
  m.client_id = "physics_" + std::to_string(k);
  return m;
}
inline void expect_eq(const thx_msgs::heartbeat_t& a, const thx_msgs::heartbeat_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.seq, b.seq);
  EXPECT_EQ(a.server_instance, b.server_instance);
  EXPECT_EQ(a.client_id, b.client_id);
}

inline thx_msgs::hello_t make_hello(int k) {
  thx_msgs::hello_t m{};
  m.utime = ival(k, 1);
  m.seq = 9 + k;
  m.server_instance = -ival(k, 3);  // any non-zero 64-bit value, negative included
  m.start_utime = ival(k, 4);
  m.start_unix_us = ival(k, 5);
  m.protocol_version = thx_msgs::hello_t::PROTOCOL_VERSION;
  m.servo_rate_hz = val(k, 7);
  m.server_name = "hapticd@host" + std::to_string(k);
  m.device = "Phantom0@localhost";
  m.scene_name = "marble_bricks" + std::to_string(k);
  m.texture_fingerprint = static_cast<std::int64_t>(0xcbf29ce484222325ULL) + ival(k, 8);  // negative too
  m.control_url = "udpm://239.255.76.67:" + std::to_string(7668 + k) + "?ttl=0";
  m.device_names = "Phantom0,left_hand,pen-" + std::to_string(k);
  return m;
}
inline void expect_eq(const thx_msgs::hello_t& a, const thx_msgs::hello_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.seq, b.seq);
  EXPECT_EQ(a.server_instance, b.server_instance);
  EXPECT_EQ(a.start_utime, b.start_utime);
  EXPECT_EQ(a.start_unix_us, b.start_unix_us);
  EXPECT_EQ(a.protocol_version, b.protocol_version);
  EXPECT_EQ(a.servo_rate_hz, b.servo_rate_hz);
  EXPECT_EQ(a.server_name, b.server_name);
  EXPECT_EQ(a.device, b.device);
  EXPECT_EQ(a.scene_name, b.scene_name);
  EXPECT_EQ(a.texture_fingerprint, b.texture_fingerprint);
  EXPECT_EQ(a.control_url, b.control_url);
  EXPECT_EQ(a.device_names, b.device_names);
}

inline thx_msgs::client_force_t make_client_force(int k) {
  thx_msgs::client_force_t m{};
  m.utime = ival(k, 1);
  m.seq = 33 + k;
  m.ref_tick = ival(k, 3);
  m.timeout_us = 20000 + k;
  m.client_id = "physics";
  m.source = "physics.sphere" + std::to_string(k);
  fill(m.f_world, k, 10);
  fill(m.tau_world, k, 20);
  fill(m.p_world, k, 30);
  m.device = 1 + k;
  return m;
}
inline void expect_eq(const thx_msgs::client_force_t& a, const thx_msgs::client_force_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.seq, b.seq);
  EXPECT_EQ(a.ref_tick, b.ref_tick);
  EXPECT_EQ(a.timeout_us, b.timeout_us);
  EXPECT_EQ(a.client_id, b.client_id);
  EXPECT_EQ(a.source, b.source);
  expect_array_eq(a.f_world, b.f_world, "f_world");
  expect_array_eq(a.tau_world, b.tau_world, "tau_world");
  expect_array_eq(a.p_world, b.p_world, "p_world");
  EXPECT_EQ(a.device, b.device);
}

inline thx_msgs::server_command_t make_server_command(int k) {
  thx_msgs::server_command_t m{};
  m.utime = ival(k, 1);
  m.seq = 41 + k;
  m.client_id = "study" + std::to_string(k);
  m.action = thx_msgs::server_command_t::ACTION_RESET_FAULTS + 100 * k;
  m.argument = "scenes/bricks" + std::to_string(k) + ".yaml";  // a later ACTION_LOAD_SCENE's operand
  return m;
}
// EXPECT_EQ on each listed member (scalars and strings), in order.
template <class T, class... M>
void expect_members_eq(const T& a, const T& b, M T::*... members) {
  int index = 0;
  auto check = [&](auto member) { EXPECT_EQ(a.*member, b.*member) << T::getTypeName() << " member #" << index++; };
  (check(members), ...);
}

inline void expect_eq(const thx_msgs::server_command_t& a, const thx_msgs::server_command_t& b) {
  using C = thx_msgs::server_command_t;
  expect_members_eq(a, b, &C::utime, &C::seq, &C::client_id, &C::action, &C::argument);
}

// The answer to make_server_command(k): done for even k, refused for odd k.
inline thx_msgs::server_command_reply_t make_server_command_reply(int k) {
  const thx_msgs::server_command_t cmd = make_server_command(k);
  const bool done = k % 2 == 0;
  thx_msgs::server_command_reply_t m{};
  m.utime = ival(k, 1);
  m.server_instance = ival(k, 2);
  m.request_seq = cmd.seq;
  m.client_id = cmd.client_id;
  m.action = cmd.action;
  m.accepted = done;
  m.reason = done ? "" : "unknown action " + std::to_string(cmd.action);
  m.tick = done ? ival(k, 8) : -1;
  return m;
}
inline void expect_eq(const thx_msgs::server_command_reply_t& a, const thx_msgs::server_command_reply_t& b) {
  using R = thx_msgs::server_command_reply_t;
  expect_members_eq(a, b, &R::utime, &R::server_instance, &R::request_seq, &R::client_id, &R::action, &R::accepted,
                    &R::reason, &R::tick);
}

// Encode into an exactly sized buffer; checks encode() returns getEncodedSize().
template <class T>
std::vector<std::uint8_t> encode(const T& m) {
  const int size = m.getEncodedSize();
  std::vector<std::uint8_t> buf(std::size_t(size > 0 ? size : 0));
  const int n = m.encode(buf.data(), 0, size);
  EXPECT_EQ(n, size) << T::getTypeName();
  return buf;
}

}  // namespace thx_test
