// An output must never replace what the command reads: `mts scene.json -o scene.json` would put
// results where the user's scene was, `merge a.json b.json -o a.json` a merge over a shard.
#pragma once

#include <string>
#include <vector>

namespace depthprec {

// A file a command reads, and what it is to the command ("the scene file", "a shard").
struct NamedInput {
  std::string what, path;
};

// Throws InputError when output -- or the files written beside it, output.tmp and the journal
// output.rows.jsonl -- is one of the inputs: the same path, or the same file through a symbolic
// or hard link (compared by device and inode where both exist). option names the output as the
// user typed it ("-o", "--plot"). A device or pipe (/dev/stdout) is written in place, never
// replaced, and is not checked; "" is no output.
void check_output_spares_inputs(const std::string& option, const std::string& output,
                                const std::vector<NamedInput>& inputs);

// A command that writes a file of a default name when no -o is given (plot: mts.png, report:
// report.html) must not silently replace a file of that name, perhaps another run's: throws
// OutputError when named is false and path exists, asking for -o. named: -o was given.
void check_default_output_is_new(const std::string& who, const std::string& path, bool named);

}  // namespace depthprec
