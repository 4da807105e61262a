// Where progress lines go and how often (docs/cli.md, "Progress"). On a terminal the lines are
// redrawn in place and erased at the end, so they never stay on the screen between the command's
// real output; in a pipe, a log or CI they are plain lines, written at most every few seconds so
// that a long run's log stays readable. Progress goes to stderr, with the notes and warnings,
// never to stdout (the command's results) nor into any file a verb writes.
#pragma once

#include <chrono>
#include <ostream>
#include <string>
#include <vector>

namespace drapelab::cli {

enum class ProgressMode {
  none,      // -q, --no-progress
  terminal,  // redrawn in place with \r and ANSI cursor moves
  plain,     // whole lines, at most every plain interval
};

// terminal when `fd` is a terminal that understands cursor moves (TERM set and not "dumb"), else
// plain; none when `enabled` is false.
ProgressMode progress_mode_for(int fd, bool enabled);

// How often plain lines are written: DRAPELAB_PROGRESS_INTERVAL (seconds, >= 0) when it is set to a
// number, else kPlainProgressInterval.
inline constexpr std::chrono::seconds kPlainProgressInterval{5};
std::chrono::steady_clock::duration plain_progress_interval();

class ProgressDisplay {
 public:
  using Clock = std::chrono::steady_clock;

  // `columns_fd`: the terminal whose width cuts the lines (a line that wraps would break the
  // redraw); -1 to leave them whole.
  ProgressDisplay(ProgressMode mode, std::ostream& out, Clock::duration plain_interval,
                  int columns_fd = -1);
  ~ProgressDisplay();
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  // Shows `lines` when they are due: on a terminal at most every kTerminalRedraw (the first
  // update at once), plain at most every plain interval (the first one interval after the
  // display was made).
  void update(const std::vector<std::string>& lines, Clock::time_point now = Clock::now());
  // Erases the lines drawn on a terminal, so that other output starts on a clean line; the next
  // update draws them again. Plain lines stay.
  void clear();

  ProgressMode mode() const { return mode_; }

  static constexpr std::chrono::milliseconds kTerminalRedraw{100};

 private:
  void draw(const std::vector<std::string>& lines);
  std::string cut_to_width(const std::string& line) const;
  std::string move_to_first_line() const;

  ProgressMode mode_;
  std::ostream& out_;
  Clock::duration plain_interval_;
  int columns_fd_;
  Clock::time_point last_shown_;
  bool shown_ = false;
  std::size_t lines_drawn_ = 0;  // terminal: lines on the screen now
};

}  // namespace drapelab::cli
