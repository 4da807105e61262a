#include "progress/progress_display.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdlib>
#include <string_view>

namespace drapelab::cli {

ProgressMode progress_mode_for(int fd, bool enabled) {
  if (!enabled) return ProgressMode::none;
  if (!::isatty(fd)) return ProgressMode::plain;
  // Emacs' shell buffers and some CI consoles are ttys that show escape codes as text.
  const char* term = std::getenv("TERM");
  if (!term || !*term || std::string_view(term) == "dumb") return ProgressMode::plain;
  return ProgressMode::terminal;
}

std::chrono::steady_clock::duration plain_progress_interval() {
  if (const char* text = std::getenv("DRAPELAB_PROGRESS_INTERVAL")) {
    char* end = nullptr;
    const double seconds = std::strtod(text, &end);
    if (end != text && *end == '\0' && seconds >= 0.0 && seconds <= 1e6)
      return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(seconds));
  }
  return kPlainProgressInterval;
}

ProgressDisplay::ProgressDisplay(ProgressMode mode, std::ostream& out,
                                 Clock::duration plain_interval, int columns_fd)
    : mode_(mode),
      out_(out),
      plain_interval_(plain_interval),
      columns_fd_(columns_fd),
      last_shown_(Clock::now()) {}

ProgressDisplay::~ProgressDisplay() { clear(); }

void ProgressDisplay::update(const std::vector<std::string>& lines, Clock::time_point now) {
  switch (mode_) {
    case ProgressMode::none:
      return;
    case ProgressMode::terminal:
      if (shown_ && now - last_shown_ < kTerminalRedraw) return;
      break;
    case ProgressMode::plain:
      if (now - last_shown_ < plain_interval_) return;
      break;
  }
  last_shown_ = now;
  shown_ = true;
  draw(lines);
}

void ProgressDisplay::draw(const std::vector<std::string>& lines) {
  std::string text;
  if (mode_ == ProgressMode::plain) {
    for (const auto& line : lines) text += line + "\n";
  } else {
    // Over the lines drawn before: each line erased and written, and any left below erased.
    text = move_to_first_line();
    for (std::size_t k = 0; k < lines.size(); ++k)
      text += "\033[K" + cut_to_width(lines[k]) + (k + 1 < lines.size() ? "\n" : "");
    if (lines.size() < lines_drawn_) text += "\033[J";
    lines_drawn_ = lines.size();
  }
  out_ << text << std::flush;
}

void ProgressDisplay::clear() {
  if (mode_ != ProgressMode::terminal || lines_drawn_ == 0) return;
  out_ << move_to_first_line() << "\033[J" << std::flush;
  lines_drawn_ = 0;
}

// The cursor rests at the end of the last line drawn: back to the start of the first.
std::string ProgressDisplay::move_to_first_line() const {
  std::string text = "\r";
  if (lines_drawn_ > 1) text += "\033[" + std::to_string(lines_drawn_ - 1) + "A";
  return text;
}

std::string ProgressDisplay::cut_to_width(const std::string& line) const {
  winsize size{};
  if (columns_fd_ < 0 || ::ioctl(columns_fd_, TIOCGWINSZ, &size) != 0 || size.ws_col < 2)
    return line;
  // One column short of the width: a line that fills the last column makes some terminals wrap.
  const std::size_t columns = size.ws_col - 1u;
  return line.size() <= columns ? line : line.substr(0, columns);
}

}  // namespace drapelab::cli
