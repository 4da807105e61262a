// The viewer's window (GLFW, Dear ImGui over fixed-function GL): the session's solvers drawn side
// by side (or one), orbit / pan / zoom with the right and middle buttons and the wheel, the left
// button grabbing the cloth (live_session.hpp), the controls and live metrics in an ImGui panel.
#pragma once

#include <string>

#include "live_session.hpp"

namespace drapelab::viewer {

struct ViewOptions {
  int width = 1280, height = 720;  // window pixels
  int frames = 0;                  // > 0: close after drawing this many frames
  bool report = false;             // print the frame rate measured at the end
  std::string script;              // input events (input_script.hpp); empty: none
  std::string save_path;           // where Save writes the scene with the recorded drags
  bool start_paused = false;
};

// Opens the window and runs until it is closed (or `frames` are drawn). Exit codes: 0 closed, 1 a
// script's screenshot or save could not be written, 2 no display (the message names DISPLAY and
// the offline way) or a bad script.
int run_view_window(LiveSession& session, const ViewOptions& options);

}  // namespace drapelab::viewer
