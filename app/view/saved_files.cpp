// The viewer's files: the live curve saved, the numbered names of what the panel saves, a file
// written and said in the panel (screenshots too, view/capture.hpp takes them), and the widgets'
// places for tests.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include "core/atomic_file.hpp"
#include "view/curve_chart.hpp"
#include "view/window.hpp"

namespace fluidbed::app {

// Where the widgets and bed panels are, in window pixels (for tests that drive the window with
// a pointer, $FLUIDBED_VIEW_WIDGETS): one line each, "name x0 y0 x1 y1 value"; rewritten when
// something changed.
void Viewer::write_widgets() {
  std::string text;
  char line[160];
  const ImGuiIO& io = ImGui::GetIO();
  std::snprintf(line, sizeof line, "window 0 0 %.0f %.0f %d\n", io.DisplaySize.x, io.DisplaySize.y,
                static_cast<int>(panel_.font));
  text += line;
  for (std::size_t k = 0; k < layout_.beds.size(); ++k) {
    const render::Rect& c = layout_.beds[k].clip;
    std::snprintf(line, sizeof line, "bed%zu %.1f %.1f %.1f %.1f %s\n", k, to_window_x(c.x0),
                  to_window_y(c.y0), to_window_x(c.x1), to_window_y(c.y1),
                  layout_.beds[k].zoomed ? "zoomed" : "whole");
    text += line;
  }
  if (beside_) {
    std::snprintf(line, sizeof line, "beside_bed %.1f %.1f %.1f %.1f %s\n", beside_area_.x0,
                  beside_area_.y0, beside_area_.x1, beside_area_.y1,
                  beside_snap_ ? "drawn" : "waiting");
    text += line;
  }
  for (const std::string& w : widget_lines_) text += w + "\n";
  if (text == widgets_written_) return;
  widgets_written_ = text;
  try {
    write_file_atomically(widgets_file_, [&](std::ofstream& out) { out << text; });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fluidbed view: %s\n", e.what());
    widgets_file_.clear();
  }
}

// What the panel says: a class sees a file's name, not the machine's folders (the terminal
// keeps the whole path).
void Viewer::say(const std::string& text) {
  std::string out;
  std::size_t k = 0;
  while (k < text.size()) {
    const std::size_t end = std::min(text.find(' ', k), text.size());
    const std::string word = text.substr(k, end - k);
    if (word.size() > 1 && word[0] == '/') {
      const std::filesystem::path p(word);
      out += (p.has_filename() ? p.filename() : p.parent_path().filename()).string();
    } else {
      out += word;
    }
    if (end < text.size()) out += ' ';
    k = end + 1;
  }
  message_ = out;
}

std::string Viewer::next_name(const std::string& stem, const std::string& ext) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(opt_.out_dir, ec);
  for (;;) {
    char name[64];
    std::snprintf(name, sizeof name, "%s_%03d%s", stem.c_str(), ++counter_, ext.c_str());
    const fs::path p = fs::path(opt_.out_dir) / name;
    if (!fs::exists(p, ec)) return p.string();
  }
}

void Viewer::save_curve_file(const std::string& path) {
  write_output(path, [&] { write_curve_file(path, status_.curve, opt_.font); });
}

// A file the viewer writes (its folder made first), said in the panel and on the terminal; a
// script stops at a failure to write (exit status 4).
void Viewer::write_output(const std::string& path, const std::function<void()>& write) {
  try {
    const auto parent = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    write();
    say("wrote " + path);
    std::printf("wrote %s\n", path.c_str());
  } catch (const std::exception& e) {
    say(e.what());
    if (!opt_.script.empty()) {
      std::fprintf(stderr, "fluidbed: output failed: %s\n", e.what());
      exit_status_ = 4;
      quit_ = true;
    }
  }
}

}  // namespace fluidbed::app
