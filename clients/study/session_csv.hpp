#pragma once
// The session CSV (docs/study.md §2): "# key: value" header lines, one column line, one row per
// trial. The writer appends and flushes row by row, so a runner that crashes after a trial keeps
// every answer given; the reader names file, line and field of anything it refuses.
#include <fstream>
#include <string>
#include <string_view>

#include "clients/study/session.hpp"

namespace thx::study {

inline constexpr int kSessionFormat = 1;
inline constexpr std::string_view kSessionMagic = "# texhaptics study session";

// The column line, in order.
std::string columnLine();

class SessionWriter {
 public:
  // Creates (or truncates) `path` and writes the header. Throws SessionError for a header that
  // breaks the format, thx::Error (Io) when the file cannot be written.
  SessionWriter(const std::string& path, const SessionHeader& header);
  SessionWriter(const SessionWriter&) = delete;  // rules_ refers to header_
  SessionWriter& operator=(const SessionWriter&) = delete;
  // Checks the row against the header and the rows before it, writes it and flushes.
  void append(const TrialRow& row);

 private:
  void flushOrThrow();
  std::string path_;
  SessionHeader header_;
  RowRules rules_;
  std::ofstream out_;
  int line_ = 0;
};

// Writes a whole session through SessionWriter.
void writeSession(const std::string& path, const Session& session);
// The text writeSession() writes, checked by the same rules; `name` stands for the file in
// messages. The header and each row are formatted by the same functions the writer uses.
std::string formatSession(const Session& session, const std::string& name);

// Throws SessionError naming `source`, the line and the field; thx::Error (Io) if unreadable.
Session readSession(const std::string& path);
Session parseSession(std::string_view text, const std::string& source);

}  // namespace thx::study
