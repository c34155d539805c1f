#include "file_dialog.h"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <system_error>

namespace sandbox {
namespace {

namespace fs = std::filesystem;

const ImVec4 kErrorColor(1.0f, 0.4f, 0.4f, 1.0f);

char lower(char c) {
  return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
}

// Case-insensitive, so "Scene.XML" written by another tool still shows up.
bool endsWith(std::string_view name, std::string_view suffix) {
  if (name.size() < suffix.size()) return false;
  return std::equal(suffix.begin(), suffix.end(), name.end() - static_cast<std::ptrdiff_t>(suffix.size()),
                    [](char a, char b) { return lower(a) == lower(b); });
}

// Case-insensitive first, so "Box" sits next to "box" the way people read a listing; the exact
// comparison breaks ties so the order never depends on the file system's.
bool byName(const DirectoryEntry& a, const DirectoryEntry& b) {
  auto folded = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), lower);
    return s;
  };
  const std::string fa = folded(a.name);
  const std::string fb = folded(b.name);
  return fa != fb ? fa < fb : a.name < b.name;
}

// Absolute and without "." / ".." or a trailing separator, so the header shows one spelling of
// each folder and "Up" is just parent_path().
fs::path cleanFolder(const fs::path& folder) {
  std::error_code ec;
  fs::path out = fs::absolute(folder, ec).lexically_normal();
  if (ec) out = folder.lexically_normal();
  if (!out.has_filename() && out.has_relative_path()) out = out.parent_path();
  return out;
}

// What is at `path`: a type, not_found when nothing is there, or none with `why` set to the
// system's reason it cannot be looked at (a name too long, a folder on the way that cannot be
// searched), which is not the same as its not being there.
fs::file_type typeAt(const fs::path& path, std::string& why) {
  std::error_code ec;
  const fs::file_type type = fs::status(path, ec).type();
  if (ec && type != fs::file_type::not_found) why = "cannot look at " + path.string() + ": " + ec.message();
  return type;
}

}  // namespace

std::vector<DirectoryEntry> listDirectory(const fs::path& folder, std::string_view extension,
                                          std::string* error) {
  if (error != nullptr) error->clear();
  std::vector<DirectoryEntry> folders;
  std::vector<DirectoryEntry> files;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    std::error_code typeError;  // a dangling link or a vanished entry is just left out
    std::string name = it->path().filename().string();
    if (it->is_directory(typeError)) {
      folders.push_back({std::move(name), true});
    } else if (it->is_regular_file(typeError) && endsWith(name, extension)) {
      files.push_back({std::move(name), false});
    }
  }
  if (ec) {
    if (error != nullptr) *error = "cannot list " + folder.string() + ": " + ec.message();
    return {};
  }
  std::sort(folders.begin(), folders.end(), byName);
  std::sort(files.begin(), files.end(), byName);
  std::vector<DirectoryEntry> out;
  if (cleanFolder(folder).has_relative_path()) out.push_back({"..", true});  // a root has no parent
  out.insert(out.end(), folders.begin(), folders.end());
  out.insert(out.end(), files.begin(), files.end());
  return out;
}

TypedPath resolveTypedPath(FileDialogMode mode, const fs::path& folder, std::string_view typed,
                           std::string_view extension) {
  TypedPath out;
  if (typed.empty()) {
    out.message = mode == FileDialogMode::Open ? "pick a file or type its path" : "type a file name";
    return out;
  }
  fs::path path(typed);
  if (path.is_relative()) path = folder / path;
  path = path.lexically_normal();
  std::string why;  // the system's reason a path on the way cannot be looked at
  fs::file_type type = typeAt(path, why);
  if (type == fs::file_type::directory) {
    out.action = TypedPath::Action::EnterFolder;
    out.path = cleanFolder(path);
    return out;
  }
  if (why.empty() && mode == FileDialogMode::Save && path.has_filename() && !path.has_extension()) {
    path += extension;
    type = typeAt(path, why);
  }
  const fs::path parent = path.parent_path();
  if (!why.empty()) {
    out.message = why;
  } else if (mode == FileDialogMode::Open && type != fs::file_type::regular) {
    out.message = type == fs::file_type::not_found ? "no such file: " + path.string()
                                                   : path.string() + " is not a regular file";
  } else if (mode == FileDialogMode::Save && typeAt(parent, why) != fs::file_type::directory) {
    out.message = why.empty() ? "no such folder: " + parent.string() : why;
  } else if (mode == FileDialogMode::Save && type != fs::file_type::not_found &&
             type != fs::file_type::regular) {
    out.message = path.string() + " exists and is not a regular file";
  } else {
    out.action = TypedPath::Action::Choose;
    out.path = path;
    out.replaces = mode == FileDialogMode::Save && type == fs::file_type::regular;
  }
  return out;
}

void FileDialog::open(FileDialogMode mode, const fs::path& folder, const std::string& title,
                      std::string_view extension) {
  open_ = true;
  extension_ = extension;
  justOpened_ = true;  // OpenPopup must run inside the ImGui frame, so draw() does it
  mode_ = mode;
  title_ = title;
  typed_[0] = '\0';
  focusPath_ = true;  // type a name straight away
  enterFolder(folder);
}

void FileDialog::enterFolder(const fs::path& folder) {
  folder_ = cleanFolder(folder);
  entries_ = listDirectory(folder_, extension_, &listError_);
  message_.clear();
  replacing_.clear();
  // A name typed for saving should follow the user into the new folder; a file picked for
  // opening belonged to the old one.
  const std::string name =
      mode_ == FileDialogMode::Save ? fs::path(typed_).filename().string() : std::string();
  std::snprintf(typed_, sizeof typed_, "%s", name.c_str());
}

std::optional<fs::path> FileDialog::accept() {
  const TypedPath result = resolveTypedPath(mode_, folder_, typed_, extension_);
  switch (result.action) {
    case TypedPath::Action::Choose:
      // A recording saved as "ragdoll.xml" replaced the scene without a word: ask once.
      if (result.replaces && result.path != replacing_) {
        replacing_ = result.path;
        message_ = result.path.filename().string() + " exists: Replace writes over it";
        return std::nullopt;
      }
      return result.path;
    case TypedPath::Action::EnterFolder:
      typed_[0] = '\0';  // the text was the folder itself; keeping it would point inside itself
      enterFolder(result.path);
      return std::nullopt;
    case TypedPath::Action::Refuse:
      message_ = result.message;
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<fs::path> FileDialog::draw() {
  if (!open_) return std::nullopt;
  if (justOpened_) {
    ImGui::OpenPopup(title_.c_str());
    justOpened_ = false;
  }
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(640.0f, 420.0f), ImGuiCond_Appearing);
  // The title bar's close button clears open_ through the pointer.
  if (!ImGui::BeginPopupModal(title_.c_str(), &open_)) {
    open_ = false;
    return std::nullopt;
  }
  std::optional<fs::path> chosen;
  bool cancelled = false;

  ImGui::TextUnformatted(folder_.string().c_str());
  if (ImGui::Button("Up")) enterFolder(folder_.parent_path());
  if (!listError_.empty()) {
    ImGui::SameLine();
    ImGui::TextColored(kErrorColor, "%s", listError_.c_str());
  }

  // Leave room under the list for the path field, its message line and the buttons.
  const float footer = ImGui::GetFrameHeightWithSpacing() * 2.0f + ImGui::GetTextLineHeightWithSpacing();
  ImGui::BeginChild("entries", ImVec2(0.0f, -footer), true);
  std::optional<fs::path> folderToEnter;  // entered after the loop, which walks entries_
  const ImGuiSelectableFlags flags =
      ImGuiSelectableFlags_AllowDoubleClick | ImGuiSelectableFlags_DontClosePopups;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const DirectoryEntry& entry = entries_[i];
    const fs::path full = folder_ / entry.name;
    ImGui::PushID(static_cast<int>(i));
    if (entry.isFolder) {
      if (ImGui::Selectable((entry.name + "/").c_str(), false, flags)) folderToEnter = full;
    } else {
      // The field holds the full path, or, when that does not fit it, the name alone, which
      // resolves against the folder shown: a path cut short would name another file.
      const std::string picked = full.string().size() < sizeof typed_ ? full.string() : entry.name;
      const bool selected = picked == typed_;
      if (ImGui::Selectable(entry.name.c_str(), selected, flags)) {
        std::snprintf(typed_, sizeof typed_, "%s", picked.c_str());
        message_.clear();
        replacing_.clear();
        // Only a double click on the file already picked confirms: the second click of a
        // double click on a folder lands on whatever the new listing shows in its place.
        if (selected && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) chosen = accept();
      }
    }
    ImGui::PopID();
  }
  ImGui::EndChild();
  if (folderToEnter) enterFolder(*folderToEnter);

  ImGui::SetNextItemWidth(-1.0f);
  if (focusPath_) ImGui::SetKeyboardFocusHere();
  // Enter leaves the field; when the dialog stays open (a folder entered, a path refused) the
  // field takes the keyboard back so the user can keep typing.
  const bool enterPressed =
      ImGui::InputText("##path", typed_, sizeof typed_, ImGuiInputTextFlags_EnterReturnsTrue);
  if (ImGui::IsItemEdited() && !replacing_.empty()) {  // another name: the question was of the old one
    replacing_.clear();
    message_.clear();
  }
  ImGui::TextColored(kErrorColor, "%s", message_.c_str());  // an empty line keeps the layout still
  const char* button = mode_ == FileDialogMode::Open ? "Open" : replacing_.empty() ? "Save" : "Replace";
  if (ImGui::Button(button) || enterPressed) chosen = accept();
  focusPath_ = enterPressed && !chosen;
  ImGui::SameLine();
  if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
    cancelled = true;

  if (chosen || cancelled) {
    open_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  return chosen;
}

}  // namespace sandbox
