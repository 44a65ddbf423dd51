#include "server/port_plan.hpp"

#include <cctype>

#include "base/error.hpp"

namespace thx::srv {

namespace {

// A port 1..65535 from all-digit text, else nullopt.
std::optional<int> portOf(const std::string& text) {
  if (text.empty() || text.size() > 5) return std::nullopt;
  for (char c : text) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
  }
  const int p = std::stoi(text);
  if (p < 1 || p > 65535) return std::nullopt;
  return p;
}

[[noreturn]] void bad(const std::string& what) { throw UsageError(what); }

}  // namespace

PortPlan planPorts(const std::string& lcm_url, int max_clients, const std::string& control_spec,
                   const std::string& data_spec) {
  PortPlan plan;
  plan.bus = parseUdpmUrl(lcm_url);
  if (!plan.bus) {
    for (const auto& [option, spec] : {std::pair{"--control-port", control_spec}, std::pair{"--data-ports", data_spec}}) {
      if (!spec.empty() && spec != "off") {
        bad(std::string(option) + " " + spec + ": needs a udpm:// --lcm-url (ports on its multicast group), got '" +
            lcm_url + "'");
      }
    }
    return plan;
  }
  const int bus = plan.bus->port;
  if (control_spec == "off") {
    plan.control_port = 0;
  } else if (control_spec.empty()) {
    plan.control_port = bus + 1 <= 65535 ? bus + 1 : 0;
  } else {
    const std::optional<int> p = portOf(control_spec);
    if (!p) bad("--control-port " + control_spec + ": expected a port 1..65535 or 'off'");
    if (*p == bus) bad("--control-port " + control_spec + ": is the bus port of --lcm-url; expected another port");
    plan.control_port = *p;
  }
  if (data_spec == "off") return plan;
  if (data_spec.empty()) {
    plan.data_first = bus + 2;
    plan.data_last = bus + 1 + max_clients;
    if (plan.data_last > 65535) {
      bad("the default data ports " + std::to_string(plan.data_first) + "-" + std::to_string(plan.data_last) +
          " (bus port + 2 .. + 1 + --max-clients) end above 65535: give --data-ports FIRST-LAST or a lower bus port");
    }
  } else {
    const std::size_t dash = data_spec.find('-');
    const std::optional<int> first = portOf(data_spec.substr(0, dash));
    const std::optional<int> last = dash == std::string::npos ? first : portOf(data_spec.substr(dash + 1));
    if (!first || !last || *last < *first) {
      bad("--data-ports " + data_spec + ": expected FIRST-LAST (ports 1..65535, FIRST <= LAST), one port, or 'off'");
    }
    plan.data_first = *first;
    plan.data_last = *last;
  }
  auto inside = [&](int p) { return p >= plan.data_first && p <= plan.data_last; };
  const std::string range = std::to_string(plan.data_first) + "-" + std::to_string(plan.data_last);
  if (inside(bus)) bad("--data-ports " + range + ": holds the bus port " + std::to_string(bus) + " of --lcm-url; expected a range apart from it");
  if (plan.control_port > 0 && inside(plan.control_port)) {
    bad("--data-ports " + range + ": holds the control port " + std::to_string(plan.control_port) +
        "; expected a range apart from it (or another --control-port)");
  }
  return plan;
}

}  // namespace thx::srv
