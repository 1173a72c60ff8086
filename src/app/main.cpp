#include <cstdio>
int main() { std::fprintf(stderr, "starnt: skeleton\n"); return 1; }
