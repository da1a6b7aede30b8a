// Shared pieces of the `vdg` command-line tool: subcommand registration, option parsing helpers,
// progress reporting. Only apps/ parse command lines.
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "vdg/geom/text.h"  // quoted, numberText, hasExtension for every subcommand

namespace vdg::cli {

// Thrown by a subcommand to stop with an exit status without an error message of its own.
struct Exit {
  int code;
};

// Bad usage detected after parsing (exit status 2), for instance two options that exclude each other.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// ---- Numeric options: one rule for every subcommand ----------------------------------------
// A numeric option's text is accepted only when it is a number of the stated kind inside the
// stated range; anything else (empty, "nan", "inf", "1e999", "12abc", out of range) stops parsing
// with a usage error (exit status 2) whose one line names the option and the accepted range:
//   "--sharpness: expected a number > 0, got 'nan'"
// The checks are CLI11 validators, attached with ->check(...); their description also appears in
// the option's --help line, so the help text and the check cannot disagree.

// How an end of a range is bounded.
enum class End { kClosed, kOpen, kUnbounded };

// An interval of accepted values; `whole` demands an integer (no fraction, no exponent).
struct NumberRange {
  double lo = 0.0;
  End lo_end = End::kUnbounded;
  double hi = 0.0;
  End hi_end = End::kUnbounded;
  bool whole = false;
};

// Whether an executable named `program` is in a folder of $PATH (ffmpeg for --video).
bool findOnPath(const std::string& program);
// `s` in single quotes for /bin/sh, with any single quote escaped.
std::string shellQuote(const std::string& s);

// "a finite number", "a number > 0", "a number in (0, 180)", "a whole number in [1, 64]".
std::string describeRange(const NumberRange& range);
// The value of `text` when it is a number inside `range` (the whole text, no spaces), else nullopt.
std::optional<double> parseNumberIn(std::string_view text, const NumberRange& range);
// A validator accepting exactly the texts parseNumberIn accepts.
CLI::Validator numberIn(const NumberRange& range);

// Shorthands for the usual ranges.
CLI::Validator finiteNumber();                   // any finite number
CLI::Validator positiveNumber(double hi = 0.0);  // (0, hi], or (0, inf) when hi <= 0
CLI::Validator openRange(double lo, double hi);  // (lo, hi)
CLI::Validator wholeNumber(long lo, long hi);    // [lo, hi], integers only

// Image sizes "W<sep>H" (render --size 512x512, align --size 640x480): both sides whole numbers in
// [1, max_side]. Throws UsageError "OPTION: expected WIDTHxHEIGHT ..., got 'TEXT'".
struct ImageSize {
  int width = 0, height = 0;
};
ImageSize parseImageSize(const std::string& text, char separator, int max_side, const std::string& option);
// A validator for the same texts (so that bad sizes stop at parse time).
CLI::Validator imageSize(char separator, int max_side);

// "X,Y,Z" -> vector; throws UsageError naming the option.
Eigen::Vector3d parseVec3(const std::string& text, const std::string& option);

// "X,Y,Z" -> unit vector (any finite, non-zero length, however large); throws UsageError naming
// the option.
Eigen::Vector3d parseDirection(const std::string& text, const std::string& option);

// Parses "A-B" or "N" into an inclusive frame range; throws UsageError.
struct FrameRange {
  int first = 0, last = -1;  // last < first: the whole range
};
FrameRange parseFrameRange(const std::string& text, const std::string& option);

// ---- Old spellings kept for one version --------------------------------------------------------
// Each prints one line on stderr and the command goes on as if the new spelling had been given:
//   "vdg: --frames N is deprecated (it will be removed in the next version): use --count N"
void noteDeprecated(std::string_view old_spelling, std::string_view new_spelling);
// True when `text` is a plain whole number (the old `--frames N` count of morph, morph3d, studio).
bool isPlainCount(std::string_view text);
// A transform for --size that accepts the old "W,H" by rewriting it to "WxH" with the note above.
CLI::Validator oldCommaSize();

// A one-line progress bar on stderr, drawn only when stderr is a terminal and not quiet.
class Progress {
 public:
  Progress(std::string label, long total, bool quiet);
  ~Progress();
  void step(long done);
  // Ends the bar's line, so that what is printed next starts on a line of its own.
  void finish();

 private:
  std::string label_;
  long total_;
  bool enabled_;
  int last_percent_ = -1;
};

// Each subcommand file defines one of these; main.cpp calls them all.
void addInfoCommand(CLI::App& app);
void addWeightsCommand(CLI::App& app);
void addEvalCommand(CLI::App& app);
void addSampleCommand(CLI::App& app);
void addAlignCommand(CLI::App& app);
void addDeformCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);
void addExportCommand(CLI::App& app);
void addBakeCommand(CLI::App& app);
void addRunCommand(CLI::App& app);
void addMorphCommand(CLI::App& app);     // 2D: image morphs and inbetweened drawings
void addMorph3dCommand(CLI::App& app);   // 3D shape interpolation
void addImplicitCommand(CLI::App& app);  // blobby objects polygonised
void addViewCommand(CLI::App& app);      // a web page showing the model live (docs/web.md)
void addStudioCommand(CLI::App& app);    // only in a build with GLFW and Dear ImGui (VDG_WITH_STUDIO)

}  // namespace vdg::cli
