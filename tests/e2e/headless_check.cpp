// Checks what the headless default wrote, independently of the code that
// wrote it: every texture stroked in every style has a WAV and a PNG; each WAV is clearly audible
// while the pen is down and has decayed to near silence at its end; each snapshot differs from the
// plain picture around the stroke's end point (the dent) and matches it far from it; the voice
// became a grey sound image unlike any texture; the idle reset wiped it.
//   usage: headless_check <output folder>
#include <sndfile.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "dent_difference.h"
#include "tools/command_line.h"
#include "ui/deformation_field.h"
#include "ui/picture_io.h"

namespace {

int failures = 0;

void Fail(const std::string& what) {
  std::printf("FAIL: %s\n", what.c_str());
  ++failures;
}

double Db(double x) {
  return x > 0.0 ? 20.0 * std::log10(x) : -999.0;
}

// RMS of channel 1 between t0 and t1 (seconds).
double RmsCh1(const std::vector<float>& frames, int channels, double fs, double t0, double t1) {
  const auto n = static_cast<long>(frames.size() / static_cast<std::size_t>(channels));
  const long a = std::max(0L, std::lround(t0 * fs));
  const long b = std::min(n, std::lround(t1 * fs));
  double sum = 0.0;
  for (long i = a; i < b; ++i) {
    const double v = frames[static_cast<std::size_t>(i * channels)];
    sum += v * v;
  }
  return b > a ? std::sqrt(sum / static_cast<double>(b - a)) : 0.0;
}

bool ReadWav(const std::string& path, std::vector<float>* frames, int* channels, double* fs) {
  SF_INFO info{};
  SNDFILE* file = sf_open(path.c_str(), SFM_READ, &info);
  if (file == nullptr) return false;
  frames->resize(static_cast<std::size_t>(info.frames * info.channels));
  sf_readf_float(file, frames->data(), info.frames);
  sf_close(file);
  *channels = info.channels;
  *fs = info.samplerate;
  return true;
}

// Mean absolute RGB difference near (cx, cy) and far from it (dent_difference.h).
void Differences(const sas::ui::ImageRgba& a, const sas::ui::ImageRgba& b, int cx, int cy,
                 double* near_mean, double* far_mean) {
  // The bottom eighth may hold a banner (the texture's name as a visit starts, a message), which
  // the visitor sees on the snapshot too.
  const auto d = sas::test::MeasureDent(a, b, cx, cy, sas::ui::DeformationConfig{}.radius_px,
                                        a.height() - a.height() / 8);
  *near_mean = d.near_mean;
  *far_mean = d.far_mean;
}

std::map<std::string, std::string> Fields(const std::string& line) {
  std::map<std::string, std::string> fields;
  std::istringstream in(line);
  std::string word;
  while (in >> word) {
    const auto eq = word.find('=');
    if (eq != std::string::npos) fields[word.substr(0, eq)] = word.substr(eq + 1);
  }
  return fields;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Checks what the headless default wrote: every stroke's WAV and PNG, the voice's "
      "sound image, the pop, the idle reset.",
      "headless_check"};
  std::string dir;
  app.add_option("folder", dir, "the headless run's output folder")->required();
  if (const int code = sas::kiosk::ParseProgramCommandLine(app, argc, argv); code >= 0) return code;
  std::ifstream visit(dir + "/visit.txt");
  if (!visit) {
    Fail("no visit.txt in " + dir);
    return 1;
  }
  std::map<std::string, std::map<std::string, std::string>> strokes;
  std::string idle_line;
  std::string pop_line;
  std::map<std::string, std::map<std::string, std::string>> spreads;
  for (std::string line; std::getline(visit, line);) {
    std::istringstream in(line);
    std::string kind, name;
    in >> kind >> name;
    if (kind == "stroke") strokes[name] = Fields(line);
    if (kind == "idle_reset") idle_line = line;
    if (kind == "pop") pop_line = line;
    if (kind == "spread") spreads[name] = Fields(line);
  }
  const std::vector<std::string> textures = {"bubble_wrap", "broken_glass", "wooden_board",
                                             "cracked_ground"};
  std::vector<std::string> expected;
  for (const auto& t : textures) {
    for (const char* style : {"scrape", "rub", "roll"}) expected.push_back(t + "_" + style);
  }
  expected.push_back("bubble_wrap_pop");
  expected.push_back("token_switch");
  expected.push_back("voice_scrape");
  for (const auto& name : expected) {
    const auto found = strokes.find(name);
    if (found == strokes.end()) {
      Fail(name + ": no stroke in visit.txt");
      continue;
    }
    auto& f = found->second;
    std::vector<float> frames;
    int channels = 0;
    double fs = 0.0;
    if (!ReadWav(dir + "/" + f["wav"], &frames, &channels, &fs) || channels != 2) {
      Fail(name + ": cannot read a 2-channel WAV " + f["wav"]);
      continue;
    }
    const double down_s = std::stod(f["down_s"]);
    const double length_s = static_cast<double>(frames.size() / 2) / fs;
    const double stroke = RmsCh1(frames, 2, fs, 0.1, down_s);
    const double after = RmsCh1(frames, 2, fs, down_s + 0.05, down_s + 0.15);
    const double end = RmsCh1(frames, 2, fs, length_s - 0.1, length_s);
    std::printf("%-22s stroke %6.1f dBFS, just after release %6.1f, last 100 ms %6.1f",
                name.c_str(), Db(stroke), Db(after), Db(end));
    if (Db(stroke) < -80.0) Fail(name + ": silent while the pen was down");
    if (Db(end) > Db(stroke) - 20.0 || Db(end) > -45.0) Fail(name + ": no decay after release");
    if (end > after && after > 0.0) Fail(name + ": louder at the end than just after release");
    try {
      const auto shot = sas::ui::LoadPicture(dir + "/" + f["png"]);
      const auto plain = sas::ui::LoadPicture(dir + "/" + f["plain"]);
      double near_mean = 0, far_mean = 0;
      Differences(shot, plain, std::stoi(f["x"]), std::stoi(f["y"]), &near_mean, &far_mean);
      std::printf(" | dent: near %.1f far %.2f\n", near_mean, far_mean);
      if (near_mean < 4.0) Fail(name + ": the snapshot shows no dent at the stroke's end");
      if (far_mean > 1.0) Fail(name + ": the snapshot differs from the picture far from the pen");
    } catch (const std::exception& e) {
      std::printf("\n");
      Fail(name + ": " + e.what());
    }
  }
  // The voice became its sound image: grey, and unlike every texture picture.
  try {
    const auto voice = sas::ui::LoadPicture(dir + "/voice_surface.png");
    bool grey = true;
    for (int y = 0; y < voice.height(); y += 7) {
      for (int x = 0; x < voice.width(); x += 7) {
        const auto p = voice.at(x, y);
        grey = grey && p.r == p.g && p.g == p.b;
      }
    }
    if (!grey) Fail("voice_surface.png is not a grey sound image");
    for (const auto& t : textures) {
      const auto picture = sas::ui::LoadPicture(dir + "/" + t + ".png");
      double near_mean = 0, far_mean = 0;
      Differences(voice, picture, -10000, -10000, &near_mean, &far_mean);
      if (far_mean < 10.0) Fail("voice_surface.png looks like " + t + ".png");
    }
  } catch (const std::exception& e) {
    Fail(std::string("voice surface: ") + e.what());
  }
  // A firm press popped the bubble under the pen: the picture shows it flattened afterwards.
  {
    auto f = Fields(pop_line);
    if (f["popped"].empty() || std::stoi(f["popped"]) < 1) {
      Fail("the firm press popped no bubble");
    } else {
      try {
        const auto popped = sas::ui::LoadPicture(dir + "/bubble_wrap_popped.png");
        const auto intact = sas::ui::LoadPicture(dir + "/bubble_wrap_intact.png");
        double near_mean = 0, far_mean = 0;
        Differences(popped, intact, std::stoi(f["x"]), std::stoi(f["y"]), &near_mean, &far_mean);
        std::printf("pop: %s bubble(s), picture near %.1f far %.2f\n", f["popped"].c_str(),
                    near_mean, far_mean);
        if (near_mean < 4.0) Fail("the popped bubble does not show in the picture");
        if (far_mean > 1.0) Fail("the pop changed the picture far from the bubble");
      } catch (const std::exception& e) {
        Fail(std::string("pop: ") + e.what());
      }
    }
  }
  // The same strokes on the four textures sound alike: each style's loudness within 3 LU across
  // them (the level matching, levels/stroke_gain.h).
  for (const char* style : {"scrape", "rub", "roll"}) {
    const auto found = spreads.find(style);
    if (found == spreads.end() || found->second["loudness_lu"].empty()) {
      Fail(std::string("no loudness spread for ") + style + " in visit.txt");
      continue;
    }
    const double lu = std::stod(found->second["loudness_lu"]);
    std::printf("%s: the same strokes on the textures within %.2f LU\n", style, lu);
    if (!(lu <= 3.0)) Fail(std::string(style) + ": the textures' loudness spreads over 3 LU");
  }
  if (idle_line.find("voice_wiped=yes") == std::string::npos)
    Fail("idle reset did not wipe the voice");
  std::printf(failures == 0 ? "PASS\n" : "%d failures\n", failures);
  return failures == 0 ? 0 : 1;
}
