// Pixels: the image, its PNG file, and anti-aliased coverage of lines, rectangles and markers.
#include "chart/raster.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "render/image.hpp"

namespace fluidbed::chart {

namespace {
constexpr int kMaxSide = 1 << 15;      // px
constexpr long kMaxPixels = 1L << 27;  // 134 M pixels, 400 MB of RGB
}  // namespace

Image::Image(int width, int height, Rgb background) : width_(width), height_(height) {
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide ||
      static_cast<long>(width) * height > kMaxPixels) {
    throw std::invalid_argument("image size " + std::to_string(width) + " x " +
                                std::to_string(height) + " px is not between 1 x 1 and " +
                                std::to_string(kMaxSide) + " x " + std::to_string(kMaxSide));
  }
  pixels_.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  for (std::size_t i = 0; i < pixels_.size(); i += 3) {
    pixels_[i] = background.r;
    pixels_[i + 1] = background.g;
    pixels_[i + 2] = background.b;
  }
}

Rgb Image::at(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) {
    throw std::out_of_range("pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") is outside the " + std::to_string(width_) + " x " +
                            std::to_string(height_) + " image");
  }
  const std::size_t i = (static_cast<std::size_t>(y) * width_ + x) * 3;
  return {pixels_[i], pixels_[i + 1], pixels_[i + 2]};
}

void Image::set(int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  const std::size_t i = (static_cast<std::size_t>(y) * width_ + x) * 3;
  pixels_[i] = c.r;
  pixels_[i + 1] = c.g;
  pixels_[i + 2] = c.b;
}

void Image::blend(int x, int y, Rgb c, float alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_ || !(alpha > 0.0F)) return;
  alpha = std::min(alpha, 1.0F);
  const std::size_t i = (static_cast<std::size_t>(y) * width_ + x) * 3;
  // Both ends lie in [0, 255], so +0.5 and truncation round to nearest.
  const auto mix = [alpha](std::uint8_t old, std::uint8_t now) {
    const float v = static_cast<float>(old) + (static_cast<float>(now) - old) * alpha;
    return static_cast<std::uint8_t>(v + 0.5F);
  };
  pixels_[i] = mix(pixels_[i], c.r);
  pixels_[i + 1] = mix(pixels_[i + 1], c.g);
  pixels_[i + 2] = mix(pixels_[i + 2], c.b);
}

void Image::paste(const Image& src, int x, int y) {
  const int x0 = std::max(0, x), x1 = std::min(width_, x + src.width_);
  if (x1 <= x0) return;
  for (int j = std::max(0, y); j < std::min(height_, y + src.height_); ++j) {
    const auto from =
        src.pixels_.begin() + static_cast<std::ptrdiff_t>(((j - y) * src.width_ + (x0 - x)) * 3);
    std::copy(from, from + (x1 - x0) * 3,
              pixels_.begin() + static_cast<std::ptrdiff_t>((j * width_ + x0) * 3));
  }
}

// The program's one PNG writer (render/image.hpp), as for the frames.
std::vector<std::uint8_t> Image::encode_png() const {
  return render::encode_png(width_, height_, pixels_.data());
}

void Image::write_png(const std::string& path) const {
  render::write_png(path, width_, height_, pixels_.data());
}

}  // namespace fluidbed::chart

namespace fluidbed::chart::detail {

namespace {

// Liang-Barsky: trims A-B to the box; false when nothing of it is inside.
bool clip_segment(Point& a, Point& b, double x0, double y0, double x1, double y1) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x - x0, x1 - a.x, a.y - y0, y1 - a.y};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return false;
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
    if (t0 > t1) return false;
  }
  const Point a0 = a;
  a = {a0.x + t0 * dx, a0.y + t0 * dy};
  b = {a0.x + t1 * dx, a0.y + t1 * dy};
  return true;
}

float coverage_of(double signed_distance) {
  return static_cast<float>(std::clamp(0.5 - signed_distance, 0.0, 1.0));
}

}  // namespace

Coverage::Coverage(int width, int height)
    : width_(width),
      height_(height),
      a_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0F),
      clip_x0_(0),
      clip_y0_(0),
      clip_x1_(width),
      clip_y1_(height),
      dirty_x0_(width),
      dirty_y0_(height),
      dirty_x1_(0),
      dirty_y1_(0) {}

void Coverage::set_clip(const Box& clip) {
  const auto to_int = [](double v, int lo, int hi) {
    return static_cast<int>(std::clamp(v, static_cast<double>(lo), static_cast<double>(hi)));
  };
  clip_x0_ = to_int(std::floor(clip.x0), 0, width_);
  clip_y0_ = to_int(std::floor(clip.y0), 0, height_);
  clip_x1_ = to_int(std::ceil(clip.x1), 0, width_);
  clip_y1_ = to_int(std::ceil(clip.y1), 0, height_);
}

void Coverage::reset_clip() {
  clip_x0_ = 0;
  clip_y0_ = 0;
  clip_x1_ = width_;
  clip_y1_ = height_;
}

void Coverage::put(int x, int y, float a) {
  float& cell = a_[static_cast<std::size_t>(y) * width_ + x];
  if (a > cell) cell = a;
  dirty_x0_ = std::min(dirty_x0_, x);
  dirty_y0_ = std::min(dirty_y0_, y);
  dirty_x1_ = std::max(dirty_x1_, x + 1);
  dirty_y1_ = std::max(dirty_y1_, y + 1);
}

void Coverage::segment(Point a, Point b, double width) {
  if (!(width > 0.0) || !std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) ||
      !std::isfinite(b.y)) {
    return;
  }
  // A line thinner than a pixel keeps a pixel's footprint and fades instead.
  const double half = 0.5 * std::max(width, 1.0);
  const float fade = static_cast<float>(std::min(width, 1.0));
  const double reach = half + 0.5;
  if (!clip_segment(a, b, clip_x0_ - reach, clip_y0_ - reach, clip_x1_ + reach, clip_y1_ + reach)) {
    return;
  }
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  const int j0 = std::max(clip_y0_, static_cast<int>(std::floor(std::min(a.y, b.y) - reach)));
  const int j1 = std::min(clip_y1_ - 1, static_cast<int>(std::floor(std::max(a.y, b.y) + reach)));
  for (int j = j0; j <= j1; ++j) {
    const double yc = j + 0.5;
    // The pixels of this row within REACH of the segment: those near its part whose y is.
    double xa, xb;
    if (std::abs(dy) < 1e-12) {
      xa = std::min(a.x, b.x) - reach;
      xb = std::max(a.x, b.x) + reach;
    } else {
      double t0 = (yc - reach - a.y) / dy, t1 = (yc + reach - a.y) / dy;
      if (t0 > t1) std::swap(t0, t1);
      t0 = std::max(t0, 0.0);
      t1 = std::min(t1, 1.0);
      if (t0 > t1) continue;
      xa = std::min(a.x + t0 * dx, a.x + t1 * dx) - reach;
      xb = std::max(a.x + t0 * dx, a.x + t1 * dx) + reach;
    }
    const int i0 = std::max(clip_x0_, static_cast<int>(std::floor(xa)));
    const int i1 = std::min(clip_x1_ - 1, static_cast<int>(std::floor(xb)));
    for (int i = i0; i <= i1; ++i) {
      const double xc = i + 0.5;
      const double t =
          len2 > 0.0 ? std::clamp(((xc - a.x) * dx + (yc - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
      const double ex = a.x + t * dx - xc, ey = a.y + t * dy - yc;
      const float c = coverage_of(std::sqrt(ex * ex + ey * ey) - half) * fade;
      if (c > 0.0F) put(i, j, c);
    }
  }
}

void Coverage::polyline(const std::vector<Point>& points, double width, double dash, double gap) {
  if (points.size() == 1) {
    segment(points[0], points[0], width);
    return;
  }
  const bool dashed = dash > 0.0 && gap > 0.0;
  bool on = true;
  double left = dash;  // px left of the current dash or gap
  for (std::size_t k = 1; k < points.size(); ++k) {
    const Point a = points[k - 1], b = points[k];
    if (!dashed) {
      segment(a, b, width);
      continue;
    }
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    if (!std::isfinite(length)) continue;
    double done = 0.0;
    while (done < length) {
      const double step = std::min(left, length - done);
      if (on) {
        const double s0 = done / length, s1 = (done + step) / length;
        segment({a.x + s0 * (b.x - a.x), a.y + s0 * (b.y - a.y)},
                {a.x + s1 * (b.x - a.x), a.y + s1 * (b.y - a.y)}, width);
      }
      done += step;
      left -= step;
      if (left <= 0.0) {
        on = !on;
        left = on ? dash : gap;
      }
    }
  }
}

template <class SignedDistance>
void Coverage::fill(double x0, double y0, double x1, double y1, SignedDistance sd) {
  if (!(x1 >= clip_x0_ && x0 < clip_x1_ && y1 >= clip_y0_ && y0 < clip_y1_)) return;
  const int i0 = std::max(clip_x0_, static_cast<int>(std::floor(x0)));
  const int i1 = std::min(clip_x1_ - 1, static_cast<int>(std::floor(x1)));
  const int j0 = std::max(clip_y0_, static_cast<int>(std::floor(y0)));
  const int j1 = std::min(clip_y1_ - 1, static_cast<int>(std::floor(y1)));
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const float c = sd(i + 0.5, j + 0.5);
      if (c > 0.0F) put(i, j, c);
    }
  }
}

void Coverage::rect(const Box& box) {
  if (!(box.x1 > box.x0 && box.y1 > box.y0)) return;
  fill(box.x0, box.y0, box.x1, box.y1, [&box](double xc, double yc) {
    // The part of the pixel inside the box, separable in x and y.
    const double cx = std::clamp(std::min(xc + 0.5, box.x1) - std::max(xc - 0.5, box.x0), 0.0, 1.0);
    const double cy = std::clamp(std::min(yc + 0.5, box.y1) - std::max(yc - 0.5, box.y0), 0.0, 1.0);
    return static_cast<float>(cx * cy);
  });
}

void Coverage::marker(Point c, double size, Shape shape, double ring) {
  if (!(size > 0.0) || !std::isfinite(c.x) || !std::isfinite(c.y)) return;
  const double r = 0.5 * size;
  // Signed distance (px, negative inside) to each outline; the sizes make the shapes' areas
  // look alike next to the circle.
  const auto distance = [shape, r, c](double x, double y) {
    const double dx = x - c.x, dy = y - c.y;
    switch (shape) {
      case Shape::Square:
        return std::max(std::abs(dx), std::abs(dy)) - 0.88 * r;
      case Shape::Diamond:
        return (std::abs(dx) + std::abs(dy) - 1.2 * r) / std::sqrt(2.0);
      case Shape::Triangle: {
        // Pointing up (y grows down); circumradius 1.3 r, inradius half that.
        const double in = 0.65 * r, s = std::sqrt(3.0) / 2.0;
        const double yy = dy - 0.2 * r;  // centred by eye rather than by centroid
        return std::max({yy - in, s * dx - 0.5 * yy - in, -s * dx - 0.5 * yy - in});
      }
      case Shape::Circle:
        break;
    }
    return std::sqrt(dx * dx + dy * dy) - r;
  };
  // Half the box around each shape (the triangle's corners reach 1.13 r across, 1.1 r up).
  const double reach = (shape == Shape::Circle   ? r
                        : shape == Shape::Square ? 0.88 * r
                                                 : 1.2 * r) +
                       1.0;
  fill(c.x - reach, c.y - reach, c.x + reach, c.y + reach, [&](double x, double y) {
    const double d = distance(x, y);
    float a = coverage_of(d);
    if (ring > 0.0) a -= coverage_of(d + ring);
    return a;
  });
}

void Coverage::composite(Image& image, Rgb colour, float opacity) {
  for (int j = dirty_y0_; j < dirty_y1_; ++j) {
    float* row = &a_[static_cast<std::size_t>(j) * width_];
    for (int i = dirty_x0_; i < dirty_x1_; ++i) {
      if (row[i] > 0.0F) {
        image.blend(i, j, colour, row[i] * opacity);
        row[i] = 0.0F;
      }
    }
  }
  dirty_x0_ = width_;
  dirty_y0_ = height_;
  dirty_x1_ = 0;
  dirty_y1_ = 0;
}

}  // namespace fluidbed::chart::detail
