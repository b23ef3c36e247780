#include "file_replacement.h"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "printable_text.h"

namespace surfel_io {

namespace {

bool fail(std::string& error, const std::string& path, const std::string& reason) {
  error = printableText("cannot write " + quotedPath(path) + ": " + reason, 200);
  return false;
}

// A name for the temporary file: the target's, cut so that the suffix fits a file name.
std::string temporaryName(const std::string& target, unsigned random) {
  const std::size_t slash = target.rfind('/');
  const std::size_t nameStart = slash == std::string::npos ? 0 : slash + 1;
  const std::size_t kMaxKeptName = 200;  // NAME_MAX is 255 on Linux; the suffix takes 12
  const std::string name = target.substr(nameStart, kMaxKeptName);
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, ".%06x.part", random & 0xffffffu);
  return target.substr(0, nameStart) + name + suffix;
}

// The file a symbolic link at `path` names, followed to its end; `path` itself otherwise.
std::string resolvedTarget(const std::string& path) {
  struct stat link;
  if (::lstat(path.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) return path;
  char* resolved = ::realpath(path.c_str(), nullptr);
  if (resolved == nullptr) return path;  // a dangling link: replaced like a missing file
  std::string target(resolved);
  std::free(resolved);
  return target;
}

}  // namespace

FileReplacement::~FileReplacement() {
  if (pending_) std::remove(writePath_.c_str());
}

bool FileReplacement::open(const std::string& path, std::string& error) {
  if (path.empty()) return fail(error, path, "the path is empty");
  path_ = path;
  target_ = resolvedTarget(path);
  struct stat existing;
  const bool exists = ::stat(target_.c_str(), &existing) == 0;
  if (exists && S_ISDIR(existing.st_mode)) return fail(error, path, "it is a folder");
  if (exists && !S_ISREG(existing.st_mode)) {
    inPlace_ = true;
    writePath_ = target_;
    return true;
  }
  std::random_device seed;
  std::mt19937 random(seed());
  for (int attempt = 0; attempt < 100; ++attempt) {
    writePath_ = temporaryName(target_, unsigned(random()));
    const int fd = ::open(writePath_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      if (exists) (void)::fchmod(fd, existing.st_mode & 07777);
      ::close(fd);
      pending_ = true;
      return true;
    }
    if (errno != EEXIST) return fail(error, path, std::strerror(errno));
  }
  return fail(error, path, "no free temporary name beside it");
}

bool FileReplacement::commit(std::string& error) {
  if (inPlace_) return true;
  if (!pending_) return fail(error, target_, "nothing was prepared");
  if (std::rename(writePath_.c_str(), target_.c_str()) != 0) return fail(error, target_, std::strerror(errno));
  pending_ = false;
  return true;
}

bool FileReplacement::write(const std::function<bool(std::ostream&, std::string&)>& writeData, std::string& error) {
  std::ofstream out(writePath_, std::ios::binary | std::ios::trunc);
  if (!out) return fail(error, path_, std::strerror(errno));
  error.clear();
  if (!writeData(out, error)) {
    if (error.empty()) fail(error, path_, std::strerror(errno));
    return false;
  }
  out.close();
  if (!out) return fail(error, path_, std::strerror(errno));
  return commit(error);
}

}  // namespace surfel_io
