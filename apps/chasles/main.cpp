#include <cstdio>
int main() {
  std::puts("chasles: under construction");
  return 0;
}
