// Output-set planning: a command names its inputs and every file it will write BEFORE any
// work, and each output name is checked against the rules of an all-or-nothing run:
//   - not empty, not an existing directory;
//   - its folder exists (or, for commands that create it, its nearest existing ancestor does)
//     and is a directory we may write into;
//   - not one of the run's inputs (same file: std::filesystem::equivalent for existing files,
//     weakly_canonical paths otherwise, so "./a.json", "dir/../a.json" and hard links count);
//   - not another output of the same run.
// Failures are InvalidInput (exit 2) naming the flag, the value and the rule.
//
// The inputs become "protected" for the rest of the process: StagedFiles and write_file_atomic
// (core/files/atomic_file) refuse to replace a protected input, an existing directory or a name
// staged twice, so a command that forgot to plan still cannot overwrite what it read. Readers of
// outside files (core/image/image_io, io/mask_json, io/psf_files) protect what they read too.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pinmask {

// One file of a command and the name the caller gave it in its messages (the command line's
// option or argument that named it: -o, the stats option, mask).
struct NamedPath {
    std::string flag;
    std::filesystem::path path;
    // The command creates the output's folder (export's and search's -o): a missing folder is
    // fine when its nearest existing ancestor is writable. Otherwise the folder must exist.
    bool folder_created = false;
};

// Checks every output against the rules above (and against each other), then protects the
// inputs. Empty paths in either list are skipped (optional flags not given), except an output
// named by "-o", which every command requires. Throws
// InvalidInput naming the first offending flag.
void plan_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

// Turns the process-wide protection of inputs on (the pinmask executable does, in cli/main.cpp:
// one process = one run). Off by default, so a library user (a test, a Python session) may
// read a file and later rewrite it. plan_outputs() also turns it on.
void enable_input_protection();
// Turns it off and forgets the protected inputs (tests).
void reset_input_protection();

// Marks a file read by this process as an input no output may replace. Idempotent; a path that
// does not exist is ignored.
void protect_input(const std::filesystem::path& path);

// Forgets one protected input: a file the run is meant to supersede (a search checkpoint that
// the run resumed from and checkpoints to again). A path that is not protected is ignored.
void release_input(const std::filesystem::path& path);

// The one-output check StagedFiles and write_file_atomic run on every final name: throws
// InvalidInput("<flag>: '<path>': <rule>") for an existing directory, an existing special file
// (device, pipe, socket: renaming over it would replace it), a name with no room for the
// temporary names, a folder where no file can be created (/proc: probed once per folder by a
// create and unlink) or a protected input.
void check_output_path(const std::filesystem::path& path, const std::string& flag);

// The check of an output folder (created when missing): throws InvalidInput naming `flag` when
// `path` is empty or exists as anything but a directory (a file, a device, a pipe, a socket:
// each named).
void check_output_folder(const std::filesystem::path& path, const std::string& flag);

// Keys of a path's identity: "i<device>:<inode>" when it exists, and its canonical path. Two
// paths sharing a key name the same file (a hash set of keys finds duplicates among N paths in
// O(N), where same_file on every pair would take N^2 / 2 canonicalisations).
std::vector<std::string> same_file_keys(const std::filesystem::path& path);

// True when a and b name the same file (or would: compared by weakly_canonical path when one
// does not exist yet).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace pinmask
