#include "vdg/io/json_text.h"

namespace vdg {

std::string compactScalarArrays(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) {
        out += text[++i];
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
      out += c;
      continue;
    }
    if (c == '[') {
      const std::size_t close = text.find_first_of("[]{}\"", i + 1);
      if (close != std::string::npos && text[close] == ']') {
        // Only scalars inside: keep the items, drop the line breaks and indentation.
        std::string flat = "[";
        std::size_t start = i + 1;
        while (start <= close) {
          std::size_t end = text.find(',', start);
          if (end == std::string::npos || end > close) end = close;
          const std::size_t a = text.find_first_not_of(" \t\r\n", start);
          if (a < end) {
            const std::size_t b = text.find_last_not_of(" \t\r\n", end - 1);
            flat += (flat.size() > 1 ? ", " : "") + text.substr(a, b - a + 1);
          }
          start = end + 1;
        }
        out += flat + "]";
        i = close;
        continue;
      }
    }
    out += c;
  }
  return out;
}

}  // namespace vdg
