// Saving a file so that a failed or interrupted save never destroys what was there: the data
// goes to a new temporary file beside the target, renamed over it once complete. The .surfel
// writer and gsresample's PLY output use it. POSIX, no Qt, no vcg.
#ifndef GAUSSPHERE_IO_SURFEL_FILE_REPLACEMENT_H
#define GAUSSPHERE_IO_SURFEL_FILE_REPLACEMENT_H

#include <functional>
#include <ostream>
#include <string>

namespace surfel_io {

class FileReplacement {
 public:
  FileReplacement() = default;
  FileReplacement(const FileReplacement&) = delete;
  FileReplacement& operator=(const FileReplacement&) = delete;
  // Removes the temporary file unless commit() succeeded.
  ~FileReplacement();

  // Prepares the save of `path`, so that an unwritable path fails here, before the work that
  // produces the data. The temporary file is `path`.XXXXXX.part in the target's folder, with a
  // fresh random XXXXXX, created exclusively: it never reuses, truncates or follows an existing
  // file or link. A symbolic link at `path` is resolved: the file it names is replaced and the
  // link kept. An existing `path` that is not a regular file (a device such as /dev/null, a
  // FIFO) is written in place; a folder is refused. On failure, `error` names the path and the
  // system's reason.
  bool open(const std::string& path, std::string& error);
  // Where to write the data: the temporary file, or the target itself when written in place.
  const std::string& writePath() const { return writePath_; }
  // Renames the temporary file over the target; an existing target's permission bits carry
  // over. Nothing to do when written in place.
  bool commit(std::string& error);
  // Writes the data through `writeData` to writePath(), then commits. On failure, `error` is
  // writeData's reason, else "cannot write '<path>': <the system's reason>".
  bool write(const std::function<bool(std::ostream&, std::string&)>& writeData, std::string& error);

 private:
  std::string path_, target_, writePath_;
  bool inPlace_ = false, pending_ = false;
};

}  // namespace surfel_io

#endif
