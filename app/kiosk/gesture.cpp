// Gestures: CSV parsing with line-precise errors, the built-in gestures, and the mapping from pen
// samples to timed probe commands (format and mapping in gesture.h).
#include "kiosk/gesture.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace sas::kiosk {
namespace {

constexpr const char* kColumns[] = {"t", "x", "y", "pressure", "tilt"};
constexpr double kMaxCoordinateMm = 2000.0;

std::string Trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream stream(line);
  while (std::getline(stream, field, ',')) fields.push_back(Trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string Where(const std::string& source, int line, const std::string& column) {
  return source + ":" + std::to_string(line) + ": " + column + ": ";
}

double ParseNumber(const std::string& field, const std::string& where) {
  double value = 0.0;
  const char* begin = field.data();
  const char* end = field.data() + field.size();
  const auto [ptr, error] = std::from_chars(begin, end, value);
  if (field.empty() || error != std::errc() || ptr != end) {
    throw GestureError(where + "\"" + field + "\" is not a number");
  }
  if (!std::isfinite(value)) throw GestureError(where + "must be a finite number");
  return value;
}

void CheckRange(double value, double min, double max, const std::string& where, const char* unit) {
  if (value < min || value > max) {
    std::ostringstream message;
    message << where << value << " is out of range [" << min << ", " << max << "] " << unit;
    throw GestureError(message.str());
  }
}

double Clamp01(double value) {
  return std::clamp(value, 0.0, 1.0);
}

Gesture FromRows(const std::string& name, std::vector<GestureSample> samples,
                 double landing_speed_mps = 0.1) {
  Gesture gesture;
  gesture.name = name;
  gesture.samples = std::move(samples);
  gesture.landing_speed_mps = landing_speed_mps;
  return gesture;
}

// A stroke along +x at constant speed, landing and lifting while moving, as a person draws a line.
Gesture SlowStroke() {
  // 30 mm/s everywhere: 3 mm per 0.1 s ramps, 57 mm in the 1.9 s between them.
  return FromRows("slow stroke", {{0.0, 10.0, 20.0, 0.0, 10.0},
                                  {0.1, 13.0, 20.0, 0.5, 10.0},
                                  {2.0, 70.0, 20.0, 0.5, 10.0},
                                  {2.1, 73.0, 20.0, 0.0, 10.0}});
}

// Seven quick back-and-forth strokes of 50 mm in 0.2 s each (0.25 m/s), drifting down the page.
Gesture FastScribble() {
  std::vector<GestureSample> rows;
  rows.push_back({0.0, 15.0, 15.0, 0.0, 20.0});
  rows.push_back({0.02, 15.0, 15.0, 0.7, 20.0});
  for (int stroke = 1; stroke <= 7; ++stroke) {
    const double x = (stroke % 2 == 1) ? 65.0 : 15.0;
    rows.push_back({0.02 + 0.2 * stroke, x, 15.0 + 1.5 * stroke, 0.7, 20.0});
  }
  const auto& last = rows.back();
  rows.push_back({last.t_s + 0.02, last.x_mm, last.y_mm, 0.0, 20.0});
  return FromRows("fast scribble", std::move(rows));
}

// Four taps 0.4 s apart, 60 ms down each, moving 10 mm between them with the pen up.
Gesture Tap() {
  std::vector<GestureSample> rows;
  rows.push_back({0.0, 20.0, 20.0, 0.0, 0.0});
  for (int i = 0; i < 4; ++i) {
    const double t = 0.1 + 0.4 * i;
    const double x = 20.0 + 10.0 * i;
    rows.push_back({t - 0.001, x, 20.0, 0.0, 0.0});
    rows.push_back({t, x, 20.0, 0.6, 0.0});
    rows.push_back({t + 0.06, x, 20.0, 0.6, 0.0});
    rows.push_back({t + 0.061, x, 20.0, 0.0, 0.0});
  }
  return FromRows("tap", std::move(rows), /*landing_speed_mps=*/0.25);
}

std::string Canonical(const std::string& name) {
  std::string canonical;
  for (char c : name) {
    if (c == '-' || c == '_') c = ' ';
    canonical += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return canonical;
}

}  // namespace

Gesture ParseGestureCsv(const std::string& text, const std::string& source_name) {
  std::istringstream stream(text);
  std::string raw;
  int line_number = 0;
  bool header_seen = false;
  std::vector<GestureSample> samples;
  while (std::getline(stream, raw)) {
    ++line_number;
    const std::string line = Trim(raw);
    if (line.empty() || line[0] == '#') continue;
    const auto fields = SplitFields(line);
    if (!header_seen) {
      const bool header_ok =
          fields.size() == 5 && std::equal(fields.begin(), fields.end(), std::begin(kColumns));
      if (!header_ok) {
        throw GestureError(Where(source_name, line_number, "header") +
                           "expected \"t,x,y,pressure,tilt\", got \"" + line + "\"");
      }
      header_seen = true;
      continue;
    }
    if (fields.size() != 5) {
      throw GestureError(Where(source_name, line_number, "row") + "expected 5 values, got " +
                         std::to_string(fields.size()));
    }
    double values[5];
    for (int i = 0; i < 5; ++i) {
      values[i] = ParseNumber(fields[static_cast<std::size_t>(i)],
                              Where(source_name, line_number, kColumns[i]));
    }
    const GestureSample sample{values[0], values[1], values[2], values[3], values[4]};
    CheckRange(sample.t_s, 0.0, 3600.0, Where(source_name, line_number, "t"), "s");
    if (!samples.empty() && sample.t_s <= samples.back().t_s) {
      throw GestureError(Where(source_name, line_number, "t") +
                         "time must increase from row to row");
    }
    CheckRange(sample.x_mm, 0.0, kMaxCoordinateMm, Where(source_name, line_number, "x"), "mm");
    CheckRange(sample.y_mm, 0.0, kMaxCoordinateMm, Where(source_name, line_number, "y"), "mm");
    CheckRange(sample.pressure, 0.0, 1.0, Where(source_name, line_number, "pressure"), "");
    CheckRange(sample.tilt_deg, 0.0, 90.0, Where(source_name, line_number, "tilt"), "degrees");
    samples.push_back(sample);
  }
  if (!header_seen) {
    throw GestureError(source_name + ":1: header: missing \"t,x,y,pressure,tilt\"");
  }
  if (samples.size() < 2) {
    throw GestureError(source_name + ":" + std::to_string(line_number) +
                       ": row: a gesture needs at least two rows");
  }
  Gesture gesture;
  gesture.name = source_name;
  gesture.samples = std::move(samples);
  return gesture;
}

Gesture LoadGestureCsv(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw GestureError(path + ": cannot open gesture file");
  std::ostringstream text;
  text << file.rdbuf();
  return ParseGestureCsv(text.str(), path);
}

std::vector<std::string> BuiltinGestureNames() {
  return {"slow stroke", "fast scribble", "tap", "passive sweep"};
}

Gesture PassiveSweep(double velocity_mps, double length_mm, double pressure, double x0_mm,
                     double y0_mm) {
  const double duration_s = length_mm * 1e-3 / velocity_mps;
  return FromRows("passive sweep", {{0.0, x0_mm, y0_mm, pressure, 0.0},
                                    {duration_s, x0_mm + length_mm, y0_mm, pressure, 0.0}});
}

std::optional<Gesture> FindBuiltinGesture(const std::string& name) {
  const std::string canonical = Canonical(name);
  if (canonical == "slow stroke") return SlowStroke();
  if (canonical == "fast scribble") return FastScribble();
  if (canonical == "tap") return Tap();
  // The paper's passive mode: 5 cm/s across 70 mm with a moderate, steady push.
  if (canonical == "passive sweep") return PassiveSweep(0.05, 70.0, 0.4);
  return std::nullopt;
}

GestureSample GestureAt(const Gesture& gesture, double t_s) {
  const auto& rows = gesture.samples;
  if (rows.empty()) return {};
  if (t_s <= rows.front().t_s) return rows.front();
  if (t_s >= rows.back().t_s) return rows.back();
  const auto next =
      std::upper_bound(rows.begin(), rows.end(), t_s,
                       [](double t, const GestureSample& row) { return t < row.t_s; });
  const GestureSample& a = *(next - 1);
  const GestureSample& b = *next;
  const double u = (t_s - a.t_s) / (b.t_s - a.t_s);
  GestureSample at;
  at.t_s = t_s;
  at.x_mm = a.x_mm + u * (b.x_mm - a.x_mm);
  at.y_mm = a.y_mm + u * (b.y_mm - a.y_mm);
  at.pressure = a.pressure + u * (b.pressure - a.pressure);
  at.tilt_deg = a.tilt_deg + u * (b.tilt_deg - a.tilt_deg);
  return at;
}

std::vector<TimedCommand> GestureToCommands(const Gesture& gesture, const GestureMapping& mapping,
                                            double sample_rate_hz) {
  if (gesture.samples.size() < 2) throw GestureError(gesture.name + ": needs at least two rows");
  if (!(mapping.control_rate_hz > 0.0) || !(sample_rate_hz > 0.0)) {
    throw GestureError(gesture.name + ": control and sample rates must be positive");
  }
  const auto& rows = gesture.samples;
  const double tick_s = 1.0 / mapping.control_rate_hz;
  const double end_s = gesture.duration_s();
  std::vector<TimedCommand> commands;
  std::size_t segment = 0;
  double direction_x = 1.0;
  double direction_y = 0.0;
  for (std::int64_t tick = 0;; ++tick) {
    const double t = static_cast<double>(tick) * tick_s;
    if (t > end_s + 1e-12) break;
    while (segment + 2 < rows.size() && t >= rows[segment + 1].t_s) ++segment;
    const GestureSample& a = rows[segment];
    const GestureSample& b = rows[segment + 1];
    const double span_s = b.t_s - a.t_s;
    const double u = Clamp01((t - a.t_s) / span_s);
    const double dx_mm = b.x_mm - a.x_mm;
    const double dy_mm = b.y_mm - a.y_mm;
    const double length_mm = std::hypot(dx_mm, dy_mm);
    if (length_mm > 0.0) {  // a pen standing still keeps its last direction
      direction_x = dx_mm / length_mm;
      direction_y = dy_mm / length_mm;
    }
    const double pressure = a.pressure + u * (b.pressure - a.pressure);
    const double tilt_deg = a.tilt_deg + u * (b.tilt_deg - a.tilt_deg);

    TimedCommand timed;
    timed.frame = static_cast<std::int64_t>(std::llround(t * sample_rate_hz));
    if (!commands.empty() && timed.frame <= commands.back().frame) continue;
    synth::ProbeCommand& c = timed.command;
    c.tip_down = t >= rows.front().t_s && pressure > kGesturePenUpPressure;
    c.x_m = (a.x_mm + u * dx_mm) * 1e-3;
    c.y_m = (a.y_mm + u * dy_mm) * 1e-3;
    c.velocity_mps = length_mm * 1e-3 / span_s;
    c.direction_x = direction_x;
    c.direction_y = direction_y;
    ApplyPenPressure(pressure, mapping.max_penetration_m, mapping, c);
    ApplyPenTilt(tilt_deg, ProbeShape{}, mapping.style, mapping, c);
    c.landing_speed_mps = gesture.landing_speed_mps;
    commands.push_back(timed);
  }
  // After the last row the pen is lifted, whatever the file's last pressure was.
  TimedCommand lift = commands.back();
  lift.frame =
      std::max<std::int64_t>(commands.back().frame + 1, std::llround(end_s * sample_rate_hz));
  lift.command.tip_down = false;
  lift.command.velocity_mps = 0.0;
  lift.command.normal_force_n = 0.0;
  commands.push_back(lift);
  return commands;
}

}  // namespace sas::kiosk
