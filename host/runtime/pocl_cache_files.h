// What depthprec knows of the files PoCL keeps in its kernel cache (PoCL 3.x; docs/caches.md):
//
//   <dir>/<2 letters>/<38 letters>/            one program: PoCL's hash of its source, options,
//                                              device, PoCL and LLVM build
//     program.bc                               the program's LLVM bitcode, parsed at every build
//     <kernel>/<local size...>/<kernel>.so     a kernel's work-group function, dlopen()ed at its
//                                              first launch (0-0-0: the generic one a program
//                                              binary export compiles), parallel.bc beside it
//                                              while it is made
//     last_accessed, build.log, descriptor.so.kernel_obj.c   bookkeeping PoCL does not execute
//   <dir>/tempfile_*, <dir>/tempdir_*, *.temp  files being written (PoCL writes to a temporary
//                                              name and renames), or a crashed write's remains
//
// PoCL trusts a file for being there: it never checks one it finds, so a truncated .so kills the
// process with SIGBUS inside dlopen(), a damaged program.bc with an assertion (SIGABRT), and a
// program binary loaded from depthprec's own cache does not help, since unpacking it leaves files
// already present alone. These functions find such files without running them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace depthprec {

// The files of a PoCL cache directory that PoCL loads and executes (.so, .bc; not the temporary
// names of files being written), as paths relative to dir, sorted. Missing dir: none.
std::vector<std::string> pocl_code_files(const std::filesystem::path& dir);

// Why the bytes of a code file cannot be what PoCL wrote ("" when nothing is visibly wrong): an
// ELF shared object whose headers, program headers or segments reach past its end (cut short),
// or a bitcode file without LLVM's magic or whose top-level blocks overrun it. Structure only:
// a file overwritten in place with well-formed bytes passes (the manifest's checksum finds it).
std::string pocl_file_structure_problem(const std::string& relative_path, const std::string& bytes);

// Whether a name at the top of a cache directory is one PoCL made (a program's two-letter
// directory, a temporary file or directory) or depthprec's own bookkeeping there: what `cache
// clear` may remove. Anything else is left alone (POCL_CACHE_DIR may name a directory that
// holds other things).
bool is_pocl_cache_entry(const std::string& top_level_name);

// A checksum of a file's bytes (64 bits, not cryptographic: it finds damage, not tampering).
std::uint64_t file_checksum(const std::string& bytes);

}  // namespace depthprec
