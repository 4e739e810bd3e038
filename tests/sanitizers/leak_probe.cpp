// Sanitizer build only (tests/CMakeLists.txt): proves the leak check is live and that
// tests/sanitizers/lsan.supp hides none of glcollide's own leaks. It leaks a Scene built by the
// scene library; ctest passes only if LeakSanitizer reports it.
#include <glcollide/scene.hpp>

namespace {
glcollide::Scene* volatile g_sink = nullptr;
}

int main() {
    g_sink = new glcollide::Scene(glcollide::defaultScene());
    g_sink = nullptr; // the only pointer is gone: a leak
    return 0;
}
