// Painting the four kiosk textures: height map first, then the picture rendered from it:
//   height (mm) -> normals at the display's pixel pitch -> Lambert diffuse + Blinn–Phong specular
//   (light from the upper left) x material albedo (colour, grain, fibres) x ambient occlusion
//   (height below its local mean) -> lens vignetting -> photographic grain -> 8-bit BGR.

#include "texture_painting.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "surface/bubble_wrap.h"

namespace sas::textures {

using surface::BubbleLayout;

namespace {

// Band-limited noise: white noise blurred at sigma, normalised to unit standard deviation.
cv::Mat1f BlurredNoise(cv::RNG& rng, const Canvas& c, double sigma_px) {
  cv::Mat1f noise(c.height, c.width);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  if (sigma_px > 0.3)
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), sigma_px, sigma_px, cv::BORDER_REFLECT);
  cv::Scalar mean, dev;
  cv::meanStdDev(noise, mean, dev);
  noise = (noise - mean[0]) / std::max(dev[0], 1e-9);
  return noise;
}

// Noise stretched along x (wood grain runs along the board): blurred with sigma_x >> sigma_y.
cv::Mat1f StretchedNoise(cv::RNG& rng, const Canvas& c, double sigma_x, double sigma_y) {
  cv::Mat1f noise(c.height, c.width);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), sigma_x, sigma_y, cv::BORDER_REFLECT);
  cv::Scalar mean, dev;
  cv::meanStdDev(noise, mean, dev);
  noise = (noise - mean[0]) / std::max(dev[0], 1e-9);
  return noise;
}

// Fractal noise: octaves of blurred noise, each half the size and amplitude of the one before.
cv::Mat1f Fbm(cv::RNG& rng, const Canvas& c, double largest_sigma_px, int octaves) {
  cv::Mat1f sum(c.height, c.width, 0.0f);
  double amplitude = 1.0, sigma = largest_sigma_px, total = 0.0;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * BlurredNoise(rng, c, sigma);
    total += amplitude * amplitude;
    amplitude *= 0.5;
    sigma *= 0.5;
  }
  sum.convertTo(sum, CV_32F, 1.0 / std::sqrt(total));
  return sum;
}

double SmoothStep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

struct Look {
  cv::Vec3f light{-0.55f, -0.62f, 0.56f};  // towards the light: upper left, 34° above the surface
  double ambient = 0.30;
  double diffuse = 0.80;
  double specular = 0.25;
  double shininess = 40.0;
  double occlusion = 0.0;  // darkening per mm below the local mean height
  double occlusion_sigma_px = 12.0;
  double grain = 0.012;  // photographic grain, std of luminance
  double vignette = 0.18;
  double exposure = 1.0;
};

// Renders the picture from the height map (mm) and the albedo (BGR, [0, 1]).
cv::Mat Render(const cv::Mat1f& height_mm, const cv::Mat3f& albedo, const Look& look, cv::RNG& rng,
               const cv::Mat1f* extra_light = nullptr) {
  const int w = height_mm.cols, h = height_mm.rows;
  cv::Mat1f dx, dy;
  cv::Sobel(height_mm, dx, CV_32F, 1, 0, 3, 1.0 / (8.0 * kPitchMm), 0.0, cv::BORDER_REFLECT);
  cv::Sobel(height_mm, dy, CV_32F, 0, 1, 3, 1.0 / (8.0 * kPitchMm), 0.0, cv::BORDER_REFLECT);
  cv::Mat1f local_mean;
  cv::GaussianBlur(height_mm, local_mean, cv::Size(0, 0), look.occlusion_sigma_px);
  const cv::Vec3f l = look.light / cv::norm(look.light);
  const cv::Vec3f half = (l + cv::Vec3f(0, 0, 1)) / cv::norm(l + cv::Vec3f(0, 0, 1));
  cv::Mat3f grain(h, w);
  rng.fill(grain, cv::RNG::NORMAL, 0.0, look.grain);
  cv::Mat1f grain_mono(h, w);
  rng.fill(grain_mono, cv::RNG::NORMAL, 0.0, look.grain);
  cv::Mat out(h, w, CV_8UC3);
  const double cx = w * 0.5, cy = h * 0.5, rmax = std::hypot(cx, cy);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      cv::Vec3f n(-dx(y, x), -dy(y, x), 1.0f);
      n /= cv::norm(n);
      const double lambert = std::max(0.0f, n.dot(l));
      const double spec = std::pow(std::max(0.0f, n.dot(half)), look.shininess);
      const double ao =
          std::exp(-look.occlusion * std::max(0.0f, local_mean(y, x) - height_mm(y, x)));
      const double r = std::hypot(x - cx, y - cy) / rmax;
      const double vignette = 1.0 - look.vignette * r * r;
      const double extra = extra_light != nullptr ? (*extra_light)(y, x) : 0.0;
      cv::Vec3b& px = out.at<cv::Vec3b>(y, x);
      for (int ch = 0; ch < 3; ++ch) {
        double v = albedo(y, x)[ch] * (look.ambient + look.diffuse * lambert) * ao;
        v += look.specular * spec + extra;
        v = v * vignette * look.exposure + grain(y, x)[ch] * 0.5 + grain_mono(y, x);
        px[ch] = cv::saturate_cast<uchar>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
      }
    }
  }
  return out;
}

// What texture.toml says of a texture besides its gains, and the probe a visitor's pen is.
struct TextureText {
  const char* folder;
  const char* name;
  const char* description;
  const char* material;
  double height_scale_mm;
  double relief_mm;
  double probe_width_mm;
  double probe_penetration_mm;
  const char* probe_style;
  double sound_trim_db = 0.0;
  const char* sound_trim_why = "";
  double haptic_trim_db = 0.0;
  const char* haptic_trim_why = "";
};

// A length as the texture files write it: no trailing zeros, but at least one decimal ("4.0").
std::string Mm(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", value);
  std::string s = text;
  while (s.size() > 1 && s.back() == '0' && s[s.size() - 2] != '.') s.pop_back();
  return s;
}

// The texture's files: its height map, its picture and the text of its texture.toml around the
// [gains] table (extra_tail follows the [probe] table).
TextureOut Assemble(const TextureText& t, const cv::Mat1f& height_mm, cv::Mat picture,
                    const std::string& extra_tail = "") {
  TextureOut out;
  out.folder = t.folder;
  out.height_mm = height_mm;
  out.height_scale_mm = t.height_scale_mm;
  out.picture = std::move(picture);
  out.toml = std::string("name = \"") + t.name + "\"\n" + "description = \"" + t.description +
             "\"\n" + "material = \"" + t.material + "\"\n" +
             "picture = \"picture.png\"\nheight_map = \"height.png\"\n" +
             "height_scale_mm = " + Mm(t.height_scale_mm) + "\n" +
             "relief_mm = " + Mm(t.relief_mm) + "\n";
  out.sound_trim_db = t.sound_trim_db;
  out.haptic_trim_db = t.haptic_trim_db;
  out.haptic_trim_why = std::string(t.haptic_trim_why) +
                        "# The haptic trim does the same for the skin-weighted vibration "
                        "(population_levels --strokes 1000\n# --seed 1).\n";
  // Why, then how the value was found (the same for every texture).
  out.sound_trim_why = std::string(t.sound_trim_why) +
                       "# The trim moves the texture after the per-stroke matching so that its "
                       "median over visitor\n# strokes sits at the four textures' mean "
                       "(population_levels --strokes 1000 --seed 1;\n# the test's seed 2026 is "
                       "held out).\n";
  out.toml_tail = "\n[probe]\nwidth_mm = " + Mm(t.probe_width_mm) +
                  "\npenetration_mm = " + Mm(t.probe_penetration_mm) + "\nstyle = \"" +
                  t.probe_style + "\"\n" + extra_tail;
  return out;
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// Bubble wrap: spherical caps on a hexagonal grid over a thin, slightly wrinkled film, lying on a
// dark blue cloth. Transparent plastic: low diffuse, strong highlights, dark refracting rims.
namespace {

BubbleLayout BubbleLayoutFor(const Canvas& c) {
  BubbleLayout layout;
  layout.pitch_px = 176.0 * c.scale;
  layout.radius_px = 72.0 * c.scale;
  layout.origin_x_px = 70.0 * c.scale;
  layout.origin_y_px = 66.0 * c.scale;
  return layout;
}

}  // namespace

TextureOut BubbleWrap(const Canvas& c) {
  cv::RNG rng(0xB0BB1E);
  const BubbleLayout layout = BubbleLayoutFor(c);
  const double cap_mm = 3.2;
  const double film_mm = 0.15;
  // The film: wrinkles of a few µm slope, far below a felt ridge.
  cv::Mat1f h = Fbm(rng, c, 40.0 * c.scale, 3);
  h.convertTo(h, CV_32F, 0.02, film_mm);
  cv::Mat1f rim_shadow(c.height, c.width, 0.0f);
  cv::Mat1f rim_glow(c.height, c.width, 0.0f);
  const double r_mm = layout.radius_px * kPitchMm;
  for (const auto& [bx, by] : layout.Centres(c.width, c.height)) {
    const double cap = cap_mm * (1.0 + 0.06 * rng.uniform(-1.0, 1.0));
    const double sphere_r = (r_mm * r_mm + cap * cap) / (2.0 * cap);
    const int r = static_cast<int>(std::ceil(layout.radius_px * 1.3));
    for (int y = std::max(0, static_cast<int>(by) - r);
         y <= std::min(c.height - 1, static_cast<int>(by) + r); ++y) {
      for (int x = std::max(0, static_cast<int>(bx) - r);
           x <= std::min(c.width - 1, static_cast<int>(bx) + r); ++x) {
        const double d_px = std::hypot(x - bx, y - by);
        const double d = d_px * kPitchMm;
        if (d_px <= layout.radius_px) {
          const double z = std::sqrt(sphere_r * sphere_r - d * d) - (sphere_r - cap);
          h(y, x) = static_cast<float>(std::max<double>(h(y, x), film_mm + z));
        }
        // Light bent by the weld where bubble meets film: a thin dark line on the rim, and a soft
        // bright ring of refracted light inside it.
        const double band =
            std::exp(-std::pow((d_px - layout.radius_px + 1.5 * c.scale) / (1.0 * c.scale), 2.0));
        rim_shadow(y, x) = static_cast<float>(std::max<double>(rim_shadow(y, x), band));
        const double glow =
            0.5 * std::exp(-std::pow((d_px - layout.radius_px * 0.78) / (7.0 * c.scale), 2.0));
        // The dome focuses the window light into a soft caustic on the far (lower right) side.
        const double caustic = 0.9 * std::exp(-(std::pow(x - bx - 0.45 * layout.radius_px, 2.0) +
                                                std::pow(y - by - 0.40 * layout.radius_px, 2.0)) /
                                              (2.0 * std::pow(16.0 * c.scale, 2.0)));
        rim_glow(y, x) = static_cast<float>(std::max<double>(
            rim_glow(y, x), d_px <= layout.radius_px * 0.9 ? std::max(glow, caustic) : 0.0));
      }
    }
  }
  cv::GaussianBlur(h, h, cv::Size(0, 0), 0.6);
  // Albedo: the cloth (dark blue, woven) seen through clear film, the bubbles a little milkier.
  cv::Mat3f albedo(c.height, c.width);
  const cv::Mat1f weave = BlurredNoise(rng, c, 1.2 * c.scale);
  const cv::Mat1f blotch = Fbm(rng, c, 120.0 * c.scale, 3);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const double lift = std::clamp((h(y, x) - film_mm) / cap_mm, 0.0, 1.0);
      const double v = 1.0 + 0.05 * blotch(y, x) + 0.012 * weave(y, x);
      const double dark = 1.0 - 0.8 * rim_shadow(y, x);
      const double milk = 0.08 * lift + 0.30 * rim_glow(y, x);  // scattered light in the plastic
      albedo(y, x) = cv::Vec3f(static_cast<float>((0.40 * v + milk) * dark),
                               static_cast<float>((0.27 * v + milk) * dark),
                               static_cast<float>((0.17 * v + milk * 0.95) * dark));
    }
  }
  const Look look{.light = cv::Vec3f(-0.45f, -0.50f, 0.74f),  // a window high to the upper left
                  .ambient = 0.35,
                  .diffuse = 0.75,
                  .specular = 0.75,
                  .shininess = 160.0,
                  .occlusion = 0.25,
                  .occlusion_sigma_px = 30.0 * c.scale};
  char bubbles[512];
  std::snprintf(bubbles, sizeof bubbles,
                "\n[bubbles]\npop_force_n = 2.5\nlayout = \"hexagonal\"\npitch_px = %.3f\n"
                "radius_px = %.3f\norigin_x_px = %.3f\norigin_y_px = %.3f\n",
                layout.pitch_px, layout.radius_px, layout.origin_x_px, layout.origin_y_px);
  return Assemble({.folder = "bubble_wrap",
                   .name = "bubble wrap",
                   .description = "A sheet of bubble wrap whose air bubbles pop when you press one "
                                  "hard enough.",
                   .material = "bubble_wrap",
                   .height_scale_mm = 4.0,
                   .relief_mm = 0.8,
                   .probe_width_mm = 1.0,
                   .probe_penetration_mm = 0.02,
                   .probe_style = "rub",
                   .sound_trim_db = -0.9,
                   .sound_trim_why = "# Firm strokes pop bubbles, which the calibration grid "
                                     "(below the pop force) never hears.\n",
                   .haptic_trim_db = -1.6,
                   .haptic_trim_why = "# Felt, the visitors' firm strokes over whole bubbles and "
                                      "pops came out 1.6 dB over the mean.\n"},
                  h, Render(h, albedo, look, rng), bubbles);
}

// ---------------------------------------------------------------------------------------------
// Broken glass: a pane hit near its centre. Radial cracks from the impact and concentric cracks
// between them split it into shards; each shard is a plate slightly raised and tilted, and every
// crack is a narrow V-groove. The pane lies over black velvet: dark, with the sky reflected in the
// shards (their tilt picks the brightness) and the fracture faces glinting.
TextureOut BrokenGlass(const Canvas& c) {
  cv::RNG rng(0x61A55);
  cv::Mat1b cracks(c.height, c.width, static_cast<uchar>(0));
  const cv::Point2d impact(c.width * 0.56, c.height * 0.46);
  const int rays = 15;
  std::vector<double> angles;
  for (int i = 0; i < rays; ++i) {
    angles.push_back(2.0 * std::numbers::pi * (i + rng.uniform(-0.3, 0.3)) / rays);
  }
  const double reach = std::hypot(c.width, c.height);
  std::vector<std::vector<cv::Point2d>> ray_points(rays);
  for (int i = 0; i < rays; ++i) {
    double angle = angles[static_cast<std::size_t>(i)];
    cv::Point2d p = impact;
    for (double r = 0.0; r < reach; r += 14.0 * c.scale) {
      angle += rng.uniform(-0.05, 0.05);
      cv::Point2d next = p + 14.0 * c.scale * cv::Point2d(std::cos(angle), std::sin(angle));
      cv::line(cracks, p, next, 255, 1, cv::LINE_8);
      ray_points[static_cast<std::size_t>(i)].push_back(next);
      p = next;
    }
  }
  // Concentric cracks: join neighbouring rays at roughly the same distance, with a sag.
  for (double ring : {70.0, 150.0, 260.0, 400.0, 570.0, 780.0}) {
    for (int i = 0; i < rays; ++i) {
      if (rng.uniform(0.0, 1.0) < 0.2) continue;  // some rings are incomplete
      const auto& a = ray_points[static_cast<std::size_t>(i)];
      const auto& b = ray_points[static_cast<std::size_t>((i + 1) % rays)];
      const auto ia = static_cast<std::size_t>(
          std::min<double>(static_cast<double>(a.size() - 1),
                           ring * rng.uniform(0.85, 1.15) * c.scale / (14.0 * c.scale)));
      const auto ib = static_cast<std::size_t>(
          std::min<double>(static_cast<double>(b.size() - 1),
                           ring * rng.uniform(0.85, 1.15) * c.scale / (14.0 * c.scale)));
      const cv::Point2d mid = (a[ia] + b[ib]) * 0.5;
      const cv::Point2d bulge = mid + (mid - impact) * rng.uniform(0.02, 0.10);
      cv::line(cracks, a[ia], bulge, 255, 1, cv::LINE_8);
      cv::line(cracks, bulge, b[ib], 255, 1, cv::LINE_8);
    }
  }
  // Shards: connected regions between cracks, each a plate with its own offset and tilt.
  cv::Mat1i labels;
  const int count = cv::connectedComponents(255 - cracks, labels, 4, CV_32S);
  std::vector<cv::Vec3d> plates(static_cast<std::size_t>(count));
  for (auto& p : plates) {
    p = cv::Vec3d(rng.uniform(0.0, 0.25), rng.uniform(-0.012, 0.012), rng.uniform(-0.012, 0.012));
  }
  cv::Mat1f h(c.height, c.width, 0.0f);
  cv::Mat1f tilt_shade(c.height, c.width, 0.0f);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const int label = labels(y, x);
      if (label == 0) continue;
      const cv::Vec3d& p = plates[static_cast<std::size_t>(label)];
      h(y, x) = static_cast<float>(
          1.0 + p[0] + (p[1] * (x - c.width / 2) + p[2] * (y - c.height / 2)) * kPitchMm);
      tilt_shade(y, x) = static_cast<float>(p[1] * 30.0 - p[2] * 25.0 + (p[0] - 0.12) * 0.6);
    }
  }
  // Crack pixels take the higher neighbouring plate, then the groove is cut.
  for (int pass = 0; pass < 3; ++pass) {
    cv::Mat1f grown;
    cv::dilate(h, grown, cv::Mat());
    grown.copyTo(h, cracks);
    cv::Mat1f shade_grown;
    cv::dilate(tilt_shade, shade_grown, cv::Mat());
    shade_grown.copyTo(tilt_shade, cracks);
  }
  cv::Mat1f distance;
  cv::distanceTransform(255 - cracks, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat1f groove(c.height, c.width);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const double d = distance(y, x);
      groove(y, x) = static_cast<float>(0.35 * std::exp(-d * d / (2.0 * 1.2 * 1.2)));
    }
  }
  h -= groove;
  cv::GaussianBlur(h, h, cv::Size(0, 0), 0.7);
  const cv::Mat1f haze = Fbm(rng, c, 200.0 * c.scale, 3);
  const cv::Mat1f sparkle = Fbm(rng, c, 25.0 * c.scale, 2);
  cv::Mat3f albedo(c.height, c.width);
  cv::Mat1f glint(c.height, c.width);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const double sky =
          0.10 + 0.05 * haze(y, x) + std::clamp<double>(tilt_shade(y, x), -0.08, 0.2);
      albedo(y, x) = cv::Vec3f(static_cast<float>(sky * 1.15), static_cast<float>(sky * 1.05),
                               static_cast<float>(sky * 0.95));
      glint(y, x) = static_cast<float>(
          (0.38 + 0.18 * std::clamp<double>(sparkle(y, x), -1.0, 2.0)) * groove(y, x) / 0.35);
    }
  }
  const Look look{.ambient = 1.0,
                  .diffuse = 0.9,
                  .specular = 0.9,
                  .shininess = 25.0,
                  .grain = 0.010,
                  .vignette = 0.3};
  return Assemble({.folder = "broken_glass",
                   .name = "broken glass",
                   .description = "A shattered pane of glass, sharp cracks running out from where "
                                  "it was struck.",
                   .material = "glass",
                   .height_scale_mm = 2.0,
                   .relief_mm = 0.3,
                   .probe_width_mm = 0.3,
                   .probe_penetration_mm = 0.01,
                   .probe_style = "scrape",
                   .sound_trim_db = -0.4,
                   .sound_trim_why = "# The grid's strokes are not the visitors' (longer, lighter "
                                     "and firmer, slower and faster) and leave out the landing:\n"
                                     "# over the visitors' whole strokes its median came out "
                                     "0.4 LU over the mean.\n",
                   .haptic_trim_db = -0.9,
                   .haptic_trim_why = "# Felt, the cracks the visitors' strokes cross left them "
                                      "0.9 dB over the mean.\n"},
                  h, Render(h, albedo, look, rng, &glint));
}

// ---------------------------------------------------------------------------------------------
// Wooden board: a wire-brushed oak plank. Growth rings run along the board (x), bent around a
// knot; the hard latewood of each ring stands proud of the brushed-out earlywood, so the dark
// rings are also the ridges. A seam between two planks crosses the picture.
TextureOut WoodenBoard(const Canvas& c) {
  cv::RNG rng(0x000D);
  const cv::Mat1f warp = StretchedNoise(rng, c, 380.0 * c.scale, 70.0 * c.scale);
  const cv::Mat1f fine = StretchedNoise(rng, c, 220.0 * c.scale, 9.0 * c.scale);
  cv::Mat1f fibres;
  {
    cv::Mat1f n(c.height, c.width);
    rng.fill(n, cv::RNG::NORMAL, 0.0, 1.0);
    cv::GaussianBlur(n, fibres, cv::Size(0, 0), 14.0 * c.scale, 0.8 * c.scale);
    cv::Scalar m, s;
    cv::meanStdDev(fibres, m, s);
    fibres = (fibres - m[0]) / s[0];
  }
  const cv::Point2d knot(c.width * 0.68, c.height * 0.36);
  const double knot_r = 60.0 * c.scale;
  const double seam_y = c.height * 0.80;
  const double ring_px = 26.0 * c.scale;
  cv::Mat1f h(c.height, c.width);
  cv::Mat1f ring_dark(c.height, c.width);
  cv::Mat1f knot_core(c.height, c.width);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      // Ring coordinate: distance across the grain, pushed aside by the knot.
      const double kx = (x - knot.x) / 2.6, ky = y - knot.y;
      const double kd = std::hypot(kx, ky);
      double u = y + 60.0 * c.scale * warp(y, x);
      u += (ky >= 0 ? 1.0 : -1.0) * 90.0 * c.scale * std::exp(-kd / (2.2 * knot_r));
      double phase;
      if (kd < knot_r * 1.4) {  // inside the knot the rings close around its centre
        const double blend = SmoothStep(knot_r * 1.1, knot_r * 0.95, kd);
        phase = (1.0 - blend) * (u / ring_px + 0.3 * fine(y, x)) + blend * (kd / (ring_px * 0.55));
      } else {
        phase = u / ring_px + 0.3 * fine(y, x);
      }
      knot_core(y, x) = static_cast<float>(SmoothStep(knot_r * 1.1, knot_r * 0.4, kd));
      const double f = phase - std::floor(phase);
      // Latewood band: f in [0.62, 0.86], raised 0.12 mm with edges about 1.5 px wide.
      const double edge = 1.4 / ring_px;
      const double late =
          SmoothStep(0.62 - edge, 0.62 + edge, f) * (1.0 - SmoothStep(0.86 - edge, 0.86 + edge, f));
      double z = 0.5 + 0.12 * late + 0.004 * fibres(y, x);
      // The seam: a V-gap 1.2 mm deep between the planks.
      const double ds = std::fabs(y - seam_y);
      z -= 1.2 * (1.0 - SmoothStep(1.0 * c.scale, 5.0 * c.scale, ds));
      h(y, x) = static_cast<float>(z);
      ring_dark(y, x) = static_cast<float>(late);
    }
  }
  cv::Mat3f albedo(c.height, c.width);
  const cv::Mat1f stain = Fbm(rng, c, 90.0 * c.scale, 3);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const double v = (1.0 + 0.06 * stain(y, x)) * (1.0 + 0.012 * fibres(y, x));
      const double late = ring_dark(y, x);
      const bool lower = y > seam_y;  // the second plank is a shade darker
      const double plank = (lower ? 0.9 : 1.0) * (1.0 - 0.35 * knot_core(y, x));
      albedo(y, x) = cv::Vec3f(static_cast<float>((0.30 - 0.10 * late) * v * plank),
                               static_cast<float>((0.50 - 0.15 * late) * v * plank),
                               static_cast<float>((0.72 - 0.18 * late) * v * plank));
    }
  }
  const Look look{.ambient = 0.40,
                  .diffuse = 0.75,
                  .specular = 0.12,
                  .shininess = 20.0,
                  .occlusion = 0.8,
                  .occlusion_sigma_px = 8.0 * c.scale};
  return Assemble({.folder = "wooden_board",
                   .name = "wooden board",
                   .description = "A brushed oak board whose hard grain lines stand up from the "
                                  "softer wood around a knot.",
                   .material = "wood",
                   .height_scale_mm = 1.0,
                   .relief_mm = 0.15,
                   .probe_width_mm = 0.6,
                   .probe_penetration_mm = 0.01,
                   .probe_style = "scrape",
                   .sound_trim_db = -1.1,
                   .sound_trim_why = "# The grid's strokes leave out the landing, which rings the "
                                     "board's low modes:\n# over the visitors' whole strokes its "
                                     "median came out 1.1 LU over the mean.\n",
                   .haptic_trim_db = -1.3,
                   .haptic_trim_why = "# Felt, the board's low modes ringing under the grain "
                                      "lines leave the visitors' strokes 1.3 dB over the mean.\n"},
                  h, Render(h, albedo, look, rng));
}

// ---------------------------------------------------------------------------------------------
// Cracked ground: dried mud split into polygonal plates (a warped Voronoi tessellation) whose
// edges curl up; cracks are deep steep-walled trenches, their floors in shadow.
TextureOut CrackedGround(const Canvas& c) {
  cv::RNG rng(0x50111);
  const cv::Mat1f warp_x = Fbm(rng, c, 50.0 * c.scale, 3);
  const cv::Mat1f warp_y = Fbm(rng, c, 50.0 * c.scale, 3);
  const cv::Mat1f rough = Fbm(rng, c, 6.0 * c.scale, 2);
  // Jittered grid of plate centres; the grid keeps the nearest-seed search to 3x3 cells.
  const double cell = 150.0 * c.scale;
  const int gx = static_cast<int>(std::ceil(c.width / cell)) + 2;
  const int gy = static_cast<int>(std::ceil(c.height / cell)) + 2;
  std::vector<cv::Point2d> seeds(static_cast<std::size_t>(gx * gy));
  std::vector<double> crack_width(seeds.size());
  for (int j = 0; j < gy; ++j) {
    for (int i = 0; i < gx; ++i) {
      seeds[static_cast<std::size_t>(j * gx + i)] = cv::Point2d(
          (i - 1 + rng.uniform(0.1, 0.9)) * cell, (j - 1 + rng.uniform(0.1, 0.9)) * cell);
      crack_width[static_cast<std::size_t>(j * gx + i)] = rng.uniform(4.0, 9.0) * c.scale;
    }
  }
  cv::Mat1f h(c.height, c.width);
  cv::Mat1f floor_mask(c.height, c.width);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const double px = x + 22.0 * c.scale * warp_x(y, x);
      const double py = y + 22.0 * c.scale * warp_y(y, x);
      const int ci = static_cast<int>(std::floor(px / cell)) + 1;
      const int cj = static_cast<int>(std::floor(py / cell)) + 1;
      double d1 = 1e18, d2 = 1e18;
      std::size_t n1 = 0, n2 = 0;
      for (int j = std::max(0, cj - 2); j <= std::min(gy - 1, cj + 2); ++j) {
        for (int i = std::max(0, ci - 2); i <= std::min(gx - 1, ci + 2); ++i) {
          const auto k = static_cast<std::size_t>(j * gx + i);
          const double d = std::hypot(px - seeds[k].x, py - seeds[k].y);
          if (d < d1) {
            d2 = d1;
            n2 = n1;
            d1 = d;
            n1 = k;
          } else if (d < d2) {
            d2 = d;
            n2 = k;
          }
        }
      }
      const double edge = (d2 - d1) * 0.5;  // distance to the Voronoi edge (warped space)
      const double half_width = 0.25 * (crack_width[n1] + crack_width[n2]);
      // Plate: curls up towards its edge by 0.3 mm, with fine roughness of a few µm.
      const double curl = 0.3 * std::exp(-edge / (30.0 * c.scale));
      const double plate = 2.0 + curl + 0.006 * rough(y, x);
      // Crack: steep walls over ~2 px down to a floor 1.8 mm below.
      const double wall = SmoothStep(half_width - 0.6, half_width + 0.9, edge);
      h(y, x) = static_cast<float>(0.2 + (plate - 0.2) * wall);
      floor_mask(y, x) = static_cast<float>(1.0 - wall);
    }
  }
  cv::Mat3f albedo(c.height, c.width);
  const cv::Mat1f tint = Fbm(rng, c, 70.0 * c.scale, 3);
  const cv::Mat1f speck = BlurredNoise(rng, c, 0.9 * c.scale);
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const double v = (1.0 + 0.09 * tint(y, x)) * (1.0 + 0.018 * speck(y, x));
      const double f = floor_mask(y, x);
      albedo(y, x) = cv::Vec3f(static_cast<float>((0.42 - 0.22 * f) * v),
                               static_cast<float>((0.56 - 0.30 * f) * v),
                               static_cast<float>((0.70 - 0.36 * f) * v));
    }
  }
  const Look look{.ambient = 0.35,
                  .diffuse = 0.80,
                  .specular = 0.04,
                  .shininess = 8.0,
                  .occlusion = 0.9,
                  .occlusion_sigma_px = 10.0 * c.scale};
  return Assemble(
      {.folder = "cracked_ground",
       .name = "cracked ground",
       .description = "Dry cracked earth, hard plates of mud split apart by deep cracks.",
       .material = "dry_soil",
       .height_scale_mm = 3.0,
       .relief_mm = 1.0,
       .probe_width_mm = 0.8,
       .probe_penetration_mm = 0.03,
       .probe_style = "scrape",
       .sound_trim_db = 1.4,
       .sound_trim_why = "# The grid's strokes are not the visitors' (longer, lighter and "
                         "firmer, slower and faster) and leave out the landing, soft on the "
                         "crust:\n# over the visitors' whole strokes its median came out 1.4 LU "
                         "under the mean.\n",
       .haptic_trim_db = 3.9,
       .haptic_trim_why = "# Felt, the crust's soft landings leave the visitors' strokes 3.9 dB "
                          "under the mean.\n"},
      h, Render(h, albedo, look, rng));
}

}  // namespace sas::textures
