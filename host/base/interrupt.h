// Ctrl-C and SIGTERM stop a batch run cleanly: the handler only raises a flag; the search checks
// it between launches and unwinds with ExitCode::interrupted, keeping every finished row. A
// second signal kills the process the usual way.
#pragma once

namespace depthprec {

void install_interrupt_handlers();
bool interrupt_requested();

}  // namespace depthprec
