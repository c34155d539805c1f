#include "engine/shader_log.h"

#include <regex>
#include <sstream>

namespace engine {
namespace {

struct LogForm {
  std::regex pattern;
  int lineGroup;
  int messageGroup;
};

const LogForm* logForms() {
  static const LogForm forms[] = {
      {std::regex(R"(^\s*\d+:(\d+)\(\d+\):\s*(.*)$)"), 1, 2},                  // Mesa
      {std::regex(R"(^\s*\d+\((\d+)\)\s*:\s*(.*)$)"), 1, 2},                   // NVIDIA
      {std::regex(R"(^\s*((?:ERROR|WARNING):)\s*\d+:(\d+):\s*(.*)$)"), 2, 3},  // AMD, Intel
  };
  return forms;
}

}  // namespace

std::string formatShaderLog(std::string_view file, std::string_view driverLog) {
  std::ostringstream out;
  std::istringstream lines{std::string(driverLog)};
  std::string line;
  while (std::getline(lines, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == '\0')) line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    std::smatch m;
    bool matched = false;
    for (int f = 0; f < 3 && !matched; ++f) {
      const LogForm& form = logForms()[f];
      if (!std::regex_match(line, m, form.pattern)) continue;
      std::string message = m[form.messageGroup].str();
      if (f == 2) {  // keep the severity word the AMD/Intel form puts first
        std::string severity = m[1].str();
        severity.pop_back();
        for (char& c : severity) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        message = severity + ": " + message;
      }
      out << file << ':' << m[form.lineGroup].str() << ": " << message << '\n';
      matched = true;
    }
    if (!matched) out << file << ": " << line << '\n';
  }
  return out.str();
}

}  // namespace engine
