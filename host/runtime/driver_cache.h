// The directory PoCL keeps its compiled kernels in while depthprec runs it, and the checks that
// keep a damaged file there from killing a run (docs/caches.md).
//
// PoCL caches every program and kernel it compiles (program.bc, one .so per kernel and local
// size) and trusts whatever it finds: a truncated .so ends the process with SIGBUS, a damaged
// program.bc with an assertion. So depthprec gives PoCL a directory of its own, unless the user
// named one with $POCL_CACHE_DIR, and keeps a manifest there (host/runtime/cache_manifest.h): at
// the first use of OpenCL in a process every file PoCL would execute is checked against it (or,
// unlisted, for a sound structure) and a damaged one is removed, with a note, so PoCL compiles
// it again; when the run ends, the files it added are recorded. A crash that gets past this says
// what to do (host/base/fatal_signal.h).
//
// Concurrent runs share the directory safely: PoCL writes each file to a temporary name and
// renames it; checks and manifest updates hold an exclusive lock (depthprec.lock); every run
// holds a shared lock (depthprec.users) while it lives, which `cache clear` needs exclusively.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace depthprec {

struct DriverCacheDir {
  std::filesystem::path path;
  bool from_environment = false;  // $POCL_CACHE_DIR named it; else depthprec's own
  bool persistent = true;         // PoCL keeps files there ($POCL_KERNEL_CACHE not 0)
  // How it was chosen, for `cache show` and messages: "$POCL_CACHE_DIR" or "depthprec's own
  // ($XDG_CACHE_HOME/depthprec/pocl)" and so on.
  std::string chosen_by;
};

// The directory depthprec runs PoCL with: $POCL_CACHE_DIR when set; else
// $XDG_CACHE_HOME/depthprec/pocl, else $HOME/.cache/depthprec/pocl, else
// /tmp/depthprec-<uid>/pocl. Not PoCL's default ~/.cache/pocl/kcache, which other programs share
// and depthprec does not check.
DriverCacheDir driver_cache_dir();

// Once per process, before the OpenCL platform is first touched (PoCL reads POCL_CACHE_DIR
// then): creates the directory, points PoCL at it, takes the shared in-use lock for the
// process's life, removes damaged files (a note on stderr names each), and arms the crash report
// with the directories and the fix. Throws RuntimeError when the directory cannot be made.
void open_driver_cache();

// After a run that used OpenCL: records the files PoCL added (nothing when open_driver_cache did
// not run). Never throws: a manifest that cannot be written leaves a note, and the next run
// checks those files' structure only.
void record_driver_cache();

// `cache clear`: removes what PoCL and depthprec keep in dir (nothing else that lies there).
// Throws RuntimeError when another depthprec run is using it. Returns the bytes removed.
std::uintmax_t clear_driver_cache(const DriverCacheDir& dir);

// The advice a crash report gives once PoCL is in use: the likely cause, the directories, the
// fix. kernel_cache: depthprec's own program-binary cache ("" when off).
std::string crash_advice(const DriverCacheDir& dir, const std::string& kernel_cache);

}  // namespace depthprec
