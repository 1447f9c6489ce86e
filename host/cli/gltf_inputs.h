// The files a glTF scene reads besides itself: its external buffers (.bin) and images. An output
// named like one of them would replace the user's geometry with a report (output_guard.h), so
// the audit checks its outputs against them before any work.
#pragma once

#include <string>
#include <vector>

#include "host/output/output_guard.h"

namespace depthprec::cli {

// Every buffer and image of the .gltf or .glb at gltf_path that is a file (not a data: URI), as
// the loader finds it: the URI percent-decoded, beside the glTF file (never in the working
// directory, where tinygltf alone would look next). Images count although the audit does not
// decode them: the loader still opens them. A file that cannot be read or parsed gives none: the
// loader refuses it with the reason.
std::vector<NamedInput> gltf_inputs(const std::string& gltf_path);

}  // namespace depthprec::cli
