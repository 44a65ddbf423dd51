#pragma once
// What study-analyze does after parsing its command line: read the session files, analyse each
// study present, write its tables (study.md, one CSV per table) and plots into a folder.
#include <string>
#include <vector>

namespace thx::study {

struct AnalyzeOutput {
  std::vector<std::string> files;  // every file written, in order
  int identification_sessions = 0, rating_sessions = 0;
};

// Throws SessionError (a bad or inconsistent session file), thx::Error (Io) for a folder or file
// that cannot be written.
AnalyzeOutput analyzeSessions(const std::vector<std::string>& session_files, const std::string& out_dir);

}  // namespace thx::study
