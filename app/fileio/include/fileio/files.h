#pragma once
// Every file the project writes (scenes, screenshots, dumps, CSVs, charts, reports, settings)
// goes through writeAtomically, and every file it reads whole through readWhole, so that a
// full disk, a symbolic link, a folder in the way or a device never loses a file or hangs, and
// every failure says which file and why, in the operating system's words.
#include <cstddef>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fileio {

/// A file that could not be written or read. what() reads "FILE: what failed: the OS's reason".
class FileError : public std::runtime_error {
 public:
  FileError(std::filesystem::path file, const std::string& message);
  const std::filesystem::path& file() const { return file_; }
  /// What failed and why, without the file name.
  const std::string& message() const { return message_; }

 private:
  std::filesystem::path file_;
  std::string message_;
};

/// Replaces `file` with `content` all at once (docs/architecture.md, "Files"):
/// - the content goes to a new file of a unique name in the target's folder, created
///   exclusively (never through an existing file or link of that name), every write checked;
/// - it is flushed to disk, closed (checked), renamed over the target, and the folder flushed,
///   so a reader or a crash sees the old file or the new one, never a mix;
/// - a symbolic link is followed, dangling or not, and what it points at is written; the link
///   stays a link;
/// - a replaced file keeps its permissions; a new one gets 0666 less the umask.
/// On any failure it throws FileError naming `file`, the target keeps its old content and the
/// temporary file is gone. An empty name, a folder as the target and a link loop are refused
/// before anything is written.
void writeAtomically(const std::filesystem::path& file, std::string_view content);

/// A file to write and what to write in it.
struct FileContent {
  std::filesystem::path file;
  std::string_view content;
};

/// Replaces the files as one set, each as writeAtomically would: every new content is written
/// and flushed to disk first, and only once all of them are there are they renamed into place,
/// so a failure on any file (a full disk, a folder in the way) leaves every target with its old
/// content. The renames themselves can fail only if the folders change under us; then the
/// files renamed before stay new, and FileError names the one that failed.
void writeAllAtomically(std::span<const FileContent> files);

/// Makes sure `folder` exists (creating it and its parents) and that a file can be created in
/// it, by creating one and removing it; throws FileError with the OS's reason otherwise. For
/// commands that write their results at the end of a long run: they can say so at the start.
void prepareFolder(const std::filesystem::path& folder);

/// Fails as writeAtomically(file, ...) would before its first byte, and writes nothing: a name that
/// is empty, a folder, a device or a pipe, a link loop, and a folder that is missing, read-only or
/// full of names (by creating the temporary file there and removing it). For commands that write a
/// file at the end of a long run: they can say so at the start. What only writing finds out (a
/// full disk) is still said by writeAtomically.
void checkWritable(const std::filesystem::path& file);

/// What `file` names once symbolic links are followed (as many as the OS would, relative ones
/// from the link's folder): the file writeAtomically replaces. The last one may not exist.
/// Throws FileError on a loop or an unreadable link.
std::filesystem::path followLinks(const std::filesystem::path& file);

/// The whole content of a file: a regular file, or a pipe or device read until its end. Throws
/// FileError with the OS's reason when it cannot be opened or read, when it is a folder, and
/// when it holds more than maxBytes (so /dev/zero is refused, not read until memory runs out).
/// `kind` names what the file is meant to be in the messages ("shader file": "cannot open shader
/// file: ...", "is a folder, not a shader file"); without it they say "file" or nothing.
std::string readWhole(const std::filesystem::path& file, std::size_t maxBytes, std::string_view kind = {});

/// Opens `file` and closes it again, for a reader that says less than FileError does (assimp:
/// "Unable to open file") and must only be handed a file it can open: the failures of readWhole
/// (`kind` as there), and anything but a regular file, which such a reader would wait on for ever
/// (a pipe with no writer) or seek in.
void checkRegularFile(const std::filesystem::path& file, std::string_view kind);

/// "" when `folder` is a folder (or a link to one), else the OS's reason: the one it gave for
/// looking at the path ("No such file or directory", "Permission denied"), or, for anything but a
/// folder, the reason it gives when a path goes through a file ("Not a directory").
std::string folderProblem(const std::filesystem::path& folder);

}  // namespace fileio
