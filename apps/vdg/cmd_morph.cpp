// vdg morph: placeholder until its branch lands.
#include "cli.h"

namespace vdg::cli {
void addMorphCommand(CLI::App& app) { (void)app; }
}  // namespace vdg::cli
