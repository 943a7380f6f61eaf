#pragma once
// Sizes of the viewer's window parts, by the window's size (no ImGui, so tests can check them):
// the panel's text grows with the window's height (legible on a projector), the panel's width
// with its text, and the bed area keeps the rest. Laid out for 1024 x 600 and up.
#include <utility>
#include <vector>

namespace fluidbed::app {

// The fonts' sizes (px); the window loads each once. The panel uses up to 24 px, the presenter
// mode all of them.
inline constexpr float kPanelFontSizes[] = {15.0f, 18.0f, 21.0f, 24.0f, 30.0f, 36.0f};
inline constexpr float kPanelFontMax = 24.0f;

struct PanelLayout {
  float font = 15.0f;    // px, one of kPanelFontSizes
  float width = 375.0f;  // px, the panel at the window's left
};

// The font: the largest size not above height / 36 (15 px at 600 px high, 18 at 720, 21 at
// 800, 24 from 900) nor width / 64 (a 16:9 window's; 21 px at 1400 x 900); the panel 25 font
// sizes wide, at most 45 % of the window.
PanelLayout panel_layout(int window_width, int window_height);

// The presenter mode (`view --present`, the `p` key): the bed on the left at the window's full
// height (a bed is tall), and on the right, in text read from the back of a room, the controls
// a demo needs, what the bed is doing in words and a large live Fig. 6.
struct PresenterLayout {
  float font = 24.0f;      // px: the largest size not above height / 28 (24 at 720, 36 at 1080)
  float bed_right = 0.0f;  // px: the bed from x = 0 to here (30 % of the width)
};
PresenterLayout presenter_layout(int window_width, int window_height);

// A plot's value range robust to a start-up spike: the q-th and (1 - q)-th quantiles of the
// values, widened by `margin` of their span on either side (an empty span: +-1 % around it).
// Values outside are drawn at the edge.
std::pair<double, double> robust_range(std::vector<float> values, double q = 0.02,
                                       double margin = 0.1);

}  // namespace fluidbed::app
