#pragma once
// What mesh_import.cpp hands Assimp instead of a PLY file: the same vertex, face and tristrips
// elements, checked and rewritten as binary PLY under a header of our own.
//
// Why: Assimp 5.2.5's PLY reader sizes its memory by numbers it reads, before finding out whether
// the file holds that much. `element vertex 2000000000` in a 200-byte file made it allocate 24 GB
// (and run for minutes); an ASCII list count of 4294967295 (or -1, read as unsigned) allocates
// 32 GB for one face. Its header parser also reads an element of a name it does not know as
// having no instances (a misaligned body after it) and a `comment TextureFile` line as an
// element. So every count is checked here against the bytes that must hold it, the body is
// walked value by value (ASCII as whitespace-separated numbers, binary by the types' sizes), and
// Assimp only ever sees a header it parses as we do and a binary body whose every list count and
// element count is backed by the data that follows. The rewrite is at most 4x the file's size
// (an ASCII value of two bytes becomes a double of eight).
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.hpp"

namespace thx::mesh::ply {

struct Type {
  const char* name;  // the canonical name written in the rewritten header
  int size;
  bool integer, is_signed;
};

struct Property {
  std::string name;
  Type type{};
  bool list = false;
  Type count_type{};  // for a list
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  bool kept = false;  // vertex, face, tristrips: what Assimp turns into a mesh
};

// A piece of file text in a message: printable ASCII, other bytes as \xNN, at most `max`
// characters of it.
inline std::string shown(std::string_view s, std::size_t max = 40) {
  std::string out;
  for (std::size_t i = 0; i < s.size() && i < max; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return s.size() > max ? out + "..." : out;
}

[[noreturn]] inline void refuse(const std::string& source, const std::string& what) {
  throw Error(Error::Kind::Config, "mesh " + source + ": PLY " + what);
}

inline bool typeNamed(std::string_view name, Type& out) {
  static const struct {
    const char* names[2];
    Type type;
  } kTypes[] = {{{"char", "int8"}, {"char", 1, true, true}},       {{"uchar", "uint8"}, {"uchar", 1, true, false}},
                {{"short", "int16"}, {"short", 2, true, true}},    {{"ushort", "uint16"}, {"ushort", 2, true, false}},
                {{"int", "int32"}, {"int", 4, true, true}},        {{"uint", "uint32"}, {"uint", 4, true, false}},
                {{"float", "float32"}, {"float", 4, false, true}}, {{"double", "float64"}, {"double", 8, false, true}}};
  for (const auto& t : kTypes) {
    if (name == t.names[0] || name == t.names[1]) {
      out = t.type;
      return true;
    }
  }
  return false;
}

inline std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

struct Header {
  enum class Format { Ascii, BinaryLittle, BinaryBig } format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t body = 0;  // offset of the first byte after end_header's line
};

inline Header readHeader(std::string_view file, const std::string& source) {
  Header h;
  std::size_t at = 0;
  bool have_format = false;
  for (int number = 1;; ++number) {
    const std::size_t end = file.find('\n', at);
    if (end == std::string_view::npos) refuse(source, "header has no end_header line");
    std::string_view line = file.substr(at, end - at);
    at = end + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const auto w = words(line);
    const std::string where = "header line " + std::to_string(number) + " ('" + shown(line) + "')";
    if (number == 1) {
      if (w.size() != 1 || w[0] != "ply") refuse(source, "file must start with a line 'ply'");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    // Names reach Assimp's header parser, which stops a word at any control byte.
    for (std::string_view word : w)
      for (char c : word)
        if (static_cast<unsigned char>(c) < 0x21 || static_cast<unsigned char>(c) > 0x7e)
          refuse(source, where + ": expected printable ASCII words");
    if (w[0] == "format") {
      if (have_format || w.size() != 3 || w[2] != "1.0")
        refuse(source, where + ": expected one 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (w[1] == "ascii") h.format = Header::Format::Ascii;
      else if (w[1] == "binary_little_endian") h.format = Header::Format::BinaryLittle;
      else if (w[1] == "binary_big_endian") h.format = Header::Format::BinaryBig;
      else refuse(source, where + ": expected format ascii, binary_little_endian or binary_big_endian");
      have_format = true;
    } else if (w[0] == "element") {
      std::uint64_t count = 0;
      if (w.size() != 3 || std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ptr != w[2].data() + w[2].size() ||
          count > std::numeric_limits<std::uint32_t>::max())
        refuse(source, where + ": expected 'element NAME COUNT' with COUNT a whole number below 2^32");
      Element e{std::string(w[1]), count, {}, w[1] == "vertex" || w[1] == "face" || w[1] == "tristrips"};
      for (const Element& other : h.elements)
        if (e.kept && other.name == e.name) refuse(source, where + ": a second element '" + e.name + "'");
      h.elements.push_back(std::move(e));
    } else if (w[0] == "property") {
      if (h.elements.empty()) refuse(source, where + ": a property before any element");
      Property p;
      const bool list = w.size() == 5 && w[1] == "list";
      if (!(list ? typeNamed(w[2], p.count_type) && typeNamed(w[3], p.type) : w.size() == 3 && typeNamed(w[1], p.type)))
        refuse(source, where + ": expected 'property TYPE NAME' or 'property list TYPE TYPE NAME' with TYPE one of "
                               "char, uchar, short, ushort, int, uint, float, double (or int8 ... float64)");
      if (list && !p.count_type.integer) refuse(source, where + ": a list count must be of an integer type");
      p.list = list;
      p.name = std::string(w.back());
      h.elements.back().properties.push_back(std::move(p));
    } else if (w[0] == "end_header" && w.size() == 1) {
      break;
    } else {
      refuse(source, where + ": expected format, element, property, comment, obj_info or end_header");
    }
  }
  if (!have_format) refuse(source, "header has no format line");
  for (const Element& e : h.elements)
    if (e.count > 0 && e.properties.empty())
      refuse(source, "element '" + shown(e.name) + "' has instances but no properties");
  h.body = at;
  return h;
}

inline void append(std::vector<std::uint8_t>& out, const void* p, std::size_t n) {
  const auto* b = static_cast<const std::uint8_t*>(p);
  out.insert(out.end(), b, b + n);
}

// Writes `value` as `type`, little-endian; false if an integer type cannot hold it.
inline bool putValue(std::vector<std::uint8_t>& out, const Type& type, double value, bool is_integer_text) {
  static_assert(std::endian::native == std::endian::little, "the rewritten PLY is written in native order");
  if (type.integer) {
    if (!is_integer_text) return false;
    const double lo = type.is_signed ? -std::ldexp(1.0, 8 * type.size - 1) : 0.0;
    const double hi = type.is_signed ? std::ldexp(1.0, 8 * type.size - 1) - 1.0 : std::ldexp(1.0, 8 * type.size) - 1.0;
    if (!(value >= lo && value <= hi)) return false;
    const auto v = static_cast<std::int64_t>(value);
    append(out, &v, std::size_t(type.size));  // the low bytes of the two's complement
    return true;
  }
  if (type.size == 8) {
    append(out, &value, 8);
  } else {
    // A double beyond float's range is undefined behaviour to convert; it becomes an infinity
    // (the mesh check then refuses it as non-finite).
    const float f = std::fabs(value) > double(std::numeric_limits<float>::max())
                        ? std::copysign(std::numeric_limits<float>::infinity(), float(value > 0 ? 1 : -1))
                        : float(value);
    append(out, &f, 4);
  }
  return true;
}

// The ASCII body as binary little-endian: whitespace-separated numbers, lists by their counts.
class AsciiBody {
 public:
  AsciiBody(std::string_view body, const std::string& source) : text_(body), source_(source) {}

  // The next value as `type`, appended to `out` when `keep`; returns it.
  double next(const Type& type, const Element& e, std::uint64_t instance, bool keep, std::vector<std::uint8_t>& out) {
    while (at_ < text_.size() && isSpace(text_[at_])) ++at_;
    if (at_ == text_.size()) {
      refuse(source_, "data ends in element '" + shown(e.name) + "' (instance " + std::to_string(instance) + " of " +
                          std::to_string(e.count) + "); expected the values the header declares");
    }
    const std::size_t start = at_;
    while (at_ < text_.size() && !isSpace(text_[at_])) ++at_;
    std::string_view word = text_.substr(start, at_ - start);
    if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    const bool whole_word = ec == std::errc() && end == word.data() + word.size();
    std::vector<std::uint8_t> scratch;
    if (!whole_word || !putValue(keep ? out : scratch, type, value, isIntegerText(word))) {
      refuse(source_, "value '" + shown(word) + "' in element '" + shown(e.name) + "' (instance " +
                          std::to_string(instance) + ") is not a number of type " + type.name);
    }
    return value;
  }

 private:
  static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
  static bool isIntegerText(std::string_view w) {
    std::size_t i = w[0] == '-' ? 1 : 0;
    if (i == w.size()) return false;
    for (; i < w.size(); ++i)
      if (w[i] < '0' || w[i] > '9') return false;
    return true;
  }
  std::string_view text_;
  std::string source_;
  std::size_t at_ = 0;
};

// The binary body: checks that every count is backed by bytes, copying kept elements as they are.
class BinaryBody {
 public:
  BinaryBody(std::string_view body, bool big_endian, const std::string& source)
      : data_(body), big_(big_endian), source_(source) {}

  std::uint64_t count(const Property& p, const Element& e, std::uint64_t instance) {
    const char* b = take(std::size_t(p.count_type.size), e, instance);
    std::uint64_t u = 0;
    for (int k = 0; k < p.count_type.size; ++k) {
      const auto byte = std::uint64_t(static_cast<unsigned char>(b[big_ ? k : p.count_type.size - 1 - k]));
      u = u << 8 | byte;
    }
    if (p.count_type.is_signed && (u >> (8 * p.count_type.size - 1)) != 0) {
      refuse(source_, "list '" + shown(p.name) + "' in element '" + shown(e.name) + "' (instance " +
                          std::to_string(instance) + ") has a negative count");
    }
    return u;
  }
  void skip(std::uint64_t bytes, const Element& e, std::uint64_t instance) { take(bytes, e, instance); }
  std::size_t at() const { return at_; }

 private:
  const char* take(std::uint64_t n, const Element& e, std::uint64_t instance) {
    if (n > data_.size() - at_) {
      refuse(source_, "data ends in element '" + shown(e.name) + "' (instance " + std::to_string(instance) + " of " +
                          std::to_string(e.count) + ", byte " + std::to_string(at_) +
                          " of the data); expected the values the header declares");
    }
    const char* p = data_.data() + at_;
    at_ += std::size_t(n);
    return p;
  }
  std::string_view data_;
  bool big_;
  std::string source_;
  std::size_t at_ = 0;
};

inline void writeHeader(std::vector<std::uint8_t>& out, const Header& h, bool big_endian) {
  std::string text = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") + " 1.0\n";
  for (const Element& e : h.elements) {
    if (!e.kept) continue;
    text += "element " + e.name + " " + std::to_string(e.count) + "\n";
    for (const Property& p : e.properties) {
      text += p.list ? std::string("property list ") + p.count_type.name + " " + p.type.name
                     : std::string("property ") + p.type.name;
      text += " " + p.name + "\n";
    }
  }
  text += "end_header\n";
  append(out, text.data(), text.size());
}

// The PLY file `file` rewritten as described above; throws thx::Error(Config) naming `source`.
inline std::vector<std::uint8_t> rewrite(std::string_view file, const std::string& source) {
  const Header h = readHeader(file, source);
  const std::string_view body = file.substr(h.body);
  std::vector<std::uint8_t> out;
  if (h.format == Header::Format::Ascii) {
    writeHeader(out, h, false);
    AsciiBody in(body, source);
    for (const Element& e : h.elements) {
      for (std::uint64_t i = 0; i < e.count; ++i) {
        for (const Property& p : e.properties) {
          if (!p.list) {
            in.next(p.type, e, i, e.kept, out);
            continue;
          }
          // A count's text was checked to be a whole number within its type (non-negative for
          // the list to make sense): every value it announces must then be read from the text.
          const double n = in.next(p.count_type, e, i, e.kept, out);
          if (n < 0) {
            refuse(source, "list '" + shown(p.name) + "' in element '" + shown(e.name) + "' (instance " +
                               std::to_string(i) + ") has a negative count");
          }
          for (std::uint64_t k = 0; k < std::uint64_t(n); ++k) in.next(p.type, e, i, e.kept, out);
        }
      }
    }
    return out;
  }
  const bool big = h.format == Header::Format::BinaryBig;
  writeHeader(out, h, big);
  BinaryBody in(body, big, source);
  for (const Element& e : h.elements) {
    const std::size_t start = in.at();
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const Property& p : e.properties) {
        if (p.list) in.skip(in.count(p, e, i) * std::uint64_t(p.type.size), e, i);
        else in.skip(std::uint64_t(p.type.size), e, i);
      }
    }
    if (e.kept) append(out, body.data() + start, in.at() - start);
  }
  return out;
}

}  // namespace thx::mesh::ply
