// vdg morph3d: placeholder until its branch lands.
#include "cli.h"

namespace vdg::cli {
void addMorph3dCommand(CLI::App& app) { (void)app; }
}  // namespace vdg::cli
