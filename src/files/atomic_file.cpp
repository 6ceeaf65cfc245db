#include "chasles/files/atomic_file.h"

#include "chasles/files/output_set.h"

namespace chasles {

void WriteFileAtomically(const std::string& path, std::string_view content) {
  OutputSet set;
  set.Add(path, std::string(content));
  set.Commit();
}

}  // namespace chasles
