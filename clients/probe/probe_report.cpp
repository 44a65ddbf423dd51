#include "probe_report.hpp"

#include "base/json_text.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace thx::client {

using json::escaped;

void writeProbeJson(const std::string& path, const ProbeResult& r) {
  const bool to_stdout = path == "-";
  std::FILE* f = to_stdout ? stdout : std::fopen(path.c_str(), "w");
  if (!f) throw thx::Error(thx::Error::Kind::Io, "cannot write " + path + ": " + std::strerror(errno));
  const StreamReport& s = r.report;
  std::fprintf(f,
               "{\n"
               "  \"stream\": \"%s\",\n  \"batch\": %s,\n  \"client_id\": \"%s\",\n"
               "  \"requested_rate_hz\": %.6g,\n  \"granted_rate_hz\": %.6g,\n  \"state\": \"%s\",\n"
               "  \"reason\": \"%s\",\n  \"channel\": \"%s\",\n  \"duration_s\": %.6g,\n"
               "  \"messages\": %llu,\n  \"span_s\": %.6f,\n  \"achieved_rate_hz\": %.6f,\n"
               "  \"rate_error\": %.6f,\n  \"steady_rate_error\": %.6f,\n"
               "  \"latency_us\": {\"p50\": %.1f, \"p99\": %.1f, \"max\": %.1f},\n"
               "  \"gaps\": %llu,\n  \"missing\": %llu,\n  \"duplicates\": %llu,\n  \"other_device\": %llu,\n"
               "  \"samples\": %llu,\n  \"sample_rate_hz\": %.3f,\n  \"samples_missing\": %llu,\n"
               "  \"samples_dropped_by_server\": %llu,\n  \"samples_out_of_order\": %llu,\n"
               "  \"server_instance\": %lld,\n  \"reconnects\": %llu,\n  \"server_restarts\": %llu,\n"
               "  \"admission_s\": %.6f,\n  \"first_message_s\": %.6f,\n"
               "  \"cpu_window_s\": %.6f,\n  \"window_wall_s\": %.6f,\n  \"cpu_total_s\": %.6f,\n"
               "  \"error\": \"%s\"\n"
               "}\n",
               thx_msgs::stream_name(r.options.stream), r.options.batch ? "true" : "false", r.options.client_id.c_str(),
               r.options.rate_hz, r.status.granted_hz, toString(r.status.state), escaped(r.status.reason).c_str(),
               r.status.channel.c_str(), r.options.duration_s, (unsigned long long)s.messages, s.span_s,
               s.achieved_rate_hz,
               r.status.granted_hz > 0 ? s.achieved_rate_hz / r.status.granted_hz - 1.0 : 0.0,
               r.status.granted_hz > 0 && s.steady_rate_hz > 0 ? s.steady_rate_hz / r.status.granted_hz - 1.0 : 0.0,
               s.latency_p50_us,
               s.latency_p99_us, s.latency_max_us, (unsigned long long)s.gaps, (unsigned long long)s.missing,
               (unsigned long long)s.duplicates, (unsigned long long)r.status.other_device,
               (unsigned long long)s.samples, s.sample_rate_hz,
               (unsigned long long)s.samples_missing, (unsigned long long)s.samples_dropped,
               (unsigned long long)s.samples_out_of_order, (long long)r.server_instance,
               (unsigned long long)r.reconnects, (unsigned long long)s.restarts, r.admission_s, r.first_message_s,
               r.cpu_window_s, r.window_wall_s, r.cpu_total_s, escaped(r.error).c_str());
  const bool failed = std::ferror(f) != 0;
  if (!to_stdout && std::fclose(f) != 0) throw thx::Error(thx::Error::Kind::Io, "cannot write " + path + ": " + std::strerror(errno));
  if (failed) throw thx::Error(thx::Error::Kind::Io, "cannot write " + path);
}

void printProbeSummary(std::FILE* out, const ProbeResult& r) {
  const StreamReport& s = r.report;
  std::fprintf(out, "probe-client %s%s: asked %.6g Hz, granted %.6g Hz (%s)%s%s\n", thx_msgs::stream_name(r.options.stream),
               r.options.batch ? " (batched)" : "", r.options.rate_hz, r.status.granted_hz, toString(r.status.state),
               r.status.reason.empty() ? "" : ": ", r.status.reason.c_str());
  std::fprintf(out, "  messages   %llu in %.3f s = %.3f Hz (%+.2f %%)\n", (unsigned long long)s.messages, s.span_s,
               s.achieved_rate_hz, r.status.granted_hz > 0 ? 100.0 * (s.achieved_rate_hz / r.status.granted_hz - 1.0) : 0.0);
  if (r.options.batch) {
    std::fprintf(out, "  samples    %llu (%.1f /s), %llu missing, %llu dropped by the server, %llu out of order\n",
                 (unsigned long long)s.samples, s.sample_rate_hz, (unsigned long long)s.samples_missing,
                 (unsigned long long)s.samples_dropped, (unsigned long long)s.samples_out_of_order);
  }
  std::fprintf(out, "  latency    p50 %.1f us, p99 %.1f us, max %.1f us (server tick -> receipt)\n", s.latency_p50_us,
               s.latency_p99_us, s.latency_max_us);
  std::fprintf(out, "  gaps       %llu (%llu messages missing), %llu duplicates, %llu reconnects, %llu server restarts\n",
               (unsigned long long)s.gaps, (unsigned long long)s.missing, (unsigned long long)s.duplicates,
               (unsigned long long)r.reconnects, (unsigned long long)s.restarts);
  if (!r.error.empty()) std::fprintf(out, "  error      %s\n", r.error.c_str());
}

}  // namespace thx::client
