// motionstyle-cli: command dispatch only; every command's work is done by core.
#include <iostream>

int main() {
  std::cout << "motionstyle-cli\n";
  return 0;
}
