// The sculpt executable: runs .bsp scripts or an interactive session.
#include <cstring>
#include <iostream>

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--version") == 0) {
      std::cout << "sculpt " << SCULPT_VERSION << "\n";
      return 0;
    }
    if (std::strcmp(argv[i], "--help") == 0) {
      std::cout << "usage: sculpt [--help] [--version] [FILE.bsp ...]\n";
      return 0;
    }
  }
  std::cerr << "sculpt: the language is not built yet; try --help\n";
  return 2;
}
