// The one writer and the one reader (app/fileio): a file is replaced whole or not at all, no
// name but its own and one hidden temporary file of its own is ever touched, links are
// followed as documented, and every failure names the file and gives the OS's reason.
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fileio/files.h"
#include "temp_folder.h"
#include "unprivileged.h"

namespace {

namespace fs = std::filesystem;
using testing_app::TempFolder;

std::string readFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeFile(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

std::vector<std::string> entries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// The FileError's message, or "" when nothing was thrown.
std::string writeError(const fs::path& file, std::string_view content) {
  try {
    fileio::writeAtomically(file, content);
  } catch (const fileio::FileError& e) {
    return e.what();
  }
  return {};
}

std::string readError(const fs::path& file, std::size_t maxBytes = 1 << 20) {
  try {
    fileio::readWhole(file, maxBytes);
  } catch (const fileio::FileError& e) {
    return e.what();
  }
  return {};
}

mode_t modeOf(const fs::path& file) {
  struct stat s {};
  ::stat(file.c_str(), &s);
  return s.st_mode & 07777;
}

TEST(AtomicWrite, ReplacesTheWholeFileAndKeepsItsPermissions) {
  const TempFolder folder;
  const fs::path file = folder.path / "out.csv";
  writeFile(file, "an old and longer content\n");
  ::chmod(file.c_str(), 0640);
  fileio::writeAtomically(file, "new\n");
  EXPECT_EQ(readFile(file), "new\n");
  EXPECT_EQ(modeOf(file), 0640u);
  EXPECT_EQ(entries(folder.path), std::vector<std::string>{"out.csv"});
}

TEST(AtomicWrite, ANewFileGetsTheUmasksPermissions) {
  const TempFolder folder;
  const mode_t old = ::umask(027);
  fileio::writeAtomically(folder.path / "new.txt", "x");
  ::umask(old);
  EXPECT_EQ(modeOf(folder.path / "new.txt"), 0640u);
}

// The old writers used FILE.tmp: a link there sent the content into the file it pointed at, and
// a user's own FILE.tmp was lost. The temporary name is now unique and created exclusively.
TEST(AtomicWrite, NeverTouchesAnotherFileOrLinkBesideTheTarget) {
  const TempFolder folder;
  const fs::path victim = folder.path / "victim.txt";
  writeFile(victim, "precious");
  fs::create_symlink(victim, folder.path / "out.csv.tmp");
  fs::create_symlink(victim, folder.path / ".out.csv.tmp");
  writeFile(folder.path / "out.png.tmp", "the user's own");
  fileio::writeAtomically(folder.path / "out.csv", "data");
  fileio::writeAtomically(folder.path / "out.png", "image");
  EXPECT_EQ(readFile(victim), "precious");
  EXPECT_TRUE(fs::is_symlink(folder.path / "out.csv.tmp"));
  EXPECT_EQ(readFile(folder.path / "out.png.tmp"), "the user's own");
  EXPECT_EQ(entries(folder.path), (std::vector<std::string>{".out.csv.tmp", "out.csv", "out.csv.tmp",
                                                            "out.png", "out.png.tmp", "victim.txt"}));
}

TEST(AtomicWrite, AFolderAsTheTargetIsRefusedAndNothingIsLeftBehind) {
  const TempFolder folder;
  fs::create_directory(folder.path / "adir.png");
  EXPECT_NE(writeError(folder.path / "adir.png", "x").find("adir.png: is a folder, not a file"),
            std::string::npos);
  EXPECT_NE(writeError(folder.path / "sub/", "x").find("names a folder"), std::string::npos);
  EXPECT_EQ(entries(folder.path), std::vector<std::string>{"adir.png"});
  EXPECT_TRUE(fs::is_empty(folder.path / "adir.png"));
}

TEST(AtomicWrite, AnEmptyNameIsRefused) {
  EXPECT_NE(writeError("", "x").find("no file name given"), std::string::npos);
}

// Renaming over a device or a pipe would replace it with a regular file (as root, --dump
// /dev/null would have replaced the device).
TEST(AtomicWrite, APipeOrDeviceIsNotReplaced) {
  const TempFolder folder;
  const fs::path fifo = folder.path / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(writeError(fifo, "x").find("is not a regular file"), std::string::npos);
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(entries(folder.path), std::vector<std::string>{"pipe"});
}

TEST(AtomicWrite, ALinkIsFollowedAndStaysALink) {
  const TempFolder folder;
  fs::create_directory(folder.path / "real");
  writeFile(folder.path / "real" / "scene.xml", "old");
  fs::create_symlink("real/scene.xml", folder.path / "link.xml");  // relative to the link's folder
  fileio::writeAtomically(folder.path / "link.xml", "new");
  EXPECT_TRUE(fs::is_symlink(folder.path / "link.xml"));
  EXPECT_EQ(readFile(folder.path / "real" / "scene.xml"), "new");
  EXPECT_EQ(entries(folder.path / "real"), std::vector<std::string>{"scene.xml"});
}

// A dangling link was replaced by a regular file; it names the file to create.
TEST(AtomicWrite, ADanglingLinkCreatesTheFileItNames) {
  const TempFolder folder;
  fs::create_directory(folder.path / "real");
  fs::create_symlink("real/new.xml", folder.path / "link.xml");
  fs::create_symlink("link.xml", folder.path / "link2.xml");  // a chain of two
  fileio::writeAtomically(folder.path / "link2.xml", "made");
  EXPECT_TRUE(fs::is_symlink(folder.path / "link.xml"));
  EXPECT_TRUE(fs::is_symlink(folder.path / "link2.xml"));
  EXPECT_EQ(readFile(folder.path / "real" / "new.xml"), "made");
}

TEST(AtomicWrite, ALinkLoopIsRefusedWithTheOsReason) {
  const TempFolder folder;
  fs::create_symlink("b", folder.path / "a");
  fs::create_symlink("a", folder.path / "b");
  EXPECT_NE(writeError(folder.path / "a", "x").find("Too many levels of symbolic links"), std::string::npos);
  EXPECT_EQ(entries(folder.path), (std::vector<std::string>{"a", "b"}));
}

TEST(AtomicWrite, AMissingFolderOrAFileAsAFolderSaysSo) {
  const TempFolder folder;
  writeFile(folder.path / "plain", "x");
  EXPECT_NE(writeError(folder.path / "missing" / "out.csv", "x").find("No such file or directory"),
            std::string::npos);
  EXPECT_NE(writeError(folder.path / "plain" / "out.csv", "x").find("Not a directory"), std::string::npos);
  EXPECT_EQ(entries(folder.path), std::vector<std::string>{"plain"});
}

// A full disk, made the way any user can make one: a file size limit, under which write() fails
// part way as it does with ENOSPC (stb's PNG writer ignored this and reported success). The old
// content must survive and the partial file must go.
TEST(AtomicWrite, AFullDiskKeepsTheOldFileAndSaysWhy) {
  const TempFolder folder;
  const fs::path file = folder.path / "shot.png";
  writeFile(file, "the old screenshot");
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);  // else the write kills the process
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string error = writeError(file, std::string(100000, 'x'));
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previous);
  EXPECT_NE(error.find("shot.png: cannot write: File too large"), std::string::npos) << error;
  EXPECT_EQ(readFile(file), "the old screenshot");
  EXPECT_EQ(entries(folder.path), std::vector<std::string>{"shot.png"});
}

// A set of files is replaced together: when the disk fills on the last one, the first two, whose
// new content was already written, keep their old content too, and no temporary file is left.
TEST(AtomicWrite, ASetOfFilesIsReplacedTogetherOrNotAtAll) {
  const TempFolder folder;
  for (const char* name : {"a.csv", "b.csv", "c.png"}) writeFile(folder.path / name, "old");
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto previous = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string big(100000, 'x');
  const fileio::FileContent set[] = {
      {folder.path / "a.csv", "new"}, {folder.path / "b.csv", "new"}, {folder.path / "c.png", big}};
  std::string error;
  try {
    fileio::writeAllAtomically(set);
  } catch (const fileio::FileError& e) {
    error = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previous);
  EXPECT_NE(error.find("c.png: cannot write: File too large"), std::string::npos) << error;
  for (const char* name : {"a.csv", "b.csv", "c.png"}) EXPECT_EQ(readFile(folder.path / name), "old") << name;
  EXPECT_EQ(entries(folder.path), (std::vector<std::string>{"a.csv", "b.csv", "c.png"}));
  // With room, all three are new.
  fileio::writeAllAtomically(set);
  for (const char* name : {"a.csv", "b.csv"}) EXPECT_EQ(readFile(folder.path / name), "new") << name;
  EXPECT_EQ(readFile(folder.path / "c.png"), big);
}

TEST(AtomicWrite, AReadOnlyFolderFailsEvenWhenTheTestsRunAsRoot) {
  const TempFolder folder;
  const fs::path locked = folder.path / "locked";
  fs::create_directory(locked);
  writeFile(locked / "out.csv", "old");
  fs::permissions(folder.path, fs::perms::owner_all | fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::others_read |
                              fs::perms::others_exec);
  const std::string error = testing_app::runAsNobody([&] { return writeError(locked / "out.csv", "new"); });
  EXPECT_NE(error.find("cannot create a temporary file in '" + locked.string() + "': Permission denied"),
            std::string::npos)
      << error;
  EXPECT_EQ(readFile(locked / "out.csv"), "old");
  EXPECT_EQ(entries(locked), std::vector<std::string>{"out.csv"});
  fs::permissions(locked, fs::perms::owner_all);
}

TEST(ReadWhole, ReadsAFileWhole) {
  const TempFolder folder;
  writeFile(folder.path / "a.txt", std::string(200000, 'a'));
  EXPECT_EQ(fileio::readWhole(folder.path / "a.txt", 200000), std::string(200000, 'a'));
}

TEST(ReadWhole, SaysWhyItCannotRead) {
  const TempFolder folder;
  EXPECT_NE(
      readError(folder.path / "missing.xml").find("missing.xml: cannot open: No such file or directory"),
      std::string::npos);
  EXPECT_NE(readError(folder.path).find("is a folder, not a file"), std::string::npos);
  writeFile(folder.path / "big.txt", std::string(2000, 'b'));
  EXPECT_NE(readError(folder.path / "big.txt", 1999).find("is larger than 1999 bytes"), std::string::npos);
  // A device without end is cut off at the limit instead of filling memory.
  EXPECT_NE(readError("/dev/zero").find("/dev/zero: is larger than"), std::string::npos);
}

// A named pipe nobody writes to held open() for ever (`lab run FIFO` hung): it reads as empty now.
// In a child process with an alarm, so that a hang fails the test instead of holding it.
TEST(ReadWhole, APipeWithNoWriterDoesNotHang) {
  const TempFolder folder;
  const fs::path fifo = folder.path / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::alarm(5);
    _exit(fileio::readWhole(fifo, 100).empty() ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status)) << "killed by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0);
}

// A pipe that has a writer is read whole, as before: reads block again once it is open.
TEST(ReadWhole, APipeWithAWriterIsReadWhole) {
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  ASSERT_EQ(::write(ends[1], "<scene/>", 8), 8);
  ::close(ends[1]);
  EXPECT_EQ(fileio::readWhole("/dev/fd/" + std::to_string(ends[0]), 100), "<scene/>");
  ::close(ends[0]);
}

TEST(ReadWhole, AnUnreadableFileGivesTheOsReason) {
  const TempFolder folder;
  fs::permissions(folder.path, fs::perms::owner_all | fs::perms::others_read | fs::perms::others_exec);
  writeFile(folder.path / "secret.xml", "<scene/>");
  fs::permissions(folder.path / "secret.xml", fs::perms::owner_read);
  const std::string error = testing_app::runAsNobody([&] { return readError(folder.path / "secret.xml"); });
  EXPECT_NE(error.find("secret.xml: cannot open: Permission denied"), std::string::npos) << error;
}

TEST(PrepareFolder, CreatesTheFolderOrSaysWhyItCannotBeWritten) {
  const TempFolder folder;
  fileio::prepareFolder(folder.path / "a" / "b");
  EXPECT_TRUE(fs::is_directory(folder.path / "a" / "b"));
  EXPECT_TRUE(fs::is_empty(folder.path / "a" / "b"));  // the probe file is gone
  writeFile(folder.path / "plain", "x");
  EXPECT_THROW(fileio::prepareFolder(folder.path / "plain" / "out"), fileio::FileError);
  fs::create_directory(folder.path / "locked");
  fs::permissions(folder.path, fs::perms::owner_all | fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(folder.path / "locked", fs::perms::owner_read | fs::perms::owner_exec |
                                              fs::perms::others_read | fs::perms::others_exec);
  const std::string error = testing_app::runAsNobody([&] {
    try {
      fileio::prepareFolder(folder.path / "locked");
    } catch (const fileio::FileError& e) {
      return std::string(e.what());
    }
    return std::string();
  });
  EXPECT_NE(error.find("Permission denied"), std::string::npos) << error;
  fs::permissions(folder.path / "locked", fs::perms::owner_all);
}

std::string checkWritableError(const fs::path& file) {
  try {
    fileio::checkWritable(file);
  } catch (const fileio::FileError& e) {
    return e.what();
  }
  return {};
}

// What writeAtomically would refuse before writing is refused by checkWritable, which writes
// nothing: a long run checks its output file first.
TEST(CheckWritable, RefusesWhatWriteAtomicallyWouldAndLeavesNothingBehind) {
  const TempFolder folder;
  writeFile(folder.path / "old.csv", "old");
  EXPECT_EQ(checkWritableError(folder.path / "old.csv"), "");
  EXPECT_EQ(checkWritableError(folder.path / "new.csv"), "");
  EXPECT_EQ(readFile(folder.path / "old.csv"), "old");
  EXPECT_EQ(entries(folder.path), std::vector<std::string>{"old.csv"});
  EXPECT_NE(checkWritableError("/dev/null").find("/dev/null: is not a regular file"), std::string::npos);
  EXPECT_NE(checkWritableError(folder.path).find("is a folder"), std::string::npos);
  EXPECT_NE(checkWritableError(folder.path / "missing" / "x.csv").find("No such file or directory"),
            std::string::npos);
  EXPECT_NE(checkWritableError("").find("no file name given"), std::string::npos);
  fs::create_directory(folder.path / "locked");
  fs::permissions(folder.path, fs::perms::owner_all | fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(folder.path / "locked", fs::perms::owner_read | fs::perms::owner_exec |
                                              fs::perms::others_read | fs::perms::others_exec);
  const fs::path locked = folder.path / "locked" / "out.csv";
  const std::string error = testing_app::runAsNobody([&] { return checkWritableError(locked); });
  EXPECT_NE(error.find(locked.string() + ": cannot create a temporary file"), std::string::npos) << error;
  EXPECT_NE(error.find("Permission denied"), std::string::npos) << error;
  fs::permissions(folder.path / "locked", fs::perms::owner_all);
}

// The one check of a folder named on a command line (the sandbox's --data and --screenshot, the
// lab's --data and --dump): a folder, a link to one, or the OS's reason it is not one.
TEST(FolderProblem, AFolderOrTheOsReason) {
  const TempFolder folder;
  writeFile(folder.path / "plain", "x");
  fs::create_directory(folder.path / "inner");
  fs::create_directory_symlink(folder.path / "inner", folder.path / "link");
  EXPECT_EQ(fileio::folderProblem(folder.path / "inner"), "");
  EXPECT_EQ(fileio::folderProblem(folder.path / "link"), "");
  EXPECT_EQ(fileio::folderProblem(folder.path / "plain"), "Not a directory");
  EXPECT_EQ(fileio::folderProblem(folder.path / "plain" / "below"), "Not a directory");
  EXPECT_EQ(fileio::folderProblem(folder.path / "missing"), "No such file or directory");
  fs::create_directory(folder.path / "locked");
  fs::permissions(folder.path, fs::perms::owner_all | fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(folder.path / "locked", fs::perms::none);  // no one but root may look inside
  EXPECT_EQ(testing_app::runAsNobody([&] { return fileio::folderProblem(folder.path / "locked" / "in"); }),
            "Permission denied");
  fs::permissions(folder.path / "locked", fs::perms::owner_all);  // for the folder to be removed
}

}  // namespace
