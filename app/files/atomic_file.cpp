// Atomic file replacement with write + fsync + rename + directory fsync (see atomic_file.h).
#include "files/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string>

namespace sas::kiosk {
namespace {

bool Fail(std::string* error, const std::string& what, int err) {
  if (error) *error = what + ": " + std::strerror(err);
  return false;
}

}  // namespace

bool AtomicWriteFile(const std::string& path, const std::string& contents, std::string* error,
                     Durability durability) {
  const bool synced = durability == Durability::kSynced;
  const std::filesystem::path target(path);
  const std::filesystem::path directory =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  std::string temp = (directory / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = mkstemp(temp.data());
  if (fd < 0) return Fail(error, "cannot create a temporary file next to " + path, errno);
  const auto abandon = [&](const std::string& what, int err) {
    close(fd);
    unlink(temp.c_str());
    return Fail(error, what, err);
  };
  const char* data = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t written = write(fd, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      return abandon("writing " + path, errno);
    }
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  // mkstemp creates 0600; the files we keep are readable by staff tools.
  if (fchmod(fd, 0644) != 0) return abandon("setting permissions of " + path, errno);
  if (synced && fsync(fd) != 0) return abandon("flushing " + path + " to disk", errno);
  if (close(fd) != 0) {
    const int err = errno;
    unlink(temp.c_str());
    return Fail(error, "closing " + path, err);
  }
  if (rename(temp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    unlink(temp.c_str());
    return Fail(error, "replacing " + path, err);
  }
  if (!synced) return true;
  // Make the rename itself durable.
  const int dir_fd = open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    fsync(dir_fd);
    close(dir_fd);
  }
  return true;
}

void RemoveStaleTemporaries(const std::string& path) {
  const std::filesystem::path target(path);
  const std::filesystem::path directory =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  const std::string prefix = "." + target.filename().string() + ".";
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    const std::string name = entry.path().filename().string();
    // mkstemp's suffix is exactly six characters.
    if (name.size() == prefix.size() + 6 && name.rfind(prefix, 0) == 0) {
      std::filesystem::remove(entry.path(), error);
    }
  }
}

std::string AsidePath(const std::string& path) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &local);
  std::string aside = path + ".damaged-" + stamp;
  struct stat info {};
  for (int n = 2; stat(aside.c_str(), &info) == 0; ++n) {
    aside = path + ".damaged-" + stamp + "-" + std::to_string(n);
  }
  return aside;
}

}  // namespace sas::kiosk
