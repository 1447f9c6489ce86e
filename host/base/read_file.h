// Reads a file the user named as input, with errors that say what is wrong with the path itself:
// a directory or an unreadable file is not "malformed JSON".
#pragma once

#include <string>

namespace depthprec {

// The whole content of path. what names it in errors ("scene file", "merge: input"). Throws
// InputError: "cannot read <what> '<path>': <reason>", or "<what> '<path>' is a directory".
std::string read_input_file(const std::string& path, const std::string& what);

}  // namespace depthprec
