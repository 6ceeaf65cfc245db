#include "chasles/io/atomic_file.h"

#include "chasles/io/output_set.h"

namespace chasles {

void WriteFileAtomically(const std::string& path, std::string_view content) {
  OutputSet set;
  set.Add(path, std::string(content));
  set.Commit();
}

}  // namespace chasles
