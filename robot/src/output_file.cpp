// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>

namespace colortrack {

namespace {

// strerror's text without its static buffer: output files are opened from several threads.
std::string errnoText(int error) {
  return std::generic_category().message(error);
}

// Letters and digits as in the C locale, whatever the process's locale is.
bool asciiAlpha(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool asciiAlnum(char c) {
  return asciiAlpha(c) || (c >= '0' && c <= '9');
}

}  // namespace

std::string fileKindName(mode_t kind) {
  switch (kind) {
    case S_IFREG:
      return "regular file";
    case S_IFCHR:
      return "character device";
    case S_IFIFO:
      return "FIFO";
    case S_IFSOCK:
      return "socket";
    case S_IFBLK:
      return "block device";
    case S_IFDIR:
      return "directory";
    default:
      return "file";
  }
}

int openOutputFile(const std::string &path, int extraFlags, mode_t &kind, std::string &why) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC | extraFlags, 0644);
  if (fd < 0) {
    // POSIX: a non-blocking open of a FIFO for writing fails with ENXIO while nobody reads it (a socket
    // file gives the same).
    why = errno == ENXIO ? "no process has it open for reading (a FIFO without a reader, or a socket)"
                         : errnoText(errno);
    return -1;
  }
  struct stat st;
  if (fstat(fd, &st) != 0) {
    why = errnoText(errno);
    ::close(fd);
    return -1;
  }
  kind = st.st_mode & S_IFMT;
  if (kind != S_IFREG && kind != S_IFCHR && kind != S_IFIFO) {
    why = "it is a " + fileKindName(kind) + ", not a regular file, character device or FIFO";
    ::close(fd);
    return -1;
  }
  return fd;
}

bool looksLikeUrl(const std::string &location) {
  const std::size_t colon = location.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  if (!asciiAlpha(location[0])) return false;
  for (std::size_t i = 1; i < colon; ++i) {
    const char c = location[i];
    if (!asciiAlnum(c) && c != '+' && c != '-' && c != '.') return false;
  }
  return true;
}

Status checkOutputPath(const std::string &path) {
  if (path.empty()) return Status::failure("it is empty");
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) {
    const mode_t kind = st.st_mode & S_IFMT;
    if (kind == S_IFREG || kind == S_IFCHR || kind == S_IFIFO) return {};
    return Status::failure("it is a " + fileKindName(kind) +
                           ", not a regular file, character device or FIFO");
  }
  if (errno != ENOENT) return Status::failure(errnoText(errno));
  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code error;
  if (std::filesystem::is_directory(folder, error)) return {};
  return Status::failure("its folder '" + folder.string() + "' does not exist");
}

}  // namespace colortrack
