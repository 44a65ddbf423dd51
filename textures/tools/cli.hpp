#pragma once
// Command-line plumbing shared by the texturetool subcommands: option parsing, strict number
// parsing, and the subcommand table. Usage mistakes throw UsageError (exit 2); bad input files
// or parameters throw TextureError (exit 1).
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "textures/sampling.hpp"
#include "textures/texture_io.hpp"

namespace thx::tex::cli {

using thx::UsageError;

struct OptionSpec {
  std::string name;  // with the leading "--"
  bool takes_value = true;
  bool repeatable = false;
};

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> options;  // name -> values ("" for flags)

  bool has(const std::string& name) const { return options.count(name) != 0; }
  std::optional<std::string> get(const std::string& name) const;  // the (single) value, if given
  std::string require(const std::string& name) const;              // UsageError if missing
};

// Accepts "--name value" and "--name=value"; "-h" / "--help" set the flag "--help".
Args parseArgs(const std::vector<std::string>& argv, const std::vector<OptionSpec>& options);
// UsageError unless exactly `names.size()` positional arguments were given.
void requirePositional(const Args& args, const std::vector<std::string>& names);

double parseNumber(const std::string& what, const std::string& text);  // finite, whole string
int parseInt(const std::string& what, const std::string& text);
std::uint64_t parseSeed(const std::string& text);
int parseBits(const std::optional<std::string>& text, int default_bits);
GreenConvention parseGreen(const std::optional<std::string>& text);
Address parseAddress(const std::optional<std::string>& text, Address default_address);

struct Command {
  const char* name;
  const char* summary;
  const char* help;  // full usage text
  int (*run)(const Args& args);
  std::vector<OptionSpec> options;
};

const std::vector<Command>& commands();

int runGenerate(const Args& args);
int runInfo(const Args& args);
int runFromHeight(const Args& args);
int runSmooth(const Args& args);
int runPreview(const Args& args);
int runImport(const Args& args);

}  // namespace thx::tex::cli
