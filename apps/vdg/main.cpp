// vdg — the command-line tool. One file per subcommand; this one dispatches and turns every error
// into ONE line on stderr (control characters in names escaped, see vdg::oneLineText):
//   exit status 1 for bad input:  "vdg: error: FILE: what is wrong"
//   exit status 2 for bad usage:  "vdg: render: --size: expected ..., got '0x0' (see vdg render --help)"
// Running out of memory is reported as such (exit status 1), with what to try.
// Signals (vdg/io/atomic_file.h, installOutputSignalHandlers): Ctrl-C, SIGTERM and SIGHUP remove
// the files being written and end with 128 + the signal; a closed reader of stdout (vdg sample |
// head -1) ends the run quietly with status 0; a file size limit fails a write as a full disk does.
// A run that fails removes the files and folders it made (vdg::removeNewOutputs).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/version.h"

namespace {

// The subcommand named on the command line ("render"), or "" before one was recognised.
std::string subcommandOf(const CLI::App& app) {
  const auto subs = app.get_subcommands();
  return subs.empty() ? std::string() : subs.front()->get_name();
}

int usage(const CLI::App& app, const std::string& message) {
  const std::string sub = subcommandOf(app);
  const std::string help = sub.empty() ? "vdg --help" : "vdg " + sub + " --help";
  std::fprintf(stderr, "vdg: %s%s (see %s)\n", sub.empty() ? "" : (sub + ": ").c_str(),
               vdg::oneLineText(message).c_str(), help.c_str());
  return 2;
}

// What a subcommand can do with less memory.
const char* memoryHint(const std::string& sub) {
  if (sub == "render") return "try a smaller --size, fewer --samples or a smaller model";
  if (sub == "sample") return "try fewer --samples or a smaller spec";
  return "try a smaller model or mesh, or free some memory";
}

int run(int argc, char** argv) {
  CLI::App app{
      "vdg — view-dependent geometry: models whose shape follows the view direction.\n"
      "Run 'vdg SUBCOMMAND --help' for the options of each subcommand."};
  app.name("vdg");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("vdg ") + vdg::versionString());
  vdg::cli::addInfoCommand(app);
  vdg::cli::addWeightsCommand(app);
  vdg::cli::addEvalCommand(app);
  vdg::cli::addSampleCommand(app);
  vdg::cli::addAlignCommand(app);
  vdg::cli::addDeformCommand(app);
  vdg::cli::addRenderCommand(app);
  vdg::cli::addExportCommand(app);
  vdg::cli::addBakeCommand(app);
  vdg::cli::addRunCommand(app);
  vdg::cli::addMorphCommand(app);
  vdg::cli::addMorph3dCommand(app);
  vdg::cli::addImplicitCommand(app);
  vdg::cli::addViewCommand(app);
#ifdef VDG_WITH_STUDIO
  vdg::cli::addStudioCommand(app);
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (app.get_subcommands().empty()) {
      std::string names;
      for (const CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
      if (argc < 2) return usage(app, "give a subcommand: one of " + names);
      if (argv[1][0] != '-')
        return usage(app, "unknown subcommand " + vdg::quotedText(argv[1]) + " (expected one of " + names + ")");
    }
    return usage(app, e.what());
  } catch (const vdg::cli::UsageError& e) {
    return usage(app, e.what());
  } catch (const vdg::cli::Exit& e) {
    return e.code;
  } catch (const vdg::ReaderClosed&) {
    return 0;  // the reader has what it wanted
  } catch (const vdg::Error& e) {
    std::fprintf(stderr, "vdg: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    const std::string sub = subcommandOf(app);
    std::fprintf(stderr, "vdg: error: %s ran out of memory; %s\n", sub.empty() ? "vdg" : sub.c_str(), memoryHint(sub));
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vdg: error: %s\n", vdg::oneLineText(e.what()).c_str());
    return 1;
  }
  return 0;
}

// What is still buffered for stdout, written now: a reader that has gone (EPIPE) is no error; a
// full disk under a redirection is.
int flushStdout() {
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return 0;
  if (errno == EPIPE) return 0;
  std::fprintf(stderr, "vdg: error: standard output: cannot write: %s\n", std::strerror(errno));
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  vdg::installOutputSignalHandlers();
  int status = run(argc, argv);
  if (status == 0) status = flushStdout();
  if (status != 0) vdg::removeNewOutputs();
  return status;
}
