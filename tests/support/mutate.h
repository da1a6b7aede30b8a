// Deterministic input mutation for parser robustness tests: every mutant must either parse or be
// rejected with vdg::Error — never crash, hang, or throw anything else. Run under ASan+UBSan in CI.
#pragma once

#include <random>
#include <string>

namespace vdg::testing {

class Mutator {
 public:
  explicit Mutator(unsigned seed) : rng_(seed) {}

  // One to four random edits of `text`: byte flips, insertions of syntax characters or nasty
  // numbers, deletions and duplications of spans.
  std::string mutate(const std::string& text) {
    std::string s = text;
    const int edits = 1 + static_cast<int>(rng_() % 4);
    for (int e = 0; e < edits; ++e) {
      if (s.empty()) s = "{";
      const std::size_t at = rng_() % s.size();
      switch (rng_() % 6) {
        case 0:
          s[at] = static_cast<char>(rng_() % 256);
          break;
        case 1: {
          static const char* kSyntax[] = {"{", "}", "[", "]", ",", ":", "\"", "-", ".", "e", "/", " ", "\n", "0", "#"};
          s.insert(at, kSyntax[rng_() % (sizeof(kSyntax) / sizeof(*kSyntax))]);
          break;
        }
        case 2: {
          static const char* kNumbers[] = {"1e999", "-1e999",     "nan",        "inf",         "-0",     "0",
                                           "-1",    "4294967296", "2147483647", "-2147483648", "1e-320", "null",
                                           "true",  "\"\"",       "[]",         "{}"};
          s.insert(at, kNumbers[rng_() % (sizeof(kNumbers) / sizeof(*kNumbers))]);
          break;
        }
        case 3:
          s.erase(at, 1 + rng_() % 16);
          break;
        case 4: {
          const std::size_t len = 1 + rng_() % 32;
          s.insert(at, s.substr(at, len));
          break;
        }
        default: {
          // Replace a digit run with another number.
          const std::size_t d = s.find_first_of("0123456789", at);
          if (d != std::string::npos) {
            const std::size_t end = s.find_first_not_of("0123456789.", d);
            static const char* kValues[] = {"0", "-5", "99999999", "1e30", "3.5", "-0.0"};
            s.replace(d, (end == std::string::npos ? s.size() : end) - d, kValues[rng_() % 6]);
          }
          break;
        }
      }
    }
    return s;
  }

 private:
  std::mt19937 rng_;
};

}  // namespace vdg::testing
