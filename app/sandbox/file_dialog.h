#pragma once
// An ImGui file browser for File > Open, Save As and the recordings: a folder listing (folders
// first, then the files with the wanted extension), a typed path, and OK / Cancel.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sandbox {

enum class FileDialogMode { Open, Save };

struct DirectoryEntry {
  std::string name;  ///< file or folder name, no path
  bool isFolder = false;
};

/// The folders (plus ".." unless `folder` is a root) and the files ending in `extension` in
/// `folder`, folders first, each group sorted by name. Unreadable folders give an empty list
/// and a message in `error`.
std::vector<DirectoryEntry> listDirectory(const std::filesystem::path& folder, std::string_view extension,
                                          std::string* error = nullptr);

/// What OK does with the typed text: enter a folder, choose a file, or refuse with a message.
/// Relative text is taken from `folder`. Open wants an existing regular file; Save wants a name in
/// an existing folder and adds `extension` (a scene's ".xml", a recording's) when it has none.
struct TypedPath {
  enum class Action { EnterFolder, Choose, Refuse };
  Action action = Action::Refuse;
  std::filesystem::path path;  ///< the folder to enter or the file chosen
  std::string message;         ///< why it was refused
  bool replaces = false;       ///< Save chose a file that exists: the dialog asks before writing over it
};
TypedPath resolveTypedPath(FileDialogMode mode, const std::filesystem::path& folder, std::string_view typed,
                           std::string_view extension = ".xml");

class FileDialog {
 public:
  /// Starts showing the dialog in `folder`, listing the files ending in `extension`; `title` is
  /// its window title.
  void open(FileDialogMode mode, const std::filesystem::path& folder, const std::string& title,
            std::string_view extension = ".xml");
  bool isOpen() const { return open_; }
  /// Draws the dialog if it is open (inside an ImGui frame). Returns the chosen path once, on the
  /// frame the user confirms; the dialog then closes. Save onto a file that exists only says so,
  /// and its button turns to Replace: a second press writes over it.
  std::optional<std::filesystem::path> draw();
  /// What the line under the path field says: why a path was refused, or that Save would replace a file.
  const std::string& message() const { return message_; }

 private:
  // see file_dialog.cpp
  void enterFolder(const std::filesystem::path& folder);
  std::optional<std::filesystem::path> accept();

  bool open_ = false;
  bool justOpened_ = false;
  FileDialogMode mode_ = FileDialogMode::Open;
  std::string title_;
  std::string extension_ = ".xml";
  std::filesystem::path folder_;
  std::vector<DirectoryEntry> entries_;
  std::string listError_;
  char typed_[1024] = {};
  bool focusPath_ = false;           ///< give the path field the keyboard on the next frame
  std::string message_;              ///< why the typed path was refused, shown under the field
  std::filesystem::path replacing_;  ///< the existing file the next Save writes over; empty: none asked
};

}  // namespace sandbox
