// Scripted input for the viewer (see input_script.hpp).
#include "input_script.hpp"

#include <fstream>
#include <sstream>

namespace drapelab::viewer {

std::optional<std::vector<ScriptEvent>> read_input_script(const std::filesystem::path& path,
                                                          std::string* error) {
  std::ifstream file(path);
  if (!file) {
    *error = path.string() + ": cannot be read";
    return std::nullopt;
  }
  std::vector<ScriptEvent> events;
  std::string line;
  int number = 0;
  int previous_frame = 0;
  while (std::getline(file, line)) {
    ++number;
    const std::string where = path.string() + ":" + std::to_string(number) + ": ";
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string at, verb;
    if (!(words >> at)) continue;  // blank or comment
    ScriptEvent event;
    if (at != "at" || !(words >> event.frame) || event.frame < 0 || !(words >> verb)) {
      *error = where + "expected 'at FRAME EVENT' (FRAME a whole number >= 0), got '" + line + "'";
      return std::nullopt;
    }
    if (event.frame < previous_frame) {
      *error = where + "frame " + std::to_string(event.frame) +
               " comes before the previous event's frame " + std::to_string(previous_frame);
      return std::nullopt;
    }
    previous_frame = event.frame;
    if (verb == "press" || verb == "move") {
      event.kind = verb == "press" ? ScriptEvent::Kind::press : ScriptEvent::Kind::move;
      if (!(words >> event.x >> event.y)) {
        *error = where + verb + " needs the pixel X Y, got '" + line + "'";
        return std::nullopt;
      }
    } else if (verb == "release" || verb == "quit") {
      event.kind = verb == "release" ? ScriptEvent::Kind::release : ScriptEvent::Kind::quit;
    } else if (verb == "screenshot" || verb == "save") {
      event.kind = verb == "save" ? ScriptEvent::Kind::save : ScriptEvent::Kind::screenshot;
      if (!(words >> event.file)) {
        *error = where + verb + " needs a file, got '" + line + "'";
        return std::nullopt;
      }
    } else {
      *error = where + "event must be press, move, release, screenshot, save or quit, got '" +
               verb + "'";
      return std::nullopt;
    }
    std::string extra;
    if (words >> extra) {
      *error = where + "unexpected '" + extra + "' after the event";
      return std::nullopt;
    }
    events.push_back(event);
  }
  return events;
}

}  // namespace drapelab::viewer
