// Scripted input for the viewer (--script FILE): mouse and key events at given frames, so that a
// test (or a reproducible demo) drives it without a person. One event per line, `#` comments:
//   at FRAME press X Y      left button down at pixel (X, Y) of the window (y down from the top)
//   at FRAME move X Y       the cursor to (X, Y)
//   at FRAME release        left button up
//   at FRAME screenshot F   the window's pixels to PNG file F (after the frame is drawn)
//   at FRAME save F         the scene with the recorded drags to YAML file F
//   at FRAME quit           close the viewer
// FRAME counts the frames the viewer has drawn, from 0.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace drapelab::viewer {

struct ScriptEvent {
  enum class Kind { press, move, release, screenshot, save, quit };
  int frame = 0;
  Kind kind = Kind::move;
  double x = 0.0, y = 0.0;  // pixels (press, move)
  std::string file;         // screenshot, save
};

// Reads a script; nullopt with `error` set to "FILE:LINE: what was expected" on a bad line.
std::optional<std::vector<ScriptEvent>> read_input_script(const std::filesystem::path& path,
                                                          std::string* error);

}  // namespace drapelab::viewer
