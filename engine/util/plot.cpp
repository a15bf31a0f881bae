#include "engine/util/plot.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#define STB_IMAGE_WRITE_STATIC  // our own private copy of the writer: no clash with other users of stb
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include "engine/util/files.h"

namespace prep {
namespace {

// A 5x7 bitmap font of our own: 7 rows per glyph, 5 bits per row, the high bit the leftmost pixel.
struct Glyph {
  char c;
  std::uint8_t rows[7];
};
constexpr Glyph kFont[] = {
    {'0', {14, 17, 19, 21, 25, 17, 14}}, {'1', {4, 12, 4, 4, 4, 4, 14}},     {'2', {14, 17, 1, 2, 4, 8, 31}},
    {'3', {30, 1, 1, 14, 1, 1, 30}},     {'4', {2, 6, 10, 18, 31, 2, 2}},    {'5', {31, 16, 30, 1, 1, 17, 14}},
    {'6', {6, 8, 16, 30, 17, 17, 14}},   {'7', {31, 1, 2, 4, 8, 8, 8}},      {'8', {14, 17, 17, 14, 17, 17, 14}},
    {'9', {14, 17, 17, 15, 1, 2, 12}},   {'A', {14, 17, 17, 31, 17, 17, 17}}, {'B', {30, 17, 17, 30, 17, 17, 30}},
    {'C', {14, 17, 16, 16, 16, 17, 14}}, {'D', {30, 17, 17, 17, 17, 17, 30}}, {'E', {31, 16, 16, 30, 16, 16, 31}},
    {'F', {31, 16, 16, 30, 16, 16, 16}}, {'G', {14, 17, 16, 23, 17, 17, 15}}, {'H', {17, 17, 17, 31, 17, 17, 17}},
    {'I', {14, 4, 4, 4, 4, 4, 14}},      {'J', {7, 2, 2, 2, 2, 18, 12}},     {'K', {17, 18, 20, 24, 20, 18, 17}},
    {'L', {16, 16, 16, 16, 16, 16, 31}}, {'M', {17, 27, 21, 21, 17, 17, 17}}, {'N', {17, 25, 21, 19, 17, 17, 17}},
    {'O', {14, 17, 17, 17, 17, 17, 14}}, {'P', {30, 17, 17, 30, 16, 16, 16}}, {'Q', {14, 17, 17, 17, 21, 18, 13}},
    {'R', {30, 17, 17, 30, 20, 18, 17}}, {'S', {15, 16, 16, 14, 1, 1, 30}},   {'T', {31, 4, 4, 4, 4, 4, 4}},
    {'U', {17, 17, 17, 17, 17, 17, 14}}, {'V', {17, 17, 17, 17, 17, 10, 4}},  {'W', {17, 17, 17, 21, 21, 21, 10}},
    {'X', {17, 17, 10, 4, 10, 17, 17}},  {'Y', {17, 17, 10, 4, 4, 4, 4}},     {'Z', {31, 1, 2, 4, 8, 16, 31}},
    {'.', {0, 0, 0, 0, 0, 12, 12}},      {',', {0, 0, 0, 0, 12, 4, 8}},       {'-', {0, 0, 0, 31, 0, 0, 0}},
    {'+', {0, 4, 4, 31, 4, 4, 0}},       {':', {0, 12, 12, 0, 12, 12, 0}},    {'(', {2, 4, 8, 8, 8, 4, 2}},
    {')', {8, 4, 2, 2, 2, 4, 8}},        {'/', {1, 1, 2, 4, 8, 16, 16}},      {'%', {24, 25, 2, 4, 8, 19, 3}},
    {'=', {0, 0, 31, 0, 31, 0, 0}},      {'_', {0, 0, 0, 0, 0, 0, 31}},       {'x', {0, 17, 10, 4, 10, 17, 0}},
};

const Glyph* glyph(char c) {
  if (c != 'x') c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& g : kFont)
    if (g.c == c) return &g;
  return nullptr;  // a space, or a character the font lacks: left blank
}

struct Canvas {
  int w, h;
  std::vector<std::uint8_t> px;
  Canvas(int w_, int h_) : w(w_), h(h_), px(static_cast<size_t>(w_) * static_cast<size_t>(h_) * 3, 255) {}
  void set(int x, int y, std::uint32_t rgb) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    std::uint8_t* p = &px[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 3];
    p[0] = static_cast<std::uint8_t>(rgb >> 16);
    p[1] = static_cast<std::uint8_t>(rgb >> 8);
    p[2] = static_cast<std::uint8_t>(rgb);
  }
  void line(double x0, double y0, double x1, double y1, std::uint32_t rgb, int thickness = 1) {
    const int n = static_cast<int>(std::ceil(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0)))) + 1;
    for (int i = 0; i <= n; ++i) {
      const double t = static_cast<double>(i) / n;
      const int x = static_cast<int>(std::lround(x0 + (x1 - x0) * t)), y = static_cast<int>(std::lround(y0 + (y1 - y0) * t));
      for (int dy = 0; dy < thickness; ++dy)
        for (int dx = 0; dx < thickness; ++dx) set(x + dx - thickness / 2, y + dy - thickness / 2, rgb);
    }
  }
  // Text with its top-left corner at (x, y); vertical text runs bottom to top.
  void text(int x, int y, const std::string& s, std::uint32_t rgb, int scale = 1, bool vertical = false) {
    for (size_t i = 0; i < s.size(); ++i) {
      const Glyph* g = glyph(s[i]);
      if (g == nullptr) continue;
      for (int r = 0; r < 7; ++r)
        for (int c = 0; c < 5; ++c) {
          if (!(g->rows[r] >> (4 - c) & 1)) continue;
          for (int sy = 0; sy < scale; ++sy)
            for (int sx = 0; sx < scale; ++sx) {
              const int u = static_cast<int>(i) * 6 * scale + c * scale + sx, v = r * scale + sy;
              if (vertical)
                set(x + v, y - u, rgb);
              else
                set(x + u, y + v, rgb);
            }
        }
    }
  }
};

std::string format_tick(double v, double step) {
  char buf[32];
  const double a = std::fabs(v);
  if (a != 0.0 && (a >= 1e5 || a < 1e-3)) {
    std::snprintf(buf, sizeof buf, "%.3g", v);
  } else {
    const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    std::snprintf(buf, sizeof buf, "%.*f", std::max(0, decimals), v);
  }
  return buf;
}

}  // namespace

int text_width(const std::string& text) { return static_cast<int>(text.size()) * 6; }

std::vector<double> nice_ticks(double lo, double hi, int count) {
  std::vector<double> ticks;
  if (!(hi > lo) || count < 1) return {lo};
  const double raw = (hi - lo) / count, mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double frac = raw / mag;
  const double step = (frac <= 1.0 ? 1.0 : frac <= 2.0 ? 2.0 : frac <= 5.0 ? 5.0 : 10.0) * mag;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step)
    ticks.push_back(std::fabs(t) < step * 1e-9 ? 0.0 : t);
  return ticks;
}

std::vector<std::uint8_t> render_line_plot(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  if (o.width < 200 || o.height < 150) throw std::invalid_argument("plot: at least 200 x 150 pixels");
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  bool any = false;
  for (const PlotSeries& s : series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if (!any) {
        x0 = x1 = s.x[i];
        y0 = y1 = s.y[i];
        any = true;
      }
      x0 = std::min(x0, s.x[i]);
      x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, s.y[i]);
      y1 = std::max(y1, s.y[i]);
    }
  if (y0 > 0 && y0 < (y1 - y0)) y0 = 0;  // start the axis at 0 when that costs little room
  if (!(x1 > x0)) x1 = x0 + 1;
  if (!(y1 > y0)) y1 = y0 + 1;
  const double y_pad = 0.05 * (y1 - y0);
  y1 += y_pad;
  if (y0 != 0) y0 -= y_pad;
  if (std::isfinite(o.y_min) && std::isfinite(o.y_max) && o.y_max > o.y_min) {
    y0 = o.y_min;
    y1 = o.y_max;
  }

  Canvas c(o.width, o.height);
  const int left = 80, right = o.width - 25, top = 40, bottom = o.height - 55;
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (right - left); };
  auto py = [&](double y) { return bottom - (y - y0) / (y1 - y0) * (bottom - top); };
  const std::uint32_t ink = 0x202020, grid = 0xe4e4e4;

  const std::vector<double> xt = nice_ticks(x0, x1, 6), yt = nice_ticks(y0, y1, 6);
  const double xs = xt.size() > 1 ? xt[1] - xt[0] : 1.0, ys = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (double t : xt) {
    c.line(px(t), top, px(t), bottom, grid);
    c.line(px(t), bottom, px(t), bottom + 5, ink);
    const std::string s = format_tick(t, xs);
    c.text(static_cast<int>(px(t)) - text_width(s) / 2, bottom + 9, s, ink);
  }
  for (double t : yt) {
    c.line(left, py(t), right, py(t), grid);
    c.line(left - 5, py(t), left, py(t), ink);
    const std::string s = format_tick(t, ys);
    c.text(left - 9 - text_width(s), static_cast<int>(py(t)) - 3, s, ink);
  }
  c.line(left, top, left, bottom, ink);
  c.line(left, bottom, right, bottom, ink);

  // Data outside a fixed y range is clamped to the frame rather than drawn over the labels.
  auto pyc = [&](double y) { return std::clamp(py(y), static_cast<double>(top), static_cast<double>(bottom)); };
  for (const PlotSeries& s : series)
    for (size_t i = 1; i < s.x.size() && i < s.y.size(); ++i)
      if (std::isfinite(s.x[i - 1] + s.y[i - 1] + s.x[i] + s.y[i]))
        c.line(px(s.x[i - 1]), pyc(s.y[i - 1]), px(s.x[i]), pyc(s.y[i]), s.rgb, 2);
  // Marks: a dot on the series' line at each marked x (the line's y there, linearly interpolated).
  for (const PlotSeries& s : series)
    for (double m : s.marks) {
      const size_t n = std::min(s.x.size(), s.y.size());
      if (n == 0 || !std::isfinite(m)) continue;
      const size_t k = static_cast<size_t>(std::lower_bound(s.x.begin(), s.x.begin() + static_cast<std::ptrdiff_t>(n), m) - s.x.begin());
      double y = s.y[std::min(k, n - 1)];
      if (k > 0 && k < n && s.x[k] > s.x[k - 1]) y = s.y[k - 1] + (s.y[k] - s.y[k - 1]) * (m - s.x[k - 1]) / (s.x[k] - s.x[k - 1]);
      const double cx = px(m), cy = pyc(y);
      for (int dy = -4; dy <= 4; ++dy)
        for (int dx = -4; dx <= 4; ++dx)
          if (dx * dx + dy * dy <= 16) c.set(static_cast<int>(std::lround(cx)) + dx, static_cast<int>(std::lround(cy)) + dy, dx * dx + dy * dy >= 9 ? ink : s.rgb);
    }
  // Legend: one row per labelled series, a colour swatch and the label, in a framed box at the top right.
  int labelled = 0, widest = 0;
  for (const PlotSeries& s : series)
    if (!s.label.empty()) ++labelled, widest = std::max(widest, text_width(s.label));
  if (labelled > 0) {
    const int box_w = widest + 40, box_h = 14 * labelled + 8, bx = right - box_w - 8, by = top + 8;
    for (int y = by; y < by + box_h; ++y)
      for (int x = bx; x < bx + box_w; ++x) c.set(x, y, 0xffffff);
    c.line(bx, by, bx + box_w, by, ink);
    c.line(bx, by + box_h, bx + box_w, by + box_h, ink);
    c.line(bx, by, bx, by + box_h, ink);
    c.line(bx + box_w, by, bx + box_w, by + box_h, ink);
    int row = 0;
    for (const PlotSeries& s : series) {
      if (s.label.empty()) continue;
      const int y = by + 7 + 14 * row++;
      c.line(bx + 6, y + 3, bx + 26, y + 3, s.rgb, 3);
      c.text(bx + 32, y, s.label, ink);
    }
  }

  c.text((o.width - text_width(o.title) * 2) / 2, 10, o.title, ink, 2);
  c.text((left + right - text_width(o.x_label)) / 2, o.height - 22, o.x_label, ink);
  c.text(12, (top + bottom + text_width(o.y_label)) / 2, o.y_label, ink, 1, true);
  return std::move(c.px);
}

void write_line_plot_png(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& options) {
  const std::vector<std::uint8_t> rgb = render_line_plot(series, options);
  std::string png;
  auto sink = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(sink, &png, options.width, options.height, 3, rgb.data(), options.width * 3))
    throw std::runtime_error(path + ": PNG encoding failed");
  write_file_atomic(path, png);
}

}  // namespace prep
