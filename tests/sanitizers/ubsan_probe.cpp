// Sanitizer build only (tests/CMakeLists.txt): proves UndefinedBehaviorSanitizer is live and stops
// the program (no recovery): a signed overflow must be reported as a runtime error.
#include <climits>
#include <cstdio>

int main(int argc, char**) {
    int x = INT_MAX - 1;
    x += argc + 1; // INT_MAX - 1 + 2: overflows
    std::printf("%d\n", x);
    return 0;
}
