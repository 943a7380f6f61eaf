#include "view/script.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "core/input_file.hpp"

namespace fluidbed::app {
namespace {

using Kind = ScriptLine::Kind;

struct Reader {
  std::vector<std::string> words;
  std::size_t next = 0;
  std::string where;  // "FILE line N"

  [[noreturn]] void fail(const std::string& what) const { throw InputError(where + ": " + what); }
  bool done() const { return next >= words.size(); }
  std::string word(const std::string& what) {
    if (done()) fail("expected " + what);
    return words[next++];
  }
  double number(const std::string& what) {
    const std::string w = word(what);
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(w, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != w.size() || !std::isfinite(v))
      fail("expected " + what + ", got '" + w + "'");
    return v;
  }
  double on_off(const std::string& command) {
    const std::string w = word("on or off after " + command);
    if (w == "on") return 1.0;
    if (w == "off") return 0.0;
    fail(command + " takes on or off, not '" + w + "'");
  }
};

const char* kCommands =
    "velocity, ideal, run, pause, step, reset, wait, colour, gas-arrows, particle-arrows, "
    "porosity, bubbles, track, zoom, screenshot, record, quit";

ScriptLine parse_line(Reader& r, int line_number) {
  ScriptLine l;
  l.line = line_number;
  std::string cmd = r.word("a command");
  if (cmd == "at") {
    l.at = r.number("a simulated time in seconds after 'at'");
    if (l.at < 0.0) r.fail("'at' needs a time >= 0 s");
    cmd = r.word("a command after 'at T'");
  }
  // The switches: a command name and on|off.
  static constexpr std::pair<const char*, Kind> switches[] = {
      {"ideal", Kind::ideal},
      {"gas-arrows", Kind::gas_arrows},
      {"particle-arrows", Kind::particle_arrows},
      {"porosity", Kind::porosity},
      {"bubbles", Kind::bubbles},
  };
  const auto* sw = std::find_if(std::begin(switches), std::end(switches),
                                [&](const auto& e) { return cmd == e.first; });
  if (sw != std::end(switches)) {
    l.kind = sw->second;
    l.number = r.on_off(cmd);
  } else if (cmd == "velocity") {
    l.kind = Kind::velocity;
    l.number = r.number("a superficial velocity in m/s");
    if (l.number < 0.0) r.fail("velocity must be >= 0 m/s");
  } else if (cmd == "run") {
    l.kind = Kind::run;
  } else if (cmd == "pause") {
    l.kind = Kind::pause;
  } else if (cmd == "step") {
    l.kind = Kind::step;
    l.number = r.done() ? 1.0 : r.number("a step count");
    if (l.number < 1.0 || l.number != std::floor(l.number)) r.fail("step takes a whole count >= 1");
  } else if (cmd == "reset") {
    l.kind = Kind::reset;
  } else if (cmd == "wait") {
    l.kind = Kind::wait;
    l.number = r.number("wall seconds");
    if (l.number < 0.0) r.fail("wait needs seconds >= 0");
  } else if (cmd == "colour" || cmd == "color") {
    l.kind = Kind::colour;
    l.text = r.word("a colour mode (speed, force, torque, overlap, mixing)");
    if (l.text != "speed" && l.text != "force" && l.text != "torque" && l.text != "overlap" &&
        l.text != "mixing")
      r.fail("unknown colour mode '" + l.text + "' (known: speed, force, torque, overlap, mixing)");
  } else if (cmd == "track") {
    l.kind = Kind::track;
    const std::string w = r.word("a particle id or off");
    if (w == "off") {
      l.number = -1.0;
    } else {
      --r.next;
      l.number = r.number("a particle id or off");
      if (l.number < 0.0 || l.number != std::floor(l.number))
        r.fail("track takes a particle id >= 0");
    }
  } else if (cmd == "zoom") {
    l.kind = Kind::zoom;
    l.number = r.number("a zoom factor");
    if (l.number < 1.0 || l.number > 16.0) r.fail("zoom takes a factor from 1 to 16");
  } else if (cmd == "screenshot") {
    l.kind = Kind::screenshot;
    l.text = r.word("a file name");
  } else if (cmd == "record") {
    const std::string w = r.word("a file (.mp4), a folder, or stop");
    l.kind = w == "stop" ? Kind::record_stop : Kind::record;
    if (l.kind == Kind::record) l.text = w;
  } else if (cmd == "quit") {
    l.kind = Kind::quit;
  } else {
    r.fail("unknown command '" + cmd + "' (known: " + kCommands + ")");
  }
  if (!r.done()) r.fail("unexpected '" + r.words[r.next] + "' after " + cmd);
  return l;
}

}  // namespace

std::vector<ScriptLine> parse_view_script(const std::string& text, const std::string& origin) {
  std::vector<ScriptLine> lines;
  std::istringstream in(text);
  std::string raw;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    if (const auto hash = raw.find('#'); hash != std::string::npos) raw.erase(hash);
    Reader r;
    r.where = origin + " line " + std::to_string(number);
    std::istringstream words(raw);
    for (std::string w; words >> w;) r.words.push_back(w);
    if (r.words.empty()) continue;
    lines.push_back(parse_line(r, number));
  }
  return lines;
}

std::vector<ScriptLine> load_view_script(const std::string& path) {
  std::ifstream in = open_input_file(path, "script", std::ios::in);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError("cannot read the script " + path);
  return parse_view_script(text.str(), path);
}

}  // namespace fluidbed::app
