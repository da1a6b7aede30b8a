// Shared pieces of the `vdg` command-line tool: subcommand registration, option parsing helpers,
// progress reporting. Only apps/ parse command lines.
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <cstdio>
#include <string>

namespace vdg::cli {

// Thrown by a subcommand to stop with an exit status without an error message of its own.
struct Exit {
  int code;
};

// Bad usage detected after parsing (exit status 2), for instance two options that exclude each other.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "X,Y,Z" -> vector; throws UsageError naming the option.
Eigen::Vector3d parseVec3(const std::string& text, const std::string& option);

// Parses "A-B" or "N" into an inclusive frame range; throws UsageError.
struct FrameRange {
  int first = 0, last = -1;  // last < first: the whole range
};
FrameRange parseFrameRange(const std::string& text, const std::string& option);

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

}  // namespace vdg::cli
