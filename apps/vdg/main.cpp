// vdg — the command-line tool. One file per subcommand; this one dispatches and turns errors
// into one line on stderr: exit status 1 for bad input (vdg::Error), 2 for bad usage.
#include <cstdio>
#include <exception>
#include <string>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/version.h"

int main(int argc, char** argv) {
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

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "vdg: %s\nRun 'vdg --help' (or 'vdg SUBCOMMAND --help') for usage.\n", e.what());
    return 2;
  } catch (const vdg::cli::UsageError& e) {
    std::fprintf(stderr, "vdg: %s\n", e.what());
    return 2;
  } catch (const vdg::cli::Exit& e) {
    return e.code;
  } catch (const vdg::Error& e) {
    std::fprintf(stderr, "vdg: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vdg: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
