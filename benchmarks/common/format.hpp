#pragma once
// tumble_bench: how numbers are written, in the terminal tables and in the CSV files.

#include <cmath>
#include <cstdio>
#include <string>

namespace tumble::bench {

/// printf of one number.
inline std::string fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

/// 1.2e-03 style, "nan" for NaN.
inline std::string sci(double x) { return std::isnan(x) ? std::string("nan") : fmt("%.1e", x); }

/// A duration with its unit and three significant digits ("3.87 ms", "140 us"); "-" when not
/// finite. `compact` drops the space ("3.87ms"), for narrow table cells.
inline std::string duration(double s, bool compact = false) {
  if (!std::isfinite(s)) {
    return "-";
  }
  const char* unit = "s";
  double v = s;
  if (s < 1e-6) {
    unit = "ns";
    v = s * 1e9;
  } else if (s < 1e-3) {
    unit = "us";
    v = s * 1e6;
  } else if (s < 1.0) {
    unit = "ms";
    v = s * 1e3;
  }
  std::string text = fmt(v < 10 ? "%.2f" : v < 100 ? "%.1f" : "%.0f", v);
  text += compact ? "" : " ";
  return text + unit;
}

/// Left-aligned in `width` columns.
inline std::string pad(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : s + std::string(width - s.size(), ' ');
}

/// Right-aligned in `width` columns.
inline std::string lpad(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : std::string(width - s.size(), ' ') + s;
}

/// A number for a CSV cell: 6 significant digits, empty for NaN.
inline std::string num(double x) { return std::isnan(x) ? std::string() : fmt("%.6g", x); }

/// A CSV cell, quoted when it holds a comma, a quote or a newline.
inline std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) {
    return s;
  }
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"') {
      q += '"';
    }
    q += ch == '\n' ? ' ' : ch;
  }
  return q + "\"";
}

}  // namespace tumble::bench
