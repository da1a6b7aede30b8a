#include "vdg/geom/text.h"

#include <cctype>
#include <cstdio>

#include "vdg/geom/error.h"

namespace vdg {

std::string shownText(std::string_view text, std::size_t max_bytes) {
  std::string s = oneLineText(text.substr(0, max_bytes));
  if (text.size() > max_bytes) s += "...";
  return s;
}

std::string quotedText(std::string_view text, std::size_t max_bytes) { return "'" + shownText(text, max_bytes) + "'"; }

std::string numberText(double value, int significant_digits) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*g", significant_digits, value);
  return buffer;
}

bool hasExtension(std::string_view path, std::string_view extension) {
  if (path.size() < extension.size()) return false;
  const std::string_view tail = path.substr(path.size() - extension.size());
  for (std::size_t i = 0; i < tail.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(tail[i])) != std::tolower(static_cast<unsigned char>(extension[i])))
      return false;
  return true;
}

bool hasGltfExtension(std::string_view path) { return hasExtension(path, ".gltf") || hasExtension(path, ".glb"); }

std::string joinedLines(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace vdg
