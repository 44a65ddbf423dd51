// study-analyze: the user studies' session CSVs (docs/study.md) into the paper's tables and plots.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "base/program_main.hpp"
#include "clients/study/analyze_run.hpp"

namespace {

constexpr const char* kHelp = R"(usage: study-analyze [--out DIR] SESSION.csv...

Reads user-study session files (docs/study.md §2: one CSV per participant and study, as the
trial runner writes them) and writes into DIR (default: study-results):
  study.md                             every table below as Markdown, with the plots
  identification_by_condition.csv      Study 1: ID rate, correct-answer time, all cues / one removed
  identification_by_cue.csv           Study 1: the same per cue removed, with Student and Welch
                                       t-tests of the times against all cues, Cohen's d
  identification_ratings.csv          Study 1: ease, cue use and cue accuracy per cue condition
  identification_by_surface.csv       Study 1: per surface drawn
  identification_confusion.csv        Study 1: surface drawn against surface answered
  identification_family_confusion.csv Study 1: the same by sound family
  identification_by_cue.png           Study 1: ID rate and time per cue condition
  ratings_relief_vs_normal.csv        Study 2: mean ratings, paired t, p, Cohen's d
  ratings_by_surface.csv              Study 2: per surface, Welch t between representations
  ratings_by_representation.png       Study 2: ratings of relief and normal maps
Only the studies present in the files are analysed.

options:
  --out DIR   the output folder (created if missing)
  --help      this text
exit status: 0 done, 1 a file that cannot be read or breaks the format (the message names the
file, line and field), 2 a command-line mistake.
)";

}  // namespace

int main(int argc, char** argv) {
  return thx::runProgram("study-analyze", kHelp, argc, argv, [](const std::vector<std::string>& args) {
    std::string out_dir = "study-results";
    std::vector<std::string> files;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      if (a == "--out") {
        if (i + 1 >= args.size()) throw thx::UsageError("--out: expected a folder after it");
        out_dir = args[++i];
      } else if (a.rfind("--", 0) == 0) {
        throw thx::UsageError("unknown option '" + a + "'");
      } else {
        files.push_back(a);
      }
    }
    if (files.empty()) throw thx::UsageError("expected at least one session file");
    const thx::study::AnalyzeOutput out = thx::study::analyzeSessions(files, out_dir);
    std::printf("study-analyze: %d identification and %d relief-vs-normal sessions; wrote %zu files to %s\n",
                out.identification_sessions, out.rating_sessions, out.files.size(), out_dir.c_str());
    return 0;
  });
}
