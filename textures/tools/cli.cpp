#include "textures/tools/cli.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace thx::tex::cli {

std::optional<std::string> Args::get(const std::string& name) const {
  const auto it = options.find(name);
  if (it == options.end()) return std::nullopt;
  return it->second.back();
}

std::string Args::require(const std::string& name) const {
  const auto value = get(name);
  if (!value) throw UsageError("missing required option " + name);
  return *value;
}

Args parseArgs(const std::vector<std::string>& argv, const std::vector<OptionSpec>& options) {
  Args args;
  for (std::size_t k = 0; k < argv.size(); ++k) {
    const std::string& token = argv[k];
    if (token == "-h" || token == "--help") {
      args.options["--help"].push_back("");
      continue;
    }
    if (token.size() < 2 || token.compare(0, 2, "--") != 0) {
      args.positional.push_back(token);
      continue;
    }
    const std::size_t eq = token.find('=');
    const std::string name = token.substr(0, eq);
    const auto spec = std::find_if(options.begin(), options.end(), [&](const OptionSpec& o) { return o.name == name; });
    if (spec == options.end()) throw UsageError("unknown option " + name);
    if (args.has(name) && !spec->repeatable) throw UsageError("option " + name + " given more than once");
    if (!spec->takes_value) {
      if (eq != std::string::npos) throw UsageError("option " + name + " takes no value");
      args.options[name].push_back("");
    } else if (eq != std::string::npos) {
      args.options[name].push_back(token.substr(eq + 1));
    } else {
      if (k + 1 >= argv.size()) throw UsageError("option " + name + " needs a value");
      args.options[name].push_back(argv[++k]);
    }
  }
  return args;
}

void requirePositional(const Args& args, const std::vector<std::string>& names) {
  if (args.positional.size() == names.size()) return;
  std::string expected;
  for (const std::string& n : names) expected += (expected.empty() ? "" : " ") + n;
  if (args.positional.size() < names.size()) throw UsageError("missing argument(s); expected " + expected);
  throw UsageError("unexpected argument '" + args.positional[names.size()] + "'; expected " + expected);
}

double parseNumber(const std::string& what, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) {
    throw UsageError(what + ": '" + text + "' is not a finite number");
  }
  return v;
}

int parseInt(const std::string& what, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || v < -2147483647L || v > 2147483647L) {
    throw UsageError(what + ": '" + text + "' is not an integer");
  }
  return int(v);
}

std::uint64_t parseSeed(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || text[0] == '-' || end != text.c_str() + text.size() || errno == ERANGE) {
    throw UsageError("--seed: '" + text + "' is not an integer in [0, 2^64)");
  }
  return std::uint64_t(v);
}

int parseBits(const std::optional<std::string>& text, int default_bits) {
  if (!text) return default_bits;
  if (*text == "8") return 8;
  if (*text == "16") return 16;
  throw UsageError("--bits: '" + *text + "'; expected 8 or 16");
}

GreenConvention parseGreen(const std::optional<std::string>& text) {
  if (!text || *text == "opengl") return GreenConvention::OpenGL;
  if (*text == "directx") return GreenConvention::DirectX;
  throw UsageError("--green: '" + *text + "'; expected opengl or directx");
}

Address parseAddress(const std::optional<std::string>& text, Address default_address) {
  if (!text) return default_address;
  if (*text == "wrap") return Address::Wrap;
  if (*text == "clamp") return Address::Clamp;
  throw UsageError("--address: '" + *text + "'; expected wrap or clamp");
}

}  // namespace thx::tex::cli
