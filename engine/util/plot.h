// A small line-plot writer for figures such as the training curve (Fig. 10): axes, ticks with numbers,
// a title and axis labels drawn with a built-in 5x7 bitmap font, written as PNG through stb_image_write.
// No GL, no fonts on disk.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace prep {

struct PlotSeries {
  std::vector<double> x, y;
  std::uint32_t rgb = 0x1f5fbf;  // line colour 0xRRGGBB
  std::string label;             // shown in the legend (top right) when any series has one
  std::vector<double> marks;     // x positions marked with a dot on the line (e.g. the launches)
};

struct PlotOptions {
  int width = 800, height = 500;
  std::string title, x_label, y_label;
  // A fixed y range (both finite and y_max > y_min), else the data's.
  double y_min = std::numeric_limits<double>::quiet_NaN(), y_max = std::numeric_limits<double>::quiet_NaN();
};

// An RGB image (row-major, 3 bytes a pixel) of the plot. Axis ranges cover every point (the y range also
// includes 0 when the data are all positive and small relative to their span, so a rise reads as a rise).
std::vector<std::uint8_t> render_line_plot(const std::vector<PlotSeries>& series, const PlotOptions& options);

// Renders and writes a PNG atomically. Throws std::runtime_error naming the file on failure.
void write_line_plot_png(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& options);

// "Nice" tick positions (1, 2 or 5 x 10^k apart) covering [lo, hi], about `count` of them.
std::vector<double> nice_ticks(double lo, double hi, int count);

// Pixel width of a text in the built-in font at scale 1 (6 px a character, including the gap).
int text_width(const std::string& text);

}  // namespace prep
