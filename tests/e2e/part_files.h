// Counts the temporary files a save through io_surfel's FileReplacement would leave beside a
// target: `name`.XXXXXX.part in the target's folder.
#ifndef GAUSSPHERE_TESTS_E2E_PART_FILES_H
#define GAUSSPHERE_TESTS_E2E_PART_FILES_H

#include <dirent.h>

#include <string>

inline int partFilesBeside(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  DIR* dir = ::opendir(folder.c_str());
  if (dir == nullptr) return 0;
  int count = 0;
  for (const dirent* entry = ::readdir(dir); entry != nullptr; entry = ::readdir(dir)) {
    const std::string file = entry->d_name;
    count += file.size() > name.size() + 5 && file.compare(0, name.size() + 1, name + ".") == 0 &&
             file.compare(file.size() - 5, 5, ".part") == 0;
  }
  ::closedir(dir);
  return count;
}

#endif
