#include "command_line.h"

#include <algorithm>
#include <exception>
#include <new>
#include <ostream>
#include <sstream>
#include <string_view>
#include <type_traits>
#include <utility>

#include <CLI/CLI.hpp>

#include "fileio/files.h"
#include "lab.h"
#include "numbers.h"
#include "scenes/scene.h"
#include "text.h"

namespace lab {

/// One line of the help: "--steps N" and what it does.
struct CommandLine::Entry {
  std::string names;  // every spelling, comma-separated: what CLI11 was given
  std::string label;  // "--steps N"
  std::string help;
  std::string needs;
};

namespace {

constexpr std::size_t kHelpWidth = 100;
constexpr std::size_t kLabelWidth = 20;

// A value the option's reader refused: carries the whole message out of CLI11's parse.
class OptionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string firstName(const std::string& names) {
  return names.substr(0, names.find(','));
}

// "(--method too)" for the spellings after the first.
std::string aliasNote(const std::string& names) {
  const std::size_t comma = names.find(',');
  return comma == std::string::npos ? std::string() : "; " + names.substr(comma + 1) + " too";
}

// `text` wrapped to the help's width, every line after the first indented by `indent`.
std::string wrapped(const std::string& text, std::size_t first, std::size_t indent) {
  std::istringstream words(text);
  std::string word, out;
  std::size_t column = first;
  while (words >> word) {
    if (!out.empty() && column + 1 + word.size() > kHelpWidth) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
    } else if (!out.empty()) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
  }
  return out;
}

// Each item of a comma-separated list through `read`; an empty item is refused by name.
std::string readList(const std::string& text, const std::function<std::string(const std::string&)>& read) {
  const std::optional<std::vector<std::string>> items = splitList(text);
  if (!items) return "'" + text + "' is not a comma-separated list (an item is empty)";
  for (const std::string& item : *items) {
    if (std::string e = read(item); !e.empty()) return e;
  }
  return {};
}

// A LIST option's target: the command's defaults are dropped at the first value given, and a
// second --option adds to the first.
template <typename T>
std::function<void(const T&)> listAppender(std::vector<T>& into) {
  auto fresh = std::make_shared<bool>(true);
  return [&into, fresh](const T& v) {
    if (*fresh) into.clear();
    *fresh = false;
    addOnce(into, v);
  };
}

// The range of a count (`whole`: 1 to spec.most) or of a time, as the help and the errors write it:
// "1 to 1000", "1e-06 to 1", "above 0 and at most 3600".
std::string rangeText(const OptionSpec& spec, bool whole) {
  if (whole) return "1 to " + std::to_string(static_cast<int>(spec.most));
  return (spec.aboveLeast ? "above " : "") + formatNumber(spec.least) +
         (spec.aboveLeast ? " and at most " : " to ") + formatNumber(spec.most);
}

// One value of each type an option reads into; the error without the option's name, or "".
std::string read(const std::string& text, const OptionSpec& spec, int& into) {
  const std::optional<int> n = parseWholeNumber(text, 1, static_cast<int>(spec.most));
  if (!n) return "'" + text + "' is not a whole number from " + rangeText(spec, true);
  into = *n;
  return {};
}

std::string read(const std::string& text, const OptionSpec& spec, double& into) {
  const std::optional<double> v = parseNumber(text);
  if (v && (spec.aboveLeast ? *v > spec.least : *v >= spec.least) && *v <= spec.most) {
    into = *v;
    return {};
  }
  return "'" + text + "' is not a number of seconds " + (spec.aboveLeast ? "" : "from ") +
         rangeText(spec, false);
}

std::string read(const std::string& text, const OptionSpec&, phys::SolverMethod& into) {
  const std::optional<phys::SolverMethod> m = phys::parseSolverMethod(text);
  if (!m) return "unknown method '" + text + "' (gauss-seidel, jacobi, xpbd or shake)";
  into = *m;
  return {};
}

std::string read(const std::string& text, const OptionSpec&, phys::BodyModel& into) {
  const std::optional<phys::BodyModel> m = phys::parseBodyModel(text);
  if (!m) return "unknown model '" + text + "' (corners, tetra or rigid)";
  into = *m;
  return {};
}

std::string read(const std::string& text, const OptionSpec&, bool& into) {
  if (text != "on" && text != "off") return "'" + text + "' is not on or off";
  into = text == "on";
  return {};
}

bool namesFile(const OptionSpec& spec) {
  return spec.value == std::string_view("FILE");
}

std::string read(const std::string& text, const OptionSpec&, std::filesystem::path& into) {
  into = text;  // an empty name is refused before (emptyValue), as every option's empty value
  return {};
}

// An empty value ("--steps ''", "--out=", a shell variable that expanded to nothing), worded
// here alike for every option of every command, before the option's own reader sees it.
std::string emptyValue(const std::string& name, const std::string& needs) {
  return name + " is empty: it needs " + (needs.empty() ? std::string("a value") : needs);
}

// "--help" or "-h" anywhere: help wins wherever it is, so "lab run x --help" shows the help
// instead of running.
bool asksForHelp(const std::vector<std::string>& args) {
  return std::any_of(args.begin(), args.end(),
                     [](const std::string& a) { return a == "--help" || a == "-h"; });
}

// What a missing value should have been: the table's word, else what the option's type reads.
template <typename Value>
std::string needsOf(const OptionSpec& spec) {
  if (spec.needs != nullptr) return spec.needs;
  if constexpr (std::is_same_v<Value, int>) return "a whole number";
  if constexpr (std::is_same_v<Value, double>) return "a number of seconds";
  if constexpr (std::is_same_v<Value, phys::SolverMethod>)
    return "a method (gauss-seidel, jacobi, xpbd or shake)";
  if constexpr (std::is_same_v<Value, phys::BodyModel>) return "a body model (corners, tetra or rigid)";
  if constexpr (std::is_same_v<Value, bool>) return "a value (on or off)";
  if constexpr (std::is_same_v<Value, std::filesystem::path>)
    return namesFile(spec) ? "a file name" : "a folder";
}

template <typename T>
struct Target {  // a plain value
  using Value = T;
  static T& slot(T& into) { return into; }
};
template <typename T>
struct Target<std::optional<T>> {
  using Value = T;
  static T& slot(std::optional<T>& into) { return into.emplace(); }
};

template <typename T>
constexpr bool kIsList = false;
template <typename T>
constexpr bool kIsList<std::vector<T>> = true;

// The table's help, its "{range}" written out (`whole`: a count's), then the command's note.
std::string helpText(const OptionSpec& spec, const std::string& note, bool whole = false) {
  constexpr std::string_view kRange = "{range}";
  std::string help = spec.help;
  if (const std::size_t at = help.find(kRange); at != std::string::npos)
    help.replace(at, kRange.size(), rangeText(spec, whole));
  return note.empty() ? help : help + " " + note;
}

}  // namespace

CommandLine::CommandLine(std::string command)
    : command_(std::move(command)), app_(std::make_unique<CLI::App>("", "lab " + command_)) {
  app_->set_help_flag();  // asksForHelp answers --help before CLI11 sees it
}

CommandLine::~CommandLine() = default;

void CommandLine::add(const OptionSpec& spec, std::string label, std::string needs, const std::string& help,
                      bool many, std::function<std::string(const std::string&)> read) {
  const std::string names = spec.names;
  const std::string name = firstName(names);
  CLI::Option* option = app_->add_option(names);
  if (many) {
    // allow_extra_args: "--scene a b" as well as "--scene a --scene b".
    option->expected(1, CLI::detail::expected_max_vector_size)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(true);
  } else {
    option->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  }
  option->check(CLI::Validator(
      [name, needs, read = std::move(read)](std::string& value) -> std::string {
        // CLI11 hands a following "--json" to an option that lacks its value; here, as when the
        // value is missing at the end, that is a forgotten value, not a file called "--json".
        if (value.starts_with("--")) throw OptionError(name + " needs " + needs);
        if (value.empty()) throw OptionError(emptyValue(name, needs));
        if (std::string e = read(value); !e.empty()) throw OptionError(name + ": " + e);
        return {};
      },
      ""));
  entries_.push_back({names, std::move(label), help + aliasNote(names), std::move(needs)});
}

void CommandLine::scene(std::string& into) {
  positional("SCENE", "a scene file, or a name in <data>/assets/scenes", false,
             [&into](const std::string& v) {
               into = v;
               return std::string();
             });
  required_.emplace_back("SCENE",
                         command_ + " needs a SCENE (a scene file, or a name in <data>/assets/scenes)");
}

void CommandLine::positional(const std::string& name, const std::string& help, bool many,
                             std::function<std::string(const std::string&)> read) {
  positionalName_ = name;
  CLI::Option* option = app_->add_option(name);
  if (many) option->expected(0, CLI::detail::expected_max_vector_size)->allow_extra_args(true);
  option->check(CLI::Validator(
      [read = std::move(read)](std::string& value) -> std::string {
        if (std::string e = read(value); !e.empty()) throw OptionError(e);
        return {};
      },
      ""));
  entries_.insert(entries_.begin(), Entry{"", many ? "[" + name + "...]" : name, help, ""});
}

template <typename T>
void CommandLine::option(const OptionSpec& spec, T& into, const std::string& note) {
  const std::string name = firstName(spec.names);
  if constexpr (kIsList<T>) {
    using Value = typename T::value_type;
    add(spec, name + " LIST", needsOf<Value>(spec), helpText(spec, note, std::is_same_v<Value, int>), false,
        [spec, append = listAppender(into)](const std::string& text) {
          return readList(text, [&](const std::string& item) {
            Value v{};
            std::string e = read(item, spec, v);
            if (e.empty()) append(v);
            return e;
          });
        });
  } else {
    using Value = typename Target<T>::Value;
    add(spec, name + " " + spec.value, needsOf<Value>(spec), helpText(spec, note, std::is_same_v<Value, int>),
        false, [spec, &into](const std::string& v) { return read(v, spec, Target<T>::slot(into)); });
  }
}

template void CommandLine::option(const OptionSpec&, int&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::optional<int>&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::vector<int>&, const std::string&);
template void CommandLine::option(const OptionSpec&, double&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::optional<double>&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::vector<double>&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::optional<phys::SolverMethod>&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::vector<phys::SolverMethod>&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::optional<phys::BodyModel>&, const std::string&);
template void CommandLine::option(const OptionSpec&, bool&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::optional<bool>&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::filesystem::path&, const std::string&);
template void CommandLine::option(const OptionSpec&, std::optional<std::filesystem::path>&,
                                  const std::string&);

void CommandLine::existingFolder(const OptionSpec& spec, std::filesystem::path& into,
                                 const std::string& note) {
  option(spec, into, note);
  folders_.emplace_back(firstName(spec.names), &into);
}

void CommandLine::requireGivenFolders() const {
  for (const auto& [name, folder] : folders_) {
    if (!folder->empty()) requireFolder(*folder, name.c_str());
  }
}

void CommandLine::models(std::vector<std::string>& into, bool ragdollModels, const std::string& note) {
  add(option::kModels, "--models LIST", needsOf<phys::BodyModel>(option::kModels),
      helpText(option::kModels, note), false,
      [ragdollModels, append = listAppender(into)](const std::string& text) {
        return readList(text, [&](const std::string& item) {
          const bool known = phys::parseBodyModel(item) || (ragdollModels && phys::parseRagdollModel(item));
          if (!known) {
            return "unknown model '" + item + "' (corners, tetra or rigid" +
                   (ragdollModels ? std::string("; seed or lean for ragdolls)") : std::string(")"));
          }
          append(item);
          return std::string();
        });
      });
}

void CommandLine::flag(const OptionSpec& spec, bool& into, bool value, const std::string& note) {
  // A flag takes no value: CLI11 would read "--json=no" as off and "--json=" as on.
  app_->add_flag_callback(spec.names, [&into, value] { into = value; })->disable_flag_override();
  if (const auto names = splitList(spec.names)) flags_.insert(flags_.end(), names->begin(), names->end());
  entries_.push_back({spec.names, spec.names, helpText(spec, note), ""});
}

void CommandLine::custom(const OptionSpec& spec, bool many,
                         std::function<std::string(const std::string&)> read, const std::string& note) {
  add(spec, std::string(firstName(spec.names)) + " " + spec.value, spec.needs != nullptr ? spec.needs : "",
      helpText(spec, note), many, std::move(read));
}

void CommandLine::require(const OptionSpec& spec, std::string why) {
  required_.emplace_back(firstName(spec.names), std::move(why));
}

std::vector<std::string> CommandLine::positionalWords() const {
  if (positionalName_.empty()) return {};
  return app_->get_option(positionalName_)->results();
}

std::string CommandLine::parse(const std::vector<std::string>& args) {
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  // The first word CLI11 did not take; it keeps a "--" it passed in remaining().
  auto firstExtra = [this] {
    std::vector<std::string> extras = app_->remaining();
    extras.erase(std::remove(extras.begin(), extras.end(), "--"), extras.end());
    return extras.empty() ? std::string() : extras.front();
  };
  auto isOption = [](const std::string& word) { return word.size() > 1 && word[0] == '-'; };
  // CLI11 refuses a value given to a flag ("--json=no") but takes an empty one ("--json=") as on.
  for (const std::string& arg : args) {
    const std::size_t eq = arg.find('=');
    if (!arg.starts_with("--") || eq == std::string::npos) continue;
    const std::string name = arg.substr(0, eq);
    if (std::find(flags_.begin(), flags_.end(), name) != flags_.end()) return name + " takes no value";
    // CLI11 takes "--out=" for a missing value; it is an empty one, said as "--out ''" is.
    if (eq + 1 == arg.size()) {
      for (const Entry& entry : entries_) {
        const std::optional<std::vector<std::string>> spellings = splitList(entry.names);
        if (spellings && std::find(spellings->begin(), spellings->end(), name) != spellings->end())
          return emptyValue(firstName(entry.names), entry.needs);
      }
    }
  }
  try {
    app_->parse(reversed);
  } catch (const OptionError& e) {
    // An unknown option's value can be read as the positional ("lab scale --data DIR" read DIR as
    // a KIND): the unknown option is the mistake to name.
    if (const std::string extra = firstExtra(); isOption(extra)) return "unknown option '" + extra + "'";
    return e.what();
  } catch (const CLI::ExtrasError&) {
    std::string extra = firstExtra();
    if (extra.empty()) extra = "?";
    if (isOption(extra)) return "unknown option '" + extra + "'";
    if (const std::vector<std::string> given = positionalWords(); !given.empty()) {
      return command_ + " takes one " + positionalName_ + "; got '" + given.front() + "' and '" + extra + "'";
    }
    return "unexpected argument '" + extra + "'";
  } catch (const CLI::ArgumentMismatch& e) {
    // "--steps: 1 required N missing": a value missing at the end of the line. (A value given to a
    // flag, "--json=banana", never gets here: the scan above names it.)
    std::string what = e.what();  // not const: returned, so moved
    const std::string name = what.substr(0, what.find(':'));
    for (const Entry& entry : entries_) {
      if (firstName(entry.names) == name && !entry.needs.empty()) return name + " needs " + entry.needs;
    }
    return what;
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  // CLI11 validates no empty word, so an empty positional ("lab run ''") is caught here.
  for (const std::string& word : positionalWords()) {
    if (word.empty()) return command_ + ": the " + positionalName_ + " is empty";
  }
  for (const auto& [name, why] : required_) {
    const bool given = name == "SCENE" ? !positionalWords().empty() : app_->count(name) > 0;
    if (!given) return why;
  }
  return {};
}

std::string CommandLine::help() const {
  std::string usage = "usage: lab " + command_;
  for (const Entry& e : entries_) {
    const bool required = std::any_of(required_.begin(), required_.end(), [&](const auto& r) {
      return r.first == (e.names.empty() ? e.label : firstName(e.names));
    });
    if (e.names.empty())
      usage += " " + (required || e.label.starts_with("[") ? e.label : "[" + e.label + "]");
    else if (required)
      usage += " " + e.label;
  }
  std::string out = usage + " [options]\n";
  if (!about_.empty()) {
    std::istringstream lines(about_);
    for (std::string line; std::getline(lines, line);) out += "  " + line + "\n";
  }
  std::vector<Entry> all = entries_;
  all.push_back({"--help", "--help", "show this text", ""});
  for (const Entry& e : all) {
    std::string line = "  " + e.label;
    if (line.size() + 1 >= kLabelWidth)
      line += "\n" + std::string(kLabelWidth, ' ');
    else
      line.resize(kLabelWidth, ' ');
    out += line + wrapped(e.help, kLabelWidth, kLabelWidth) + "\n";
  }
  return out;
}

int commandMain(CommandLine& line, const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                const std::function<int()>& body) {
  if (asksForHelp(args)) {
    out << line.help();
    return kExitOk;
  }
  if (const std::string e = line.parse(args); !e.empty()) {
    err << "lab: " << e << "\n" << line.help();
    return kExitUsage;
  }
  try {
    line.requireGivenFolders();
    return body();
  } catch (const UsageError& e) {
    err << "lab: " << e.what() << "\n" << line.help();
    return kExitUsage;
  } catch (const CommandFailure& e) {
    err << "lab: " << e.what() << "\n";
  } catch (const scenes::LoadError& e) {
    err << e.what() << "\n";  // already "file:line: ...", the form editors jump to
  } catch (const std::invalid_argument& e) {
    // A combination the world refuses (each value's range was checked above).
    err << "lab: " << line.command() << ": the settings were refused: " << e.what() << "\n";
  } catch (const std::bad_alloc&) {
    err << "lab: " << line.command()
        << ": out of memory (the scene or the run is too large for this machine)\n";
  } catch (const std::exception& e) {
    err << "lab: " << line.command() << ": " << e.what() << "\n";
  }
  return kExitFailure;
}

void asOptionFailure(const char* option, const std::function<void()>& fileWork) {
  try {
    fileWork();
  } catch (const fileio::FileError& e) {
    throw CommandFailure(std::string(option) + ": " + e.what());
  }
}

void prepareOutputFolder(const std::filesystem::path& folder, const char* option) {
  asOptionFailure(option, [&] { fileio::prepareFolder(folder); });
}

void checkOutputFile(const std::filesystem::path& file, const char* option) {
  asOptionFailure(option, [&] { fileio::checkWritable(file); });
}

void prepareOutputFiles(const std::filesystem::path& folder, const std::vector<std::string>& names,
                        const char* option) {
  prepareOutputFolder(folder, option);
  for (const std::string& name : names) checkOutputFile(folder / name, option);
}

void refuseOutputsOverScenes(const std::filesystem::path& folder, const std::vector<std::string>& names,
                             const std::vector<std::filesystem::path>& scenes, const char* option) {
  for (const std::string& name : names) {
    for (const std::filesystem::path& scene : scenes) {
      std::error_code ec;  // a file that is not there yet is no scene
      if (std::filesystem::equivalent(folder / name, scene, ec)) {
        throw CommandFailure(std::string(option) + ": " + (folder / name).string() + ": is the scene " +
                             scene.string() + " being run; the output would write over it");
      }
    }
  }
}

void requireFolder(const std::filesystem::path& folder, const char* option) {
  if (const std::string why = fileio::folderProblem(folder); !why.empty())
    throw CommandFailure(std::string(option) + ": " + folder.string() + ": " + why);
}

std::filesystem::path dataDir(const std::filesystem::path& given) {
  return given.empty() ? std::filesystem::path(LAB_DATA_DIR) : given;
}

std::filesystem::path sceneFile(const std::string& scene, const std::filesystem::path& dataGiven) {
  return scenes::resolveScene(scene, scenes::sceneDirectory(dataDir(dataGiven)));
}

}  // namespace lab
