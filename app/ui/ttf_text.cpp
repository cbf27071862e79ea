// SDL2_ttf text into overlay masks (see ttf_text.h).
#include "ui/ttf_text.h"

#include <SDL.h>
#include <SDL_ttf.h>

#include <filesystem>

namespace sas::ui {

struct TextRenderer::Font {
  TTF_Font* font = nullptr;
};

std::string FindFontFile(bool bold) {
  const char* candidates[] = {
      bold ? "/usr/share/fonts/opentype/b612/B612-Bold.otf"
           : "/usr/share/fonts/opentype/b612/B612-Regular.otf",
      bold ? "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf"
           : "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
  };
  for (const char* file : candidates) {
    std::error_code error;
    if (std::filesystem::is_regular_file(file, error)) return file;
  }
  return {};
}

TextRenderer::TextRenderer() {
  regular_file_ = FindFontFile(false);
  bold_file_ = FindFontFile(true);
  if (regular_file_.empty()) return;
  if (bold_file_.empty()) bold_file_ = regular_file_;
  if (TTF_WasInit() == 0 && TTF_Init() != 0) return;
  ttf_started_ = true;
  available_ = FontAt(24, false) != nullptr;
}

TextRenderer::~TextRenderer() {
  for (auto& [key, font] : fonts_) {
    if (font->font) TTF_CloseFont(font->font);
    delete font;
  }
  if (ttf_started_) TTF_Quit();
}

TextRenderer::Font* TextRenderer::FontAt(int size_px, bool bold) {
  const auto key = std::make_pair(size_px, bold);
  if (const auto found = fonts_.find(key); found != fonts_.end()) return found->second;
  auto* font = new Font;
  font->font = TTF_OpenFont((bold ? bold_file_ : regular_file_).c_str(), size_px);
  if (font->font) TTF_SetFontHinting(font->font, TTF_HINTING_LIGHT);
  fonts_[key] = font;
  return font->font ? font : nullptr;
}

std::shared_ptr<const TextMask> TextRenderer::Render(std::string_view utf8, int size_px,
                                                     bool bold) {
  if (!available_ || utf8.empty()) return nullptr;
  const auto key = std::make_tuple(std::string(utf8), size_px, bold);
  if (const auto found = cache_.find(key); found != cache_.end()) return found->second;
  Font* font = FontAt(size_px, bold);
  if (font == nullptr) return nullptr;
  SDL_Surface* rendered =
      TTF_RenderUTF8_Blended(font->font, std::get<0>(key).c_str(), SDL_Color{255, 255, 255, 255});
  if (rendered == nullptr) return nullptr;
  SDL_Surface* rgba = SDL_ConvertSurfaceFormat(rendered, SDL_PIXELFORMAT_RGBA32, 0);
  SDL_FreeSurface(rendered);
  if (rgba == nullptr) return nullptr;
  auto mask = std::make_shared<TextMask>();
  mask->w = rgba->w;
  mask->h = rgba->h;
  mask->text = std::get<0>(key);
  mask->alpha.resize(static_cast<std::size_t>(mask->w) * static_cast<std::size_t>(mask->h));
  SDL_LockSurface(rgba);
  for (int y = 0; y < rgba->h; ++y) {
    const auto* row = static_cast<const std::uint8_t*>(rgba->pixels) + y * rgba->pitch;
    for (int x = 0; x < rgba->w; ++x) {
      mask->alpha[static_cast<std::size_t>(y * mask->w + x)] = row[4 * x + 3];
    }
  }
  SDL_UnlockSurface(rgba);
  SDL_FreeSurface(rgba);
  // A screen shows a few dozen lines; staff numbers change a few times a second. Bounded.
  if (cache_.size() > 512) cache_.clear();
  cache_[key] = mask;
  return mask;
}

int TextRenderer::Width(std::string_view utf8, int size_px, bool bold) {
  Font* font = available_ ? FontAt(size_px, bold) : nullptr;
  if (font == nullptr) return 0;
  int w = 0, h = 0;
  TTF_SizeUTF8(font->font, std::string(utf8).c_str(), &w, &h);
  return w;
}

int TextRenderer::LineHeight(int size_px, bool bold) {
  Font* font = available_ ? FontAt(size_px, bold) : nullptr;
  return font == nullptr ? size_px : TTF_FontLineSkip(font->font);
}

std::vector<std::string> TextRenderer::Wrap(std::string_view utf8, int size_px, int max_width_px,
                                            bool bold) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t at = 0;
  while (at < utf8.size()) {
    std::size_t end = utf8.find(' ', at);
    if (end == std::string_view::npos) end = utf8.size();
    const std::string word(utf8.substr(at, end - at));
    at = end + 1;
    if (word.empty()) continue;
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && Width(candidate, size_px, bold) > max_width_px) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace sas::ui
