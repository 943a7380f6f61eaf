#include "view/script.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <utility>

#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "render/colour_by.hpp"
#include "view/presets.hpp"

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
    "velocity, preset, ideal, stiffness, run, pause, step, reset, wait, colour, gas-arrows, "
    "particle-arrows, porosity, bubbles, track, zoom, screenshot, record, settle, average, curve, "
    "caption, quit";

// A line's words: split at white space, a double-quoted part ("a caption, with spaces") one word
// without its quotes; `#` outside quotes starts a comment. False for an unclosed quote.
bool split_words(const std::string& raw, std::vector<std::string>& words) {
  std::string w;
  bool in_word = false, quoted = false;
  for (char c : raw) {
    if (quoted) {
      if (c == '"') {
        quoted = false;
      } else {
        w += c;
      }
      continue;
    }
    if (c == '#') break;
    if (c == '"') {
      quoted = in_word = true;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      if (in_word) words.push_back(w);
      w.clear();
      in_word = false;
    } else {
      w += c;
      in_word = true;
    }
  }
  if (in_word) words.push_back(w);
  return !quoted;
}

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
    if (!r.done()) {
      l.text = r.word("umf");
      if (l.text != "umf") r.fail("velocity takes m/s, or a multiple of U_mf: 'velocity 1.2 umf'");
    }
  } else if (cmd == "preset") {
    l.kind = Kind::preset;
    l.text = r.word(std::string("a preset (") + preset_names() + ")");
    if (!find_preset(l.text))
      r.fail("unknown preset '" + l.text + "' (known: " + preset_names() + ")");
  } else if (cmd == "stiffness") {
    l.kind = Kind::stiffness;
    const std::string w = r.word("a contact stiffness in N/m, or scene");
    if (w == "scene") {
      l.number = 0.0;
    } else {
      --r.next;
      l.number = r.number("a contact stiffness in N/m, or scene");
      if (!(l.number > 0.0)) r.fail("stiffness must be > 0 N/m");
    }
  } else if (cmd == "particles") {
    l.kind = Kind::particles;
    const std::string w = r.word("a diameter in m and a density in kg/m^3, or scene");
    if (w != "scene") {
      --r.next;
      l.number = r.number("a particle diameter in m");
      if (!(l.number > 0.0)) r.fail("the particle diameter must be > 0 m");
      l.density = r.number("a particle density in kg/m^3 after the diameter");
      if (!(l.density > 0.0)) r.fail("the particle density must be > 0 kg/m^3");
    }
  } else if (cmd == "settle" || cmd == "average") {
    l.kind = cmd == "settle" ? Kind::settle : Kind::average;
    l.number = r.number("simulated seconds");
    if (cmd == "settle" ? l.number < 0.0 : !(l.number > 0.0))
      r.fail(cmd + (cmd == "settle" ? " needs seconds >= 0" : " needs seconds > 0"));
  } else if (cmd == "curve") {
    l.kind = Kind::curve;
    l.text = r.word("a file name (.csv or .png)");
    const std::string ext = std::filesystem::path(l.text).extension().string();
    if (ext != ".csv" && ext != ".png")
      r.fail("curve saves FILE.csv or FILE.png, not '" + l.text + "'");
  } else if (cmd == "caption") {
    l.kind = Kind::caption;
    l.text = r.word("a caption in double quotes, or off");
    if (l.text == "off") l.text.clear();
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
    l.text = r.word("a colour mode (" +
                    render::joined_colour_names(render::viewer_colour_names()) + ")");
    try {
      (void)render::parse_viewer_colour(l.text);
    } catch (const InputError& e) {
      r.fail(e.what());
    }
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

bool ViewScript::needs_umf() const {
  return std::any_of(lines.begin(), lines.end(), [](const ScriptLine& l) {
    return l.kind == Kind::preset || (l.kind == Kind::velocity && l.text == "umf");
  });
}

ViewScript parse_view_script(const std::string& text, const std::string& origin) {
  ViewScript script;
  std::istringstream in(text);
  std::string raw;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    Reader r;
    r.where = origin + " line " + std::to_string(number);
    if (!split_words(raw, r.words)) r.fail("a double quote is not closed");
    if (r.words.empty()) continue;
    if (r.words.front() == "scene") {  // a lesson's scene: before every command
      if (!script.lines.empty() || !script.scene.empty())
        r.fail("'scene' must come before every other command");
      if (r.words.size() != 2) r.fail("scene takes one scene file name");
      script.scene = r.words[1];
      continue;
    }
    script.lines.push_back(parse_line(r, number));
  }
  return script;
}

ViewScript load_view_script(const std::string& path) {
  std::ifstream in = open_input_file(path, "script", std::ios::in);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError("cannot read the script " + path);
  return parse_view_script(text.str(), path);
}

}  // namespace fluidbed::app
