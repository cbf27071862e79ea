// Sound -> image and sound/vibration -> profile (see sound_image.h).
#include "surface/sound_image.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "surface/image_surface.h"

namespace sas::surface {
namespace {

float PeakOf(std::span<const float> samples, std::size_t count) {
  float peak = 0.0f;
  for (std::size_t i = 0; i < count; ++i) peak = std::max(peak, std::fabs(samples[i]));
  return peak;
}

// The |sample| below which `quantile` of the active samples lie, from a histogram of |s| / peak
// (no copy of the recording, which stays in the caller's memory only). 1: the peak itself.
// Active: the 10 ms blocks within kActiveRangeDb of the loudest block. Pauses and the silence
// before and after a take are not speech; counted, they pull the level down and the speech
// clips the more the longer the visitor waited (the speech level is that of the active speech
// alone: ITU-T P.56). 30 dB is the dynamic range of running speech, peaks to weakest sounds
// (ANSI S3.5-1997, the Speech Intelligibility Index).
constexpr double kActiveRangeDb = 30.0;

// The 10 ms blocks of a recording and the power a block must reach to count as active.
struct BlockGate {
  std::span<const float> samples;
  std::size_t count = 0;
  std::size_t block = 1;
  double gate = 0.0;

  BlockGate(std::span<const float> s, std::size_t n, double sample_rate_hz)
      : samples(s),
        count(n),
        block(std::max<std::size_t>(1, static_cast<std::size_t>(0.01 * sample_rate_hz))) {
    double loudest = 0.0;
    for (std::size_t first = 0; first < count; first += block) {
      loudest = std::max(loudest, Power(first));
    }
    gate = loudest * std::pow(10.0, -kActiveRangeDb / 10.0);
  }
  double Power(std::size_t first) const {
    const std::size_t last = End(first);
    double sum = 0.0;
    for (std::size_t i = first; i < last; ++i) sum += static_cast<double>(samples[i]) * samples[i];
    return sum / static_cast<double>(last - first);
  }
  std::size_t End(std::size_t first) const { return std::min(count, first + block); }
  bool Active(std::size_t first) const { return gate > 0.0 && Power(first) >= gate; }
};

double LevelOf(std::span<const float> samples, std::size_t count, float peak, double quantile,
               double sample_rate_hz) {
  if (quantile >= 1.0 || !(peak > 1e-9f)) return peak;
  const BlockGate blocks(samples, count, sample_rate_hz);
  constexpr std::size_t kBins = 4096;  // the level to 1/4096 of the peak: finer than any screen
  constexpr double kTop = static_cast<double>(kBins - 1);
  std::array<std::size_t, kBins> histogram{};
  std::size_t active = 0;
  for (std::size_t first = 0; first < count; first += blocks.block) {
    if (!blocks.Active(first)) continue;
    const std::size_t last = blocks.End(first);
    for (std::size_t i = first; i < last; ++i) {
      const double bin = static_cast<double>(std::fabs(samples[i])) / peak * kTop;
      ++histogram[std::min(static_cast<std::size_t>(bin), kBins - 1)];
    }
    active += last - first;
  }
  const double wanted = std::ceil(quantile * static_cast<double>(active));
  double below = 0.0;
  for (std::size_t b = 0; b < kBins; ++b) {
    below += static_cast<double>(histogram[b]);
    // Bin b holds |s| / peak in [b, b + 1) / kTop: its upper edge is the level.
    if (below >= wanted) {
      return std::min(static_cast<double>(b + 1) / kTop, 1.0) * static_cast<double>(peak);
    }
  }
  return peak;
}

// Value of the recording's chunk `chunk` at pixel x (see temporal expansion in the header).
float PixelValue(std::span<const float> s, std::size_t count, std::size_t chunk, int x,
                 const SoundImageOptions& o) {
  const double per_px = static_cast<double>(o.samples_per_row) / o.row_length_px;
  const double start = static_cast<double>(chunk) * o.samples_per_row;
  const auto sample = [&](double index) -> double {
    if (index < 0.0 || index >= static_cast<double>(count)) return 0.0;
    return s[static_cast<std::size_t>(index)];
  };
  if (per_px >= 1.0) {
    // Compressing: the mean of the samples the pixel covers.
    const double a = start + x * per_px;
    const auto first = static_cast<std::size_t>(std::floor(a));
    const auto last = static_cast<std::size_t>(std::ceil(a + per_px)) - 1;
    double sum = 0.0;
    for (std::size_t i = first; i <= last; ++i) sum += sample(static_cast<double>(i));
    return static_cast<float>(sum / static_cast<double>(last - first + 1));
  }
  // Expanding: linear interpolation at the pixel centre (sample k sits at pixels [k/per_px, ...)).
  const double t = (x + 0.5) * per_px - 0.5;
  const double local = std::clamp(t, 0.0, static_cast<double>(o.samples_per_row - 1));
  const double i0 = std::floor(local);
  const double frac = local - i0;
  const double v0 = sample(start + i0);
  const double v1 = i0 + 1 < o.samples_per_row ? sample(start + i0 + 1) : v0;
  return static_cast<float>(v0 + frac * (v1 - v0));
}

[[noreturn]] void CsvFail(const std::string& name, std::size_t line, const std::string& why) {
  throw LoadError("vibration " + name + ":" + std::to_string(line) + ": " + why);
}

bool ParseDouble(std::string_view text, double& value) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) {
    text.remove_suffix(1);
  }
  if (text.empty()) return false;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size() &&
         std::isfinite(value);
}

}  // namespace

std::pmr::vector<float> TrimToSpeech(std::span<const float> samples, double sample_rate_hz,
                                     const SpeechTrimOptions& o,
                                     std::pmr::memory_resource* memory) {
  if (!(sample_rate_hz > 0.0) || !(o.margin_s >= 0.0) || !(o.max_pause_s >= 0.0)) {
    throw std::invalid_argument("TrimToSpeech: options out of range");
  }
  std::pmr::vector<float> speech(memory);
  const BlockGate blocks(samples, samples.size(), sample_rate_hz);
  // The active stretches as [begin, end) sample ranges, in order.
  std::vector<std::pair<std::size_t, std::size_t>> active;
  for (std::size_t first = 0; first < samples.size(); first += blocks.block) {
    if (!blocks.Active(first)) continue;
    if (!active.empty() && active.back().second == first) {
      active.back().second = blocks.End(first);
    } else {
      active.push_back({first, blocks.End(first)});
    }
  }
  if (active.empty()) return speech;  // silence: nothing of the voice to show
  const auto margin = static_cast<std::size_t>(o.margin_s * sample_rate_hz);
  const auto half_pause = static_cast<std::size_t>(o.max_pause_s * sample_rate_hz / 2.0);
  // The kept ranges: each stretch with the margin before the first and after the last, and of a
  // long pause its two ends (the fading of one sound and the onset of the next stay whole).
  std::vector<std::pair<std::size_t, std::size_t>> kept;
  std::size_t total = 0;
  const auto keep = [&](std::size_t begin, std::size_t end) {
    if (end <= begin) return;
    if (!kept.empty() && kept.back().second >= begin) {
      total += end - kept.back().second;
      kept.back().second = end;
    } else {
      kept.push_back({begin, end});
      total += end - begin;
    }
  };
  keep(active.front().first - std::min(margin, active.front().first), active.front().first);
  for (std::size_t i = 0; i < active.size(); ++i) {
    keep(active[i].first, active[i].second);
    if (i + 1 < active.size()) {
      const std::size_t gap_end = active[i + 1].first;
      keep(active[i].second, std::min(gap_end, active[i].second + half_pause));
      keep(gap_end - std::min(half_pause, gap_end - active[i].second), gap_end);
    }
  }
  keep(active.back().second, std::min(samples.size(), active.back().second + margin));
  speech.reserve(total);
  for (const auto& [begin, end] : kept) {
    speech.insert(speech.end(), samples.begin() + static_cast<std::ptrdiff_t>(begin),
                  samples.begin() + static_cast<std::ptrdiff_t>(end));
  }
  return speech;
}

GrayImage SoundToImage(std::span<const float> samples, const SoundImageOptions& o,
                       std::pmr::memory_resource* memory) {
  if (samples.empty()) throw std::invalid_argument("SoundToImage: empty recording");
  if (o.samples_per_row < 1 || o.row_length_px < 1 || o.row_height_px < 1 ||
      o.row_length_px > 16384 || !(o.max_duration_s > 0.0) || !(o.sample_rate_hz > 0.0) ||
      !(o.level_quantile > 0.0 && o.level_quantile <= 1.0)) {
    throw std::invalid_argument("SoundToImage: options out of range");
  }
  const auto max_samples = static_cast<std::size_t>(o.max_duration_s * o.sample_rate_hz);
  const std::size_t count = std::min(samples.size(), std::max<std::size_t>(1, max_samples));
  const std::size_t chunks = (count + static_cast<std::size_t>(o.samples_per_row) - 1) /
                             static_cast<std::size_t>(o.samples_per_row);
  if (chunks * static_cast<std::size_t>(o.row_height_px) > 16384) {
    throw std::invalid_argument("SoundToImage: image would be taller than 16384 rows");
  }
  const float peak = PeakOf(samples, count);
  const double level = LevelOf(samples, count, peak, o.level_quantile, o.sample_rate_hz);
  const double scale = level > 1e-9 ? 0.5 / level : 0.0;  // silence: uniform mid-grey
  GrayImage image{o.row_length_px, static_cast<int>(chunks) * o.row_height_px,
                  std::pmr::vector<float>(memory)};
  image.luminance.assign(
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height), 0.5f);
  const std::size_t first_half = (chunks + 1) / 2;
  for (std::size_t row = 0; row < chunks; ++row) {
    // Interlacing: even rows walk the first half of the chunks, odd rows the second half.
    const std::size_t chunk = !o.interlace ? row : (row % 2 == 0 ? row / 2 : first_half + row / 2);
    for (int x = 0; x < o.row_length_px; ++x) {
      double lum = 0.5 + scale * PixelValue(samples, count, chunk, x, o);
      if (o.invert) lum = 1.0 - lum;
      for (int r = 0; r < o.row_height_px; ++r) {
        const auto y =
            row * static_cast<std::size_t>(o.row_height_px) + static_cast<std::size_t>(r);
        image.luminance[y * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)] =
            static_cast<float>(std::clamp(lum, 0.0, 1.0));
      }
    }
  }
  return image;
}

HeightField SoundToHeightField(const AudioClip& clip, const SoundImageOptions& options,
                               double relief_mm, double pixel_pitch_mm) {
  if (clip.samples.empty() || clip.silent) {
    throw std::invalid_argument("SoundToHeightField: the recording is empty or silent");
  }
  SoundImageOptions o = options;
  o.sample_rate_hz = clip.sample_rate_hz;
  return SoundToHeightField(clip.samples, o, relief_mm, pixel_pitch_mm,
                            std::pmr::get_default_resource());
}

HeightField SoundToHeightField(std::span<const float> samples, const SoundImageOptions& options,
                               double relief_mm, double pixel_pitch_mm,
                               std::pmr::memory_resource* memory) {
  if (samples.empty()) throw std::invalid_argument("SoundToHeightField: the recording is empty");
  ReliefOptions relief;
  relief.source = ReliefSource::kLuminance;
  relief.relief_mm = relief_mm;
  relief.pixel_pitch_mm = pixel_pitch_mm;
  // Returned by a move out of the temporary: the field keeps `memory` (height_field.h).
  return SurfaceFromImage(SoundToImage(samples, options, memory), relief, memory).field;
}

HeightField SoundToProfile(const AudioClip& clip, const SoundProfileOptions& o) {
  if (clip.samples.empty() || !(clip.sample_rate_hz > 0.0)) {
    throw std::invalid_argument("SoundToProfile: empty recording");
  }
  if (!(o.mm_per_s > 0.0) || !(o.pitch_mm > 0.0) || !(o.amplitude_mm >= 0.0) ||
      !(o.envelope_window_ms > 0.0)) {
    throw std::invalid_argument("SoundToProfile: options out of range");
  }
  const double length_mm = clip.duration_s() * o.mm_per_s;
  if (length_mm > o.max_length_mm) throw std::invalid_argument("SoundToProfile: profile too long");
  const auto points =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(length_mm / o.pitch_mm)));
  const double samples_per_point = clip.sample_rate_hz * o.pitch_mm / o.mm_per_s;
  const auto n = clip.samples.size();
  std::vector<double> values(points, 0.0);
  if (o.shape == ProfileShape::kEnvelope) {
    // RMS over a window centred on each point, via a prefix sum of squares.
    std::vector<double> energy(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      energy[i + 1] = energy[i] + static_cast<double>(clip.samples[i]) * clip.samples[i];
    }
    const double half = std::max(0.5, o.envelope_window_ms * 1e-3 * clip.sample_rate_hz * 0.5);
    for (std::size_t p = 0; p < points; ++p) {
      const double centre = (static_cast<double>(p) + 0.5) * samples_per_point;
      const auto a =
          static_cast<std::size_t>(std::clamp(centre - half, 0.0, static_cast<double>(n)));
      const auto b =
          static_cast<std::size_t>(std::clamp(centre + half, 0.0, static_cast<double>(n)));
      values[p] = b > a ? std::sqrt((energy[b] - energy[a]) / static_cast<double>(b - a)) : 0.0;
    }
  } else {
    for (std::size_t p = 0; p < points; ++p) {
      // Mean over the samples the point covers (a box filter before decimating).
      const auto a = static_cast<std::size_t>(static_cast<double>(p) * samples_per_point);
      const auto b = std::min(
          n, std::max(a + 1,
                      static_cast<std::size_t>(static_cast<double>(p + 1) * samples_per_point)));
      double sum = 0.0;
      for (std::size_t i = std::min(a, n - 1); i < b; ++i) sum += clip.samples[i];
      values[p] = sum / static_cast<double>(std::max<std::size_t>(1, b - std::min(a, n - 1)));
    }
  }
  const auto [lo_it, hi_it] = std::minmax_element(values.begin(), values.end());
  const double lo = o.shape == ProfileShape::kEnvelope ? 0.0 : *lo_it;
  const double range = *hi_it - lo;
  std::pmr::vector<float> heights(points, 0.0f);
  if (range > 1e-12) {
    for (std::size_t p = 0; p < points; ++p) {
      heights[p] = static_cast<float>((values[p] - lo) / range * o.amplitude_mm * 1e-3);
    }
  }
  return HeightField(static_cast<int>(points), 1, o.pitch_mm * 1e-3, std::move(heights));
}

HeightField VibrationProfileFromCsv(const std::string& text, const std::string& name,
                                    const VibrationOptions& o) {
  if (!(o.csv_pitch_mm > 0.0)) throw std::invalid_argument("VibrationProfileFromCsv: bad pitch");
  std::vector<double> positions, heights;
  int columns = 0;
  std::size_t line_no = 0;
  std::istringstream in(text);
  std::string line;
  bool skipped_header = false;
  while (std::getline(in, line)) {
    ++line_no;
    std::string_view view(line);
    while (!view.empty() && (view.back() == '\r' || view.back() == ' ')) view.remove_suffix(1);
    if (view.empty() || view.front() == '#') continue;
    const auto comma = view.find(',');
    const int here = comma == std::string_view::npos ? 1 : 2;
    double a = 0.0, b = 0.0;
    const bool ok = here == 1 ? ParseDouble(view, a)
                              : (ParseDouble(view.substr(0, comma), a) &&
                                 ParseDouble(view.substr(comma + 1), b));
    if (!ok) {
      if (!skipped_header && positions.empty() && heights.empty()) {
        skipped_header = true;  // a column-name line
        continue;
      }
      CsvFail(name, line_no, "expected 'height_mm' or 'position_mm,height_mm' numbers");
    }
    if (columns == 0) columns = here;
    if (here != columns) CsvFail(name, line_no, "column count changes within the file");
    if (here == 2) {
      if (!positions.empty() && !(a > positions.back())) {
        CsvFail(name, line_no, "positions must increase strictly");
      }
      positions.push_back(a);
      heights.push_back(b);
    } else {
      heights.push_back(a);
    }
    if (heights.size() > o.max_points) CsvFail(name, line_no, "too many points");
  }
  if (heights.size() < 2) CsvFail(name, line_no, "a profile needs at least two points");
  if (std::any_of(heights.begin(), heights.end(), [](double h) { return std::fabs(h) > 1000.0; })) {
    CsvFail(name, line_no, "heights beyond ±1000 mm are not a surface scan");
  }
  if (columns == 1) {
    positions.resize(heights.size());
    for (std::size_t i = 0; i < heights.size(); ++i)
      positions[i] = static_cast<double>(i) * o.csv_pitch_mm;
  }
  const double length = positions.back() - positions.front();
  const auto points = static_cast<std::size_t>(std::floor(length / o.csv_pitch_mm + 1e-9)) + 1;
  if (points > o.max_points) CsvFail(name, line_no, "profile too long for the pitch");
  std::pmr::vector<float> out(points);
  std::size_t seg = 0;
  for (std::size_t p = 0; p < points; ++p) {
    const double x = positions.front() + static_cast<double>(p) * o.csv_pitch_mm;
    while (seg + 2 < positions.size() && positions[seg + 1] < x) ++seg;
    const double t =
        std::clamp((x - positions[seg]) / (positions[seg + 1] - positions[seg]), 0.0, 1.0);
    out[p] = static_cast<float>((heights[seg] + t * (heights[seg + 1] - heights[seg])) * 1e-3);
  }
  return HeightField(static_cast<int>(points), 1, o.csv_pitch_mm * 1e-3, std::move(out));
}

HeightField VibrationProfileFromFile(const std::string& path, const VibrationOptions& o) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".csv") {
    const auto bytes = ReadFileBytes(path, 512ULL << 20);
    return VibrationProfileFromCsv(std::string(bytes.begin(), bytes.end()), path, o);
  }
  const AudioClip clip = ReadAudioFile(path, o.audio_limits);
  return SoundToProfile(clip, o.sound);
}

}  // namespace sas::surface
