// glcollide view in a build configured without GLFW or Dear ImGui (src/CMakeLists.txt).
#include "app/commands.hpp"

#include <glcollide/error.hpp>

namespace glcollide::app {

int viewCommand(const ViewOptions&) {
    throw Error(
        "view is not in this build: it needs GLFW and Dear ImGui (Debian: libglfw3-dev, libimgui-dev; "
        "scripts/install-deps.sh installs them), found when CMake configures");
}

} // namespace glcollide::app
