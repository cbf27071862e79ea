// Helpers for the kiosk's end-to-end test under Xvfb (kiosk_xvfb_e2e.sh), independent of the
// kiosk's own code paths except for reading files:
//   pace ...            real-time audio through ALSA's file plugin (below)
//   speech IN.wav OUT.f32        a WAV (espeak-ng) as float32 mono 48 kHz at a -6 dBFS peak
//   audio OUT.raw DOWN UP        the played stream (float32 stereo) between byte offsets DOWN
//                                and UP (the drag) is audible, and its end has decayed to silence
//   level OUT.raw CH FROM TO MIN MAX   the RMS of channel CH (1 sound, 2 vibration) between byte
//                                offsets FROM and TO of the played stream, in dBFS, is within
//                                [MIN, MAX] (exit 1 when not)
//   matches SHOT.png PICTURE     the screenshot shows PICTURE fitted to the screen (pixel check)
//   dent SHOT.png PICTURE X Y    the dent at (X, Y) and the picture elsewhere
//   voice SHOT.png               the screenshot is a sound image: grey, silent rows mid-grey,
//                                some rows carrying sound
//   find SPEECH.f32 FILE...      exit 1 when any FILE contains a stretch of the speech samples
//   amber SHOT.png               prints how many pixels have the staff panel's warning amber
//                                (a lost device's line, the panel's title)
//
// pace: real-time pacing for ALSA's file plugin. The plugin neither plays
// nor captures in real time (measured: 0.5 s "plays" in ~1 ms), so the test points
// its `file` and `infile` at two FIFOs and this program sits on the other ends:
//   playback: reads the kiosk's float32 stereo stream from <out_fifo> at 48 kHz real time and
//             appends it to <out.raw> (so the file's size tells the test which sample is playing);
//   capture:  writes float32 mono at 48 kHz real time into <in_fifo>: silence, and once
//             <trigger_file> exists, the samples of <speech.f32> once, then silence again.
// Either side reopens its FIFO when the kiosk closes and reopens the device (PortAudio probes).
//   usage: kiosk_e2e_tool pace <out_fifo> <out.raw> <in_fifo> <speech.f32> <trigger_file>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "dent_difference.h"
#include "surface/audio_file.h"
#include "tools/command_line.h"
#include "ui/picture_io.h"

namespace {

constexpr double kRateHz = 48000.0;
using Clock = std::chrono::steady_clock;

void Playback(const std::string& fifo, const std::string& out_path) {
  std::FILE* out = std::fopen(out_path.c_str(), "wb");
  if (out == nullptr) return;
  std::vector<char> buffer(1920 * 8);  // 40 ms of stereo float
  for (;;) {
    const int fd = open(fifo.c_str(), O_RDONLY);
    if (fd < 0) return;
    fcntl(fd, F_SETPIPE_SZ, 4096);  // keep the pipe's own buffering small
    const auto start = Clock::now();
    double bytes = 0.0;
    for (;;) {
      const ssize_t n = read(fd, buffer.data(), buffer.size());
      if (n <= 0) break;  // the writer closed: wait for the next open
      std::fwrite(buffer.data(), 1, static_cast<std::size_t>(n), out);
      std::fflush(out);
      bytes += static_cast<double>(n);
      const double due_s = bytes / (kRateHz * 2 * sizeof(float));
      std::this_thread::sleep_until(start + std::chrono::duration<double>(due_s));
    }
    close(fd);
  }
}

void Capture(const std::string& fifo, const std::string& speech_path, const std::string& trigger) {
  std::vector<float> speech;
  {
    std::ifstream in(speech_path, std::ios::binary | std::ios::ate);
    if (in) {
      speech.resize(static_cast<std::size_t>(in.tellg()) / sizeof(float));
      in.seekg(0);
      in.read(reinterpret_cast<char*>(speech.data()),
              static_cast<std::streamsize>(speech.size() * sizeof(float)));
    }
  }
  std::size_t speech_pos = 0;
  bool speaking = false;
  std::vector<float> block(480);  // 10 ms
  for (;;) {
    const int fd = open(fifo.c_str(), O_WRONLY);
    if (fd < 0) return;
    fcntl(fd, F_SETPIPE_SZ, 4096);
    const auto start = Clock::now();
    double frames = 0.0;
    for (;;) {
      if (!speaking && speech_pos == 0 && access(trigger.c_str(), F_OK) == 0) speaking = true;
      std::fill(block.begin(), block.end(), 0.0f);
      if (speaking) {
        const std::size_t n = std::min(block.size(), speech.size() - speech_pos);
        std::copy_n(speech.begin() + static_cast<std::ptrdiff_t>(speech_pos), n, block.begin());
        speech_pos += n;
        if (speech_pos >= speech.size()) speaking = false;
      }
      const ssize_t n = write(fd, block.data(), block.size() * sizeof(float));
      if (n <= 0) break;  // the reader closed
      frames += static_cast<double>(block.size());
      std::this_thread::sleep_until(start + std::chrono::duration<double>(frames / kRateHz));
    }
    close(fd);
  }
}

std::vector<float> ReadF32(const std::string& path) {
  std::vector<float> data;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return data;
  data.resize(static_cast<std::size_t>(in.tellg()) / sizeof(float));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size() * 4));
  return data;
}

double Db(double x) {
  return x > 0.0 ? 20.0 * std::log10(x) : -999.0;
}

int Speech(const std::string& wav, const std::string& out) {
  const auto clip = sas::surface::ReadAudioFile(wav);
  std::vector<float> samples = clip.samples;
  const float peak = clip.peak > 0.0f ? clip.peak : 1.0f;
  for (auto& s : samples) s *= 0.5f / peak;
  std::ofstream f(out, std::ios::binary);
  f.write(reinterpret_cast<const char*>(samples.data()),
          static_cast<std::streamsize>(samples.size() * sizeof(float)));
  std::printf("speech: %.2f s\n", static_cast<double>(samples.size()) / kRateHz);
  return 0;
}

// RMS of channel 1 over frames [a, b).
double Rms(const std::vector<float>& stereo, std::size_t a, std::size_t b) {
  b = std::min(b, stereo.size() / 2);
  double sum = 0.0;
  for (std::size_t i = a; i < b; ++i) sum += static_cast<double>(stereo[2 * i]) * stereo[2 * i];
  return b > a ? std::sqrt(sum / static_cast<double>(b - a)) : 0.0;
}

int Audio(const std::string& raw, long down_bytes, long up_bytes) {
  const auto stereo = ReadF32(raw);
  const std::size_t frames = stereo.size() / 2;
  const auto down = static_cast<std::size_t>(down_bytes / 8),
             up = static_cast<std::size_t>(up_bytes / 8);
  // The stream runs ahead of what the pacer has written by a few buffers: allow 0.3 s.
  const auto slack = static_cast<std::size_t>(0.3 * kRateHz);
  const double during = Rms(stereo, down, up + slack);
  const double end =
      Rms(stereo, frames - std::min(frames, static_cast<std::size_t>(0.2 * kRateHz)), frames);
  std::printf(
      "audio: %.2f s played, drag %.2f..%.2f s: %.1f dBFS rms; last 200 ms %.1f dBFS (ends %.2f s "
      "after release)\n",
      static_cast<double>(frames) / kRateHz, static_cast<double>(down) / kRateHz,
      static_cast<double>(up) / kRateHz, Db(during), Db(end),
      static_cast<double>(frames - std::min(frames, up)) / kRateHz);
  if (frames < up + static_cast<std::size_t>(1.0 * kRateHz)) {
    std::printf("FAIL: less than 1 s played after the release\n");
    return 1;
  }
  if (Db(during) < -70.0) {
    std::printf("FAIL: silent during the drag\n");
    return 1;
  }
  if (Db(end) > -70.0 && Db(end) > Db(during) - 30.0) {
    std::printf("FAIL: not decayed to silence after the release\n");
    return 1;
  }
  return 0;
}

int Level(const std::string& raw, int channel, long from_bytes, long to_bytes, double min_db,
          double max_db) {
  const auto stereo = ReadF32(raw);
  const std::size_t frames = stereo.size() / 2;
  const auto a = static_cast<std::size_t>(std::max(0L, from_bytes) / 8);
  const auto b = std::min(frames, static_cast<std::size_t>(std::max(0L, to_bytes) / 8));
  double sum = 0.0;
  for (std::size_t i = a; i < b; ++i) {
    const double x = stereo[2 * i + static_cast<std::size_t>(channel == 2)];
    sum += x * x;
  }
  const double db = b > a ? Db(std::sqrt(sum / static_cast<double>(b - a))) : -999.0;
  std::printf("level: channel %d, %.2f..%.2f s: %.1f dBFS rms (wanted %.0f..%.0f)\n", channel,
              static_cast<double>(a) / kRateHz, static_cast<double>(b) / kRateHz, db, min_db,
              max_db);
  return b > a && db >= min_db && db <= max_db ? 0 : 1;
}

double MeanDiff(const sas::ui::ImageRgba& a, const sas::ui::ImageRgba& b) {
  double sum = 0.0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      const auto p = a.at(x, y), q = b.at(x, y);
      sum += (std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b)) / 3.0;
    }
  }
  return sum / (static_cast<double>(a.width()) * a.height());
}

int Matches(const std::string& shot_path, const std::vector<std::string>& pictures) {
  const auto shot = sas::ui::LoadPicture(shot_path);
  double own = 0.0;
  for (std::size_t i = 0; i < pictures.size(); ++i) {
    const auto picture =
        sas::ui::ResizeToCover(sas::ui::LoadPicture(pictures[i]), shot.width(), shot.height());
    const double d = MeanDiff(shot, picture);
    std::printf("matches: %s mean difference %.2f\n", pictures[i].c_str(), d);
    if (i == 0) own = d;
    // Decided before the other pictures are loaded: the tests retry screenshots with this check
    // until the screen shows the picture, and a busy machine takes seconds per picture.
    if (i == 0 && own > 4.0) {
      std::printf("FAIL: the screen does not show %s\n", pictures[0].c_str());
      return 1;
    }
    if (i > 0 && d < own + 10.0) {
      std::printf("FAIL: the screenshot is as close to %s\n", pictures[i].c_str());
      return 1;
    }
  }
  return 0;
}

// The dent: pixels within 0.8 R of (cx, cy) differ clearly from the fitted picture, pixels beyond
// 3 R do not (R = the deformation's default radius, 56 px; dent_difference.h).
int Dent(const std::string& shot_path, const std::string& picture_path, int cx, int cy) {
  const auto shot = sas::ui::LoadPicture(shot_path);
  const auto picture =
      sas::ui::ResizeToCover(sas::ui::LoadPicture(picture_path), shot.width(), shot.height());
  const auto dent = sas::test::MeasureDent(shot, picture, cx, cy);
  const double near_mean = dent.near_mean, far_mean = dent.far_mean;
  std::printf("dent: near mean difference %.2f, far %.3f\n", near_mean, far_mean);
  return near_mean > 6.0 && far_mean < 2.0 ? 0 : 1;
}

int Voice(const std::string& shot_path) {
  const auto shot = sas::ui::LoadPicture(shot_path);
  int grey_violations = 0, flat_rows = 0, busy_rows = 0, rows = 0;
  // The bottom eighth holds the "now scratch your voice" banner for its first seconds.
  for (int y = 0; y < shot.height() - shot.height() / 8; y += 4) {
    double sum = 0.0, sum_sq = 0.0;
    for (int x = 0; x < shot.width(); ++x) {
      const auto p = shot.at(x, y);
      if (std::abs(p.r - p.g) > 2 || std::abs(p.g - p.b) > 2) ++grey_violations;
      sum += p.r;
      sum_sq += static_cast<double>(p.r) * p.r;
    }
    const double mean = sum / shot.width();
    const double sd = std::sqrt(std::max(0.0, sum_sq / shot.width() - mean * mean));
    ++rows;
    if (sd < 2.0 && std::abs(mean - 128.0) < 3.0) ++flat_rows;  // silence is mid-grey
    if (sd > 8.0) ++busy_rows;
  }
  std::printf(
      "voice: %d rows sampled, %d silent (mid-grey), %d carrying sound, %d non-grey pixels\n", rows,
      flat_rows, busy_rows, grey_violations);
  if (grey_violations > shot.width()) return std::printf("FAIL: not a grey sound image\n"), 1;
  // The kiosk cuts the silence around the speech and shortens its pauses: the speech fills the
  // picture, though the take holds silence before and after the speech.
  if (busy_rows < rows / 2) return std::printf("FAIL: the speech does not fill the image\n"), 1;
  if (flat_rows > rows / 4)
    return std::printf("FAIL: a quarter of the image or more is silence (not trimmed)\n"), 1;
  return 0;
}

int Find(const std::string& speech_path, const std::vector<std::string>& files) {
  const auto speech = ReadF32(speech_path);
  if (speech.size() < 4096) return 2;
  // 64 consecutive samples from the loudest part of the speech: bytes no other file holds.
  std::size_t at = 0;
  float peak = 0.0f;
  for (std::size_t i = 0; i + 64 < speech.size(); ++i) {
    if (std::abs(speech[i]) > peak) {
      peak = std::abs(speech[i]);
      at = i;
    }
  }
  const std::string needle(reinterpret_cast<const char*>(speech.data() + at), 64 * sizeof(float));
  int found = 0;
  for (const auto& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::string content((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
    if (content.find(needle) != std::string::npos) {
      std::printf("FAIL: %s holds the visitor's voice\n", file.c_str());
      ++found;
    }
  }
  std::printf("find: %zu files searched, %d hold the voice\n", files.size(), found);
  return found == 0 ? 0 : 1;
}

// The staff panel's amber (about 250, 190, 60), with room for the panel's blending.
int Amber(const std::string& shot_path) {
  const auto shot = sas::ui::LoadPicture(shot_path);
  long count = 0;
  for (int y = 0; y < shot.height(); ++y) {
    for (int x = 0; x < shot.width(); ++x) {
      const auto p = shot.at(x, y);
      if (std::abs(p.r - 250) < 30 && std::abs(p.g - 190) < 30 && std::abs(p.b - 60) < 40) ++count;
    }
  }
  std::printf("%ld\n", count);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Helpers for the kiosk's end-to-end test under Xvfb (kiosk_xvfb_e2e.sh).",
               "kiosk_e2e_tool"};
  app.require_subcommand(1);
  std::string shot, picture, in, out, speech, trigger, out_fifo, out_raw, in_fifo;
  std::vector<std::string> files;
  long down = 0, up = 0;
  int x = 0, y = 0;
  CLI::App* pace = app.add_subcommand(
      "pace",
      "real-time pacing of ALSA's file plugin: plays OUT_FIFO into OUT.raw, captures "
      "SPEECH.f32 into IN_FIFO once TRIGGER exists");
  pace->add_option("out_fifo", out_fifo, "the kiosk's playback FIFO")->required();
  pace->add_option("out_raw", out_raw, "where the played stream is appended")->required();
  pace->add_option("in_fifo", in_fifo, "the kiosk's capture FIFO")->required();
  pace->add_option("speech", speech, "float32 mono 48 kHz speech")->required();
  pace->add_option("trigger", trigger, "file whose existence starts the speech")->required();
  CLI::App* speech_cmd =
      app.add_subcommand("speech", "a WAV as float32 mono 48 kHz at a -6 dBFS peak");
  speech_cmd->add_option("in", in, "the WAV")->required();
  speech_cmd->add_option("out", out, "the .f32 to write")->required();
  CLI::App* audio = app.add_subcommand(
      "audio", "the played stream between byte offsets DOWN and UP is audible, its end decayed");
  audio->add_option("raw", in, "float32 stereo stream")->required();
  audio->add_option("down", down, "byte offset of the pen down")->required();
  audio->add_option("up", up, "byte offset of the pen up")->required();
  CLI::App* matches = app.add_subcommand(
      "matches", "the screenshot shows one of the PICTUREs fitted to the screen");
  matches->add_option("shot", shot, "the screenshot (PNG)")->required();
  matches->add_option("pictures", files, "the pictures")->required();
  CLI::App* dent = app.add_subcommand("dent", "the dent at (X, Y) and the picture elsewhere");
  dent->add_option("shot", shot, "the screenshot (PNG)")->required();
  dent->add_option("picture", picture, "the picture")->required();
  dent->add_option("x", x, "dent centre, px")->required();
  dent->add_option("y", y, "dent centre, px")->required();
  CLI::App* voice = app.add_subcommand(
      "voice", "the screenshot is a sound image: grey, the speech filling it (few silent mid-grey rows)");
  voice->add_option("shot", shot, "the screenshot (PNG)")->required();
  CLI::App* find =
      app.add_subcommand("find", "exit 1 when any FILE contains a stretch of the speech samples");
  find->add_option("speech", speech, "float32 speech samples")->required();
  find->add_option("files", files, "the files to search");
  int channel = 1;
  double min_db = 0.0, max_db = 0.0;
  CLI::App* level = app.add_subcommand(
      "level", "the RMS level of CHANNEL (1 or 2) between byte offsets FROM and TO lies in "
               "[MIN_DB, MAX_DB] dBFS");
  level->add_option("raw", in, "float32 stereo stream")->required();
  level->add_option("channel", channel, "1: speaker, 2: transducer")
      ->required()
      ->check(CLI::Range(1, 2));
  level->add_option("from", down, "byte offset where the span starts")->required();
  level->add_option("to", up, "byte offset where it ends")->required();
  level->add_option("min_db", min_db, "lowest level wanted, dBFS")->required();
  level->add_option("max_db", max_db, "highest level wanted, dBFS")->required();
  CLI::App* amber =
      app.add_subcommand("amber", "prints how many pixels have the staff panel's warning amber");
  amber->add_option("shot", shot, "the screenshot (PNG)")->required();
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  try {
    if (speech_cmd->parsed()) return Speech(in, out);
    if (audio->parsed()) return Audio(in, down, up);
    if (matches->parsed()) return Matches(shot, files);
    if (dent->parsed()) return Dent(shot, picture, x, y);
    if (voice->parsed()) return Voice(shot);
    if (find->parsed()) return Find(speech, files);
    if (level->parsed()) return Level(in, channel, down, up, min_db, max_db);
    if (amber->parsed()) return Amber(shot);
  } catch (const std::exception& e) {
    std::printf("FAIL: %s\n", e.what());
    return 1;
  }
  std::signal(SIGPIPE, SIG_IGN);
  std::thread playback(Playback, out_fifo, out_raw);
  std::thread capture(Capture, in_fifo, speech, trigger);
  playback.join();
  capture.join();
  return 0;
}
