// The run's video: ffmpeg encodes the rendered frames to H.264 when it is installed. It is spawned
// directly (posix_spawn, no shell), so folder names need no quoting.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::render {

// The first executable `name` in the folders of $PATH, or nullopt.
std::optional<std::filesystem::path> find_on_path(const std::string& name);

// ffmpeg's arguments (without the program) to encode `folder`/frame_*.png (sorted by name: the
// numbers are zero-padded to one width) at `frames_per_second` into `output`: H.264 (libx264),
// yuv420p (what players expect), the size padded to even numbers (yuv420p needs them).
std::vector<std::string> ffmpeg_arguments(const std::filesystem::path& folder,
                                          double frames_per_second,
                                          const std::filesystem::path& output);

// The same command as one line to paste into a shell (arguments quoted where needed).
std::string shell_command(const std::string& program, const std::vector<std::string>& arguments);

// Runs `program` with `arguments`, waits, and returns its exit status (-1 when it did not start or
// did not exit normally; `error` then says why).
int run_program(const std::filesystem::path& program, const std::vector<std::string>& arguments,
                std::string* error);

}  // namespace drapelab::render
