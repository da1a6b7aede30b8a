// vdg implicit: placeholder until its branch lands.
#include "cli.h"

namespace vdg::cli {
void addImplicitCommand(CLI::App& app) { (void)app; }
}  // namespace vdg::cli
