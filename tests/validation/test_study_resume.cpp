// A study that is stopped resumes where it stopped (`study NAME --resume DIR`): the points that
// finished are read back from DIR/points, the rest are measured, and the study ends with the
// uninterrupted study's table, charts and summary (its measured costs are a point's own: read
// back, a point keeps the cost it was measured with). Another study or size refuses to resume,
// in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "../test_support.hpp"

using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

// The energy study, tiny, one point at a time: 12 points of run_point, a few seconds in all.
constexpr std::size_t kPoints = 12;

std::string energy_study(const std::string& folder_option, const fs::path& dir) {
  return "study energy --size tiny --jobs 1 " + folder_option + " \"" + dir.string() + "\"";
}

// The files DIR/points/*.json and what they hold.
std::map<std::string, std::string> stored_points(const fs::path& dir) {
  std::map<std::string, std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir / "points", ec))
    if (e.path().extension() == ".json") out[e.path().filename().string()] = read_file(e.path());
  return out;
}

std::size_t stored_count(const fs::path& dir) {
  std::error_code ec;
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir / "points", ec))
    n += e.path().extension() == ".json" ? 1 : 0;
  return n;
}

// study.csv without its measured columns (cost_*): what two runs of one study share.
std::string without_costs(const fs::path& csv) {
  std::istringstream in(read_file(csv));
  std::string line, out;
  std::vector<bool> keep;
  while (std::getline(in, line)) {
    const std::vector<std::string> v = split_csv_line(line);
    if (keep.empty())
      for (const auto& c : v) keep.push_back(c.rfind("cost", 0) != 0);
    EXPECT_EQ(v.size(), keep.size()) << line;
    for (std::size_t k = 0; k < v.size() && k < keep.size(); ++k)
      if (keep[k]) out += v[k] + ",";
    out += "\n";
  }
  return out;
}

// summary.md without the study's own wall time ("... in 3 s on 1 worker thread(s)" becomes
// "... in N s on ..."). By hand, not std::regex: GCC 12 warns falsely inside <regex> once this
// file is compiled in a batch with others under the sanitizers.
std::string without_wall_time(const fs::path& md) {
  const std::string text = read_file(md);
  std::string out;
  std::size_t from = 0;  // text[from, at) is copied as it is
  for (std::size_t at = text.find(" in "); at != std::string::npos;
       at = text.find(" in ", at + 1)) {
    std::size_t end = at + 4;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    if (end > at + 4 && text.compare(end, 6, " s on ") == 0) {
      out.append(text, from, at + 4 - from);
      out.push_back('N');
      from = end;
    }
  }
  out.append(text, from, std::string::npos);
  return out;
}

std::vector<std::string> charts(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".png") out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// The uninterrupted study into REF; DIR stopped by SIG once 3 points are stored, then resumed:
// the two end the same. Returns what the stopped command did: its exit status and its stderr.
CommandResult stop_resume_and_compare(int sig, const std::string& tag) {
  const fs::path ref = temp_dir(tag + "-ref"), dir = temp_dir(tag);
  const CommandResult r = run_fluidbed(energy_study("--out", ref), tag + "-ref");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(stored_count(ref), kPoints);

  const TerminatedRun t = fluidbed_terminated(energy_study("--out", dir), dir,
                                              [&] { return stored_count(dir) >= 3; }, sig);
  EXPECT_TRUE(t.terminated) << "the study finished before three of its points were stored";
  const CommandResult stopped = {t.status, read_file(dir / "err.txt"), read_file(dir / "out.txt")};
  for (const char* f : {"summary.md", "status.json", "study.csv"})
    EXPECT_FALSE(fs::exists(dir / f)) << f << ": an unfinished study has none";
  const std::map<std::string, std::string> kept = stored_points(dir);
  EXPECT_GE(kept.size(), 3u);
  EXPECT_LT(kept.size(), kPoints);

  const CommandResult resumed = run_fluidbed(energy_study("--resume", dir), tag + "-resume");
  EXPECT_EQ(resumed.status, 0) << resumed.err;
  const std::map<std::string, std::string> all = stored_points(dir);
  EXPECT_EQ(all.size(), kPoints);
  for (const auto& [name, text] : kept)  // read back, not measured again (its cost would differ)
    EXPECT_TRUE(all.count(name) && all.at(name) == text) << name << " was measured again";

  EXPECT_EQ(without_costs(ref / "study.csv"), without_costs(dir / "study.csv"));
  EXPECT_EQ(charts(ref), charts(dir));
  for (const auto& c : charts(ref)) EXPECT_EQ(read_file(ref / c), read_file(dir / c)) << c;
  EXPECT_EQ(without_wall_time(ref / "summary.md"), without_wall_time(dir / "summary.md"));

  // Every point stored: a resume measures none again, and the table is the same to the byte,
  // costs included.
  const std::string csv = read_file(dir / "study.csv");
  const CommandResult again = run_fluidbed(energy_study("--resume", dir), tag + "-again");
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(read_file(dir / "study.csv"), csv);
  EXPECT_TRUE(stored_points(dir) == all) << "a resume with every point stored measured one again";
  return stopped;
}

}  // namespace

TEST(StudyResume, SigtermThenResumeEndsWithTheUninterruptedStudy) {
  const CommandResult r = stop_resume_and_compare(SIGTERM, "study-resume-term");
  EXPECT_EQ(r.status, 130);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("interrupted (SIGTERM); resume with: fluidbed study energy --size tiny "
                       "--resume "),
            std::string::npos)
      << r.err;
}

TEST(StudyResume, KilledThenResumeEndsWithTheUninterruptedStudy) {
  EXPECT_EQ(stop_resume_and_compare(SIGKILL, "study-resume-kill").status, -1);
}

TEST(StudyResume, AnotherStudyOrSizeRefusesInOneLine) {
  const fs::path dir = temp_dir("study-resume-refuse"), empty = temp_dir("study-resume-empty");
  const CommandResult r =
      run_fluidbed("study failures --size tiny --out \"" + dir.string() + "\"", "study-refuse");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string summary = read_file(dir / "summary.md");
  const std::string d = " --resume \"" + dir.string() + "\"";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"study failures" + d, "--size tiny, not --size full"},
      {"study energy --size tiny" + d, "holds study failures, not energy"},
      {"study failures --size tiny --resume \"" + empty.string() + "\"", "no study.json"},
      {"study failures --size tiny" + d + " --out \"" + empty.string() + "\"",
       "is not the study's folder"}};
  for (const auto& [args, says] : bad) {
    const CommandResult b = run_fluidbed(args, "study-refuse-bad");
    EXPECT_EQ(b.status, 2) << args;
    EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << b.err;
    EXPECT_NE(b.err.find(says), std::string::npos) << b.err;
  }
  EXPECT_EQ(read_file(dir / "summary.md"), summary);  // a refused resume touches nothing
}
