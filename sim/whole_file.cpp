#include "sim/whole_file.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace polysim::sim {

void writeWholeFile(const std::string& path, const std::string& what, const std::function<void(std::ostream&)>& write) {
  const std::string partial = path + ".partial";
  std::ofstream file(partial);
  if (!file) throw std::runtime_error(path + ": cannot write " + what);
  try {
    write(file);
    if (!file.flush()) throw std::runtime_error(path + ": writing " + what + " failed");
    file.close();
    if (std::rename(partial.c_str(), path.c_str()) != 0) throw std::runtime_error(path + ": cannot write " + what);
  } catch (...) {
    std::remove(partial.c_str());
    throw;
  }
}

}  // namespace polysim::sim
