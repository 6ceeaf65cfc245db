// chasles: the command-line program. Thin by design: parse -> load scene -> compute -> report
// (apps/chasles/program.cpp holds the parser and the exit-code promise).

#include "program.h"

int main(int argc, char** argv) {
  return chasles::cli::Main(argc, argv);
}
