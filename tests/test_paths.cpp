#include "test_paths.h"

namespace chasles::test {

const char* SourceDir() {
  return CHASLES_SOURCE_DIR;
}

const char* CliPath() {
  return CHASLES_CLI;
}

}  // namespace chasles::test
