#pragma once
// A minimal line plot written as a PNG, with no dependency: the examples use it to draw
// omega(t) and similar curves. The PNG is RGB, 8 bit, with zlib "stored" (uncompressed) deflate
// blocks (RFC 1950/1951) and the CRC-32 and Adler-32 checksums the format requires (PNG spec,
// ISO/IEC 15948). Text is drawn with a built-in 5x7 pixel font (digits, letters, a few signs).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace tumble_examples {

struct Rgb {
  std::uint8_t r, g, b;
};

class PngPlot {
 public:
  PngPlot(int width, int height, std::string title)
      : w_(width),
        h_(height),
        title_(std::move(title)),
        px_(std::size_t(width) * height, {255, 255, 255}) {}

  /// Add a curve (x, y samples) with a legend label.
  void add(const std::vector<double>& x, const std::vector<double>& y, Rgb color,
           std::string label) {
    series_.push_back({x, y, color, std::move(label)});
  }
  void set_labels(std::string xlabel, std::string ylabel) {
    xlabel_ = std::move(xlabel);
    ylabel_ = std::move(ylabel);
  }

  void write(const std::string& path) {
    render();
    std::vector<std::uint8_t> raw;
    raw.reserve(std::size_t(h_) * (1 + 3 * std::size_t(w_)));
    for (int j = 0; j < h_; ++j) {
      raw.push_back(0);  // filter type: none
      for (int i = 0; i < w_; ++i) {
        const Rgb& c = px_[std::size_t(j) * w_ + i];
        raw.insert(raw.end(), {c.r, c.g, c.b});
      }
    }
    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<std::uint8_t> ihdr;
    put32(ihdr, std::uint32_t(w_));
    put32(ihdr, std::uint32_t(h_));
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8 bit, RGB, deflate, no filter set, no interlace
    chunk(png, "IHDR", ihdr);
    chunk(png, "IDAT", zlib_stored(raw));
    chunk(png, "IEND", {});
    std::ofstream out(path, std::ios::binary);
    if (!out) {
      throw std::runtime_error("cannot write " + path);
    }
    out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  }

 private:
  struct Series {
    std::vector<double> x, y;
    Rgb color;
    std::string label;
  };

  void render() {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const Series& s : series_) {
      for (double v : s.x) x0 = std::min(x0, v), x1 = std::max(x1, v);
      for (double v : s.y) y0 = std::min(y0, v), y1 = std::max(y1, v);
    }
    if (!(x1 > x0)) x1 = x0 + 1;
    if (!(y1 > y0)) y1 = y0 + 1;
    const double pad = 0.05 * (y1 - y0);
    y0 -= pad;
    y1 += pad;
    const int left = 70, right = w_ - 20, top = 40, bottom = h_ - 50;
    auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (right - left); };
    auto py = [&](double y) { return bottom - (y - y0) / (y1 - y0) * (bottom - top); };
    // grid and tick labels
    for (int k = 0; k <= 5; ++k) {
      const double xv = x0 + k * (x1 - x0) / 5, yv = y0 + k * (y1 - y0) / 5;
      const int gx = int(std::lround(px(xv))), gy = int(std::lround(py(yv)));
      line(gx, top, gx, bottom, {225, 225, 225});
      line(left, gy, right, gy, {225, 225, 225});
      text(number(xv), gx - 12, bottom + 8, {0, 0, 0});
      text(number(yv), 4, gy - 3, {0, 0, 0});
    }
    line(left, bottom, right, bottom, {0, 0, 0});
    line(left, top, left, bottom, {0, 0, 0});
    line(right, top, right, bottom, {0, 0, 0});
    line(left, top, right, top, {0, 0, 0});
    for (const Series& s : series_) {
      for (std::size_t k = 1; k < s.x.size(); ++k) {
        thick_line(px(s.x[k - 1]), py(s.y[k - 1]), px(s.x[k]), py(s.y[k]), s.color);
      }
    }
    text(title_, left, 12, {0, 0, 0});
    text(xlabel_, (left + right) / 2 - 3 * int(xlabel_.size()), h_ - 22, {0, 0, 0});
    text(ylabel_, 4, top - 14, {0, 0, 0});
    int ly = top + 8;
    for (const Series& s : series_) {  // legend
      for (int d = 0; d < 3; ++d)
        line(right - 110, ly + 3 + d - 1, right - 90, ly + 3 + d - 1, s.color);
      text(s.label, right - 84, ly, {0, 0, 0});
      ly += 14;
    }
  }

  static std::string number(double v) {
    char buf[32];
    if (v != 0 && (std::abs(v) < 1e-2 || std::abs(v) >= 1e4)) {
      std::snprintf(buf, sizeof buf, "%.1e", v);
    } else {
      std::snprintf(buf, sizeof buf, "%.3g", v);
    }
    return buf;
  }

  void set(int i, int j, Rgb c) {
    if (i >= 0 && i < w_ && j >= 0 && j < h_) px_[std::size_t(j) * w_ + i] = c;
  }
  void line(int xa, int ya, int xb, int yb, Rgb c) {  // Bresenham
    const int dx = std::abs(xb - xa), dy = -std::abs(yb - ya);
    const int sx = xa < xb ? 1 : -1, sy = ya < yb ? 1 : -1;
    int err = dx + dy;
    for (;;) {
      set(xa, ya, c);
      if (xa == xb && ya == yb) break;
      const int e2 = 2 * err;
      if (e2 >= dy) err += dy, xa += sx;
      if (e2 <= dx) err += dx, ya += sy;
    }
  }
  void thick_line(double xa, double ya, double xb, double yb, Rgb c) {
    const int a = int(std::lround(xa)), b = int(std::lround(ya));
    const int p = int(std::lround(xb)), q = int(std::lround(yb));
    line(a, b, p, q, c);
    line(a, b + 1, p, q + 1, c);
  }

  // 5x7 font: each glyph is 7 rows of 5 bits.
  static const std::array<std::uint8_t, 7>* glyph(char ch) {
    static const std::string chars = "0123456789.-+e()/=abcdefghijklmnopqrstuvwxyz,:_ ";
    static const std::array<std::uint8_t, 7> g[] = {
        {14, 17, 19, 21, 25, 17, 14}, {4, 12, 4, 4, 4, 4, 14},      {14, 17, 1, 2, 4, 8, 31},
        {31, 2, 4, 2, 1, 17, 14},     {2, 6, 10, 18, 31, 2, 2},     {31, 16, 30, 1, 1, 17, 14},
        {6, 8, 16, 30, 17, 17, 14},   {31, 1, 2, 4, 8, 8, 8},       {14, 17, 17, 14, 17, 17, 14},
        {14, 17, 17, 15, 1, 2, 12},   {0, 0, 0, 0, 0, 12, 12},      {0, 0, 0, 31, 0, 0, 0},
        {0, 4, 4, 31, 4, 4, 0},       {0, 0, 14, 17, 31, 16, 14},   {2, 4, 8, 8, 8, 4, 2},
        {8, 4, 2, 2, 2, 4, 8},        {1, 1, 2, 4, 8, 16, 16},      {0, 0, 31, 0, 31, 0, 0},
        {0, 0, 14, 1, 15, 17, 15},    {16, 16, 22, 25, 17, 17, 30}, {0, 0, 14, 16, 16, 17, 14},
        {1, 1, 13, 19, 17, 17, 15},   {0, 0, 14, 17, 31, 16, 14},   {6, 9, 8, 28, 8, 8, 8},
        {0, 0, 15, 16, 19, 17, 15},   {16, 16, 22, 25, 17, 17, 17}, {4, 0, 12, 4, 4, 4, 14},
        {2, 0, 6, 2, 2, 18, 12},      {16, 16, 18, 20, 24, 20, 18}, {12, 4, 4, 4, 4, 4, 14},
        {0, 0, 26, 21, 21, 17, 17},   {0, 0, 22, 25, 17, 17, 17},   {0, 0, 14, 17, 17, 17, 14},
        {0, 0, 30, 17, 30, 16, 16},   {0, 0, 13, 19, 15, 1, 1},     {0, 0, 22, 25, 16, 16, 16},
        {0, 0, 14, 16, 14, 1, 30},    {8, 8, 28, 8, 8, 9, 6},       {0, 0, 17, 17, 17, 19, 13},
        {0, 0, 17, 17, 17, 10, 4},    {0, 0, 17, 17, 21, 21, 10},   {0, 0, 17, 10, 4, 10, 17},
        {0, 0, 17, 17, 15, 1, 14},    {0, 0, 31, 2, 4, 8, 31},      {0, 0, 0, 0, 12, 4, 8},
        {0, 12, 12, 0, 12, 12, 0},    {0, 0, 0, 0, 0, 0, 31},       {0, 0, 0, 0, 0, 0, 0}};
    const char lower = (ch >= 'A' && ch <= 'Z') ? char(ch - 'A' + 'a') : ch;
    const auto pos = chars.find(lower);
    return pos == std::string::npos ? &g[chars.size() - 1] : &g[pos];
  }
  void text(const std::string& s, int x, int y, Rgb c) {
    for (char ch : s) {
      const auto& gl = *glyph(ch);
      for (int r = 0; r < 7; ++r)
        for (int k = 0; k < 5; ++k)
          if (gl[r] & (16 >> k)) set(x + k, y + r, c);
      x += 6;
    }
  }

  static void put32(std::vector<std::uint8_t>& v, std::uint32_t x) {
    v.insert(v.end(),
             {std::uint8_t(x >> 24), std::uint8_t(x >> 16), std::uint8_t(x >> 8), std::uint8_t(x)});
  }
  static std::uint32_t crc32(const std::uint8_t* d, std::size_t n, std::uint32_t c = 0xffffffffu) {
    for (std::size_t i = 0; i < n; ++i) {
      c ^= d[i];
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c;
  }
  static void chunk(std::vector<std::uint8_t>& png, const char* type,
                    const std::vector<std::uint8_t>& data) {
    put32(png, std::uint32_t(data.size()));
    std::vector<std::uint8_t> td(type, type + 4);
    td.insert(td.end(), data.begin(), data.end());
    png.insert(png.end(), td.begin(), td.end());
    put32(png, crc32(td.data(), td.size()) ^ 0xffffffffu);
  }
  static std::vector<std::uint8_t> zlib_stored(const std::vector<std::uint8_t>& raw) {
    std::vector<std::uint8_t> z = {0x78, 0x01};
    std::size_t pos = 0;
    do {
      const std::size_t n = std::min<std::size_t>(65535, raw.size() - pos);
      z.push_back(pos + n == raw.size() ? 1 : 0);  // BFINAL, BTYPE = 00 (stored)
      z.insert(z.end(),
               {std::uint8_t(n), std::uint8_t(n >> 8), std::uint8_t(~n), std::uint8_t(~n >> 8)});
      z.insert(z.end(), raw.begin() + std::ptrdiff_t(pos), raw.begin() + std::ptrdiff_t(pos + n));
      pos += n;
    } while (pos < raw.size());
    std::uint32_t a = 1, b = 0;  // Adler-32
    for (std::uint8_t x : raw) a = (a + x) % 65521, b = (b + a) % 65521;
    put32(z, (b << 16) | a);
    return z;
  }

  int w_, h_;
  std::string title_, xlabel_, ylabel_;
  std::vector<Rgb> px_;
  std::vector<Series> series_;
};

}  // namespace tumble_examples
